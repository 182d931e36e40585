// The force passes of the Burger's and modified Burger's laws (law_models.h).
#include "dem/law_models.h"

#include <stdexcept>
#include <string>

namespace dem
{
namespace
{
template <class Law>
std::unique_ptr<ContactModel> make_burgers(const LawParameters &p)
{
  const BurgersContactConstants k = Law::constants_from(p);
  if (!k.valid())
    throw std::invalid_argument(std::string(Law::keyword) + ": every Burger's constant must be positive and finite");
  return std::make_unique<LawModel<Law>>(Law{k});
}
} // namespace

std::unique_ptr<ContactModel> make_burgers_model(const LawParameters &p) { return make_burgers<BurgersLaw>(p); }

std::unique_ptr<ContactModel> make_modified_burgers_model(const LawParameters &p)
{
  return make_burgers<ModifiedBurgersLaw>(p);
}
} // namespace dem
