// The deck-kind registry: one row per kind.  To add a kind, write its
// declare_* and run_* functions and add one row here and one in commands.cpp.
#include "verify/kinds/continuum_cylinder.h"
#include "verify/kinds/continuum_mms.h"
#include "verify/kinds/continuum_ode.h"
#include "verify/decks/deck.h"
#include "verify/kinds/prepare.h"
#include "verify/kinds/scene.h"
#include "verify/kinds/uniaxial.h"

namespace verify
{
const std::vector<DeckKind> &deck_kinds()
{
  static const std::vector<DeckKind> kinds = {
    {"scene", "explicit particles, walls, bonds and prescribed motions (two-ball tests, chains)", &declare_scene},
    {"prepare", "numerical sample preparation (thesis ch. 5): a dense random bonded packing saved to a sample file",
     &declare_prepare},
    {"uniaxial", "constant-strain-rate compression of a bonded cylinder between platens", &declare_uniaxial},
    {"burgers_ode", "one Burger's chain (contact or material point) under a prescribed history, SUNDIALS CVODE "
                    "beside its closed form", &declare_burgers_ode},
    {"cylinder", "viscoelastic continuum cylinder (deal.II) compressed between frictionless or bonded platens",
     &declare_cylinder},
    {"mms", "manufactured-solution convergence study of the continuum cylinder in space or time", &declare_mms},
  };
  return kinds;
}
} // namespace verify
