// The verification catalogue: what every check is measured against, as a
// document that lives in the repository (docs/verification_catalogue.md).
//
// The document is generated from the check registry, never written by hand,
// so it cannot drift from the checks that run: `demvv catalogue --out
// docs/verification_catalogue.md` writes it, and a test fails when the
// committed file differs from what the registry gives.  Besides one entry
// per check (id, title, requirement, category, reference, tolerance classes)
// it defines the four V&V categories (thesis §2.5) and the four tolerance
// classes, with the reasoning behind each class's pass rule.
//
// Tolerances themselves are computed when a check runs (many depend on the
// step or the mesh of that run), so the catalogue lists the classes a check
// declares in its registry row; the tests hold every metric a check returns
// to those declared classes.
#pragma once

#include "verify/checks/check.h"

#include <string>
#include <string_view>

namespace demvv
{
/// One paragraph: what a V&V category asks and what counts as evidence for it.
std::string_view category_definition(Category c);

/// One line: what limits the accuracy of a metric of this class.
std::string_view tolerance_class_limit(ToleranceClass t);
/// One line: how a tolerance of this class is set (the pass rule).
std::string_view tolerance_class_rule(ToleranceClass t);
/// One paragraph: why that rule follows from what limits the accuracy.
std::string_view tolerance_class_reasoning(ToleranceClass t);

/// The whole catalogue as Markdown, deterministic (no dates, no paths).
std::string verification_catalogue();

/// docs/verification_catalogue.md in the source tree this build was configured from.
std::string committed_catalogue_path();
} // namespace demvv
