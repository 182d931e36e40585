// The contact-law registry.  To add a law: write law_<name>.h with its
// History (and its state_fields, load and store to a LawState slot), its
// deck_constants, normal_force, shear_force, stored_energy and stiffness
// functions and its closed forms, its model's maker in law_model_<name>.cpp
// (law_models.h), then add one row below.  Nothing else changes: decks
// select a law by this keyword and set its deck_constants (`demvv defaults`
// lists both), and sample files name the law's state columns after its
// state_fields.
#include "dem/law_models.h"

namespace dem
{
namespace
{
template <class Law>
std::vector<std::string_view> fields()
{
  return {Law::state_fields.begin(), Law::state_fields.end()};
}

const std::vector<LawEntry> table = {
  {LinearLaw::keyword, &make_linear_model,
   "linear springs with per-ball stiffnesses in series (thesis eq. 3.2-3.4, 3.17-3.18)", fields<LinearLaw>(),
   LinearLaw::deck_constants()},
  {BurgersLaw::keyword, &make_burgers_model,
   "Burger's element (Maxwell + Kelvin) in the normal and shear directions, Crank-Nicolson update "
   "(thesis §3.4.3, eq. 3.25-3.35); constants per contact, no series combination",
   fields<BurgersLaw>(), BurgersLaw::deck_constants()},
  {ModifiedBurgersLaw::keyword, &make_modified_burgers_model,
   "modified Burger's (thesis §7.2.2): elastic E_0^n in normal compression, Burger's in normal tension "
   "and in shear",
   fields<ModifiedBurgersLaw>(), ModifiedBurgersLaw::deck_constants()},
};
} // namespace

const std::vector<LawEntry> &law_registry() { return table; }

const LawEntry *find_law(std::string_view keyword)
{
  for (const LawEntry &e : table)
    if (e.keyword == keyword)
      return &e;
  return nullptr;
}

std::unique_ptr<ContactModel> make_contact_model(std::string_view keyword, const LawParameters &p)
{
  const LawEntry *e = find_law(keyword);
  return e ? e->make(p) : nullptr;
}
} // namespace dem
