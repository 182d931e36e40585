// The contact-law registry.  To add a law: write law_<name>.h with its
// History, normal_force, shear_force, stored_energy and stiffness functions
// and its closed forms, then add one row below.  Nothing else changes: decks
// select a law by this keyword and `demvv defaults` lists the rows.
#include "contact_model.h"

namespace dem
{
namespace
{
template <class Law>
std::unique_ptr<ContactModel> make(const LawParameters & /*p*/)
{
  return std::make_unique<LawModel<Law>>(Law{});
}

const std::vector<LawEntry> table = {
  {LinearLaw::keyword, &make<LinearLaw>,
   "linear springs with per-ball stiffnesses in series (thesis eq. 3.2-3.4, 3.17-3.18)"},
};
} // namespace

const std::vector<LawEntry> &law_registry() { return table; }

std::unique_ptr<ContactModel> make_contact_model(std::string_view keyword, const LawParameters &p)
{
  for (const LawEntry &e : table)
    if (e.keyword == keyword)
      return e.make(p);
  return nullptr;
}
} // namespace dem
