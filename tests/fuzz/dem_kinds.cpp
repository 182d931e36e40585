// The fuzz targets' table of deck kinds: the DEM kinds of
// verify/kinds/deck_kinds.cpp (scene, prepare, uniaxial), row for row.  The
// continuum kinds are left out: their parse lives beside their runs, which
// would bring the whole continuum companion (deal.II's solvers, MPI) into
// the fuzz build; the deck reader they share is fuzzed through these three.
#include "verify/kinds/prepare.h"
#include "verify/kinds/scene.h"
#include "verify/kinds/uniaxial.h"

namespace verify
{
const std::vector<DeckKind> &deck_kinds()
{
  static const std::vector<DeckKind> kinds = {
    {"scene", "explicit particles, walls, bonds and prescribed motions", &declare_scene,
     [](const Deck &d) { parse_scene(d); }, [](const Deck &d, const RunOptions &o) { return run_scene(d, o).status; }, false, true},
    {"prepare", "numerical sample preparation", &declare_prepare, [](const Deck &d) { parse_prepare(d); },
     [](const Deck &d, const RunOptions &o) { return run_prepare(d, o).status; }},
    {"uniaxial", "constant-strain-rate compression of a bonded cylinder between platens", &declare_uniaxial,
     [](const Deck &d) { parse_uniaxial(d); },
     [](const Deck &d, const RunOptions &o) { return run_uniaxial(d, o).status; }, false, true},
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
