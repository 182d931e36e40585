// The DEM rows of the table of deck kinds (deck_kinds.h).  To add a DEM
// kind, write its file in app/kinds/ (declare, a typed spec with its parse,
// run on the spec) and its figures in app/plot/run_figures.cpp, and add one row here.
#include "app/kinds/deck_kinds.h"
#include "app/kinds/prepare.h"
#include "app/kinds/scene.h"
#include "app/kinds/uniaxial.h"
#include "app/plot/run_figures.h"

namespace demvv
{
const DeckKinds &dem_deck_kinds()
{
  static const DeckKinds kinds = {
    {"scene", "explicit particles, walls, bonds and prescribed motions (two-ball tests, chains, boxes)", &declare_scene,
     [](const Deck &d)
     { return parsed_run(parse_scene(d), [](const auto &s, const RunOptions &o) { return run_scene(s, o); }); },
     &scene_run_figures, false, true},
    {"prepare", "numerical sample preparation (thesis ch. 5): a dense random bonded packing saved to a sample file",
     &declare_prepare,
     [](const Deck &d) {
       return parsed_run(parse_prepare_spec(d), [](const auto &s, const RunOptions &o) { return run_prepare(s, o); });
     },
     &prepare_run_figures},
    {"uniaxial", "compression of a bonded cylinder between platens: constant rate, creep, relaxation or cyclic",
     &declare_uniaxial,
     [](const Deck &d)
     { return parsed_run(parse_uniaxial(d), [](const auto &s, const RunOptions &o) { return run_uniaxial(s, o); }); },
     &uniaxial_run_figures, false, true},
  };
  return kinds;
}
} // namespace demvv
