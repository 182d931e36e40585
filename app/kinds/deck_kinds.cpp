// THE table of deck kinds (deck_kinds.h): the DEM rows of dem_kinds.cpp,
// then the continuum and micro-macro rows here.  To add a kind, write its
// file in app/kinds/ (declare, a typed spec with its parse, run on the
// spec) and its figures in app/plot/run_figures.cpp, and add one row here
// (or in dem_kinds.cpp for a DEM kind).
#include "app/kinds/deck_kinds.h"
#include "app/kinds/compare.h"
#include "app/kinds/continuum_cylinder.h"
#include "app/kinds/continuum_mms.h"
#include "app/kinds/continuum_ode.h"
#include "app/plot/run_figures.h"

namespace demvv
{
const DeckKinds &deck_kinds()
{
  static const DeckKinds kinds = []
  {
    DeckKinds all = dem_deck_kinds();
    const DeckKinds continuum = {
      {"burgers_ode",
       "one Burger's chain (contact or material point) under a prescribed history, SUNDIALS CVODE "
       "beside its closed form",
       &declare_burgers_ode,
       [](const Deck &d) {
         return parsed_run(parse_burgers_ode(d),
                           [](const auto &s, const RunOptions &o) { return run_burgers_ode(s, o); });
       },
       &burgers_ode_run_figures},
      {"cylinder", "viscoelastic continuum cylinder (deal.II) compressed between frictionless or bonded platens",
       &declare_cylinder,
       [](const Deck &d)
       { return parsed_run(parse_cylinder(d), [](const auto &s, const RunOptions &o) { return run_cylinder(s, o); }); },
       &cylinder_run_figures, true},
      {"compare", "DEM bulk beside the continuum cylinder built from the same contacts, same sample and history",
       &declare_compare,
       [](const Deck &d)
       { return parsed_run(parse_compare(d), [](const auto &s, const RunOptions &o) { return run_compare(s, o); }); },
       &compare_run_figures},
      {"mms", "manufactured-solution convergence study of the continuum cylinder in space or time", &declare_mms,
       [](const Deck &d)
       { return parsed_run(parse_mms(d), [](const auto &s, const RunOptions &o) { return run_mms_deck(s, o); }); },
       &mms_run_figures, true},
    };
    all.insert(all.end(), continuum.begin(), continuum.end());
    return all;
  }();
  return kinds;
}
} // namespace demvv
