// The deck-kind registry: one row per kind.  To add a kind, write its
// declare_* and run_* functions and add one row here and one in commands.cpp.
#include "deck.h"
#include "prepare.h"
#include "scene.h"
#include "uniaxial.h"

namespace verify
{
const std::vector<DeckKind> &deck_kinds()
{
  static const std::vector<DeckKind> kinds = {
    {"scene", "explicit particles, walls, bonds and prescribed motions (two-ball tests, chains)", &declare_scene},
    {"prepare", "numerical sample preparation (thesis ch. 5): a dense random bonded packing saved to a sample file",
     &declare_prepare},
    {"uniaxial", "constant-strain-rate compression of a bonded cylinder between platens", &declare_uniaxial},
  };
  return kinds;
}
} // namespace verify
