// The force pass of each contact law, compiled in a file of its own
// (law_model_*.cpp), so that each law's pass gets the compiler settings
// measured fastest for it (dem/CMakeLists.txt); the registry
// (law_registry.cpp) makes models through these.
#pragma once

#include "dem/contact_model.h"

#include <memory>

namespace dem
{
/// The linear law's model (parameters unused: its constants are per ball).
std::unique_ptr<ContactModel> make_linear_model(const LawParameters &p);
/// The Burger's law's model from a deck's constants; throws
/// std::invalid_argument unless every constant is positive and finite.
std::unique_ptr<ContactModel> make_burgers_model(const LawParameters &p);
/// The modified Burger's law's model, likewise.
std::unique_ptr<ContactModel> make_modified_burgers_model(const LawParameters &p);
} // namespace dem
