// The deck-kind registry: one row per kind.  To add a kind, write its
// declare_* and run_* functions and add one row here and one in commands.cpp.
#include "continuum_cylinder.h"
#include "continuum_mms.h"
#include "continuum_ode.h"
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
    {"burgers_ode", "one Burger's chain (contact or material point) under a prescribed history, SUNDIALS CVODE "
                    "beside its closed form", &declare_burgers_ode},
    {"cylinder", "viscoelastic continuum cylinder (deal.II) compressed between frictionless or bonded platens",
     &declare_cylinder},
    {"mms", "manufactured-solution convergence study of the continuum cylinder in space or time", &declare_mms},
  };
  return kinds;
}
} // namespace verify
