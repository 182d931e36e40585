// THE table of deck kinds: one row per kind (keyword, one-line summary,
// schema, parse, run).  To add a kind, write its file in verify/kinds/
// (declare, a typed spec with its parse, run) and add one row here.
#include "verify/kinds/compare.h"
#include "verify/kinds/continuum_cylinder.h"
#include "verify/kinds/continuum_mms.h"
#include "verify/kinds/continuum_ode.h"
#include "verify/kinds/prepare.h"
#include "verify/kinds/scene.h"
#include "verify/kinds/uniaxial.h"

namespace verify
{
const std::vector<DeckKind> &deck_kinds()
{
  static const std::vector<DeckKind> kinds = {
    {"scene", "explicit particles, walls, bonds and prescribed motions (two-ball tests, chains, boxes)",
     &declare_scene, [](const Deck &d) { parse_scene(d); },
     [](const Deck &d, const RunOptions &o) { return run_scene(d, o).status; }, false, true},
    {"prepare", "numerical sample preparation (thesis ch. 5): a dense random bonded packing saved to a sample file",
     &declare_prepare, [](const Deck &d) { parse_prepare(d); },
     [](const Deck &d, const RunOptions &o) { return run_prepare(d, o).status; }},
    {"uniaxial", "compression of a bonded cylinder between platens: constant rate, creep, relaxation or cyclic",
     &declare_uniaxial,
     [](const Deck &d) { parse_uniaxial(d); },
     [](const Deck &d, const RunOptions &o) { return run_uniaxial(d, o).status; }, false, true},
    {"burgers_ode", "one Burger's chain (contact or material point) under a prescribed history, SUNDIALS CVODE "
                    "beside its closed form",
     &declare_burgers_ode, [](const Deck &d) { parse_burgers_ode(d); },
     [](const Deck &d, const RunOptions &o) { return run_burgers_ode(d, o).status; }},
    {"cylinder", "viscoelastic continuum cylinder (deal.II) compressed between frictionless or bonded platens",
     &declare_cylinder, [](const Deck &d) { parse_cylinder(d); },
     [](const Deck &d, const RunOptions &o) { return run_cylinder(d, o).status; }, true},
    {"compare", "DEM bulk beside the continuum cylinder built from the same contacts, same sample and history",
     &declare_compare, [](const Deck &d) { parse_compare(d); },
     [](const Deck &d, const RunOptions &o) { return run_compare(d, o).status; }},
    {"mms", "manufactured-solution convergence study of the continuum cylinder in space or time", &declare_mms,
     [](const Deck &d) { parse_mms(d); }, [](const Deck &d, const RunOptions &o) { return run_mms_deck(d, o).status; },
     true},
  };
  return kinds;
}

const DeckKind *find_deck_kind(std::string_view name)
{
  for (const DeckKind &k : deck_kinds())
    if (k.name == name)
      return &k;
  return nullptr;
}
} // namespace verify
