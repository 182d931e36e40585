// The linear law's force pass (law_models.h).
#include "dem/law_models.h"

namespace dem
{
std::unique_ptr<ContactModel> make_linear_model(const LawParameters & /*p*/)
{
  return std::make_unique<LawModel<LinearLaw>>(LinearLaw{});
}
} // namespace dem
