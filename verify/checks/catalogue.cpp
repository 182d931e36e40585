// The catalogue text.  The definitions below are the project's own wording
// of the V&V categories of thesis §2.5 and of the tolerance classes every
// metric is given; the entries are read from the registry row by row.
#include "verify/checks/catalogue.h"

#include "build_info.h"

#include <map>
#include <sstream>

namespace demvv
{
std::string_view category_definition(Category c)
{
  switch (c)
  {
  case Category::code_verification:
    return "Is the equation solved right? The code's result is compared with an exact solution of the same "
           "mathematical model: a closed form, an identity, an eigen-solve, or the order at which the error falls "
           "under refinement. A difference beyond the tolerance is a bug, not a modelling choice.";
  case Category::solution_verification:
    return "How accurate is this particular numerical solution? Where no exact solution exists, the "
           "discretisation error of a result is estimated from the result itself, by refining the step or the "
           "mesh (observed order, Richardson extrapolation, Roache's grid convergence index).";
  case Category::model_comparison:
    return "Do two models built from the same inputs agree where theory says they must? demvv's DEM bulk response "
           "is compared with the continuum built from the same contacts, whose equivalence (the correspondence "
           "principle) is exact only under conditions a DEM run meets approximately (quasi-static loading; every "
           "contact, the platens' included, of one viscoelastic shape; no slip, no breakage). Neither side is exact: "
           "the tolerance is argued from the differences the two models are known to have, and a difference "
           "beyond it is a bug in one of them or an assumption that does not hold, which the check names.";
  case Category::calibration:
    return "Which parameters make the model reproduce given data? Parameters are fitted to targets, so agreement "
           "with those targets is by construction: it shows the fit worked, not that the model predicts.";
  case Category::validation:
    return "Is it the right equation? Predictions are compared with experiments (or the thesis's measured laws) "
           "at conditions never used in calibration, with the numerical and the experimental uncertainty stated; "
           "whatever is built into the model by construction is named as such.";
  }
  return "?";
}

std::string_view tolerance_class_limit(ToleranceClass t)
{
  switch (t)
  {
  case ToleranceClass::A:
    return "floating-point round-off only";
  case ToleranceClass::B:
    return "the truncation error of a time step or a mesh, O(dt^p) or O(h^p)";
  case ToleranceClass::C:
    return "an event (contact onset, bond break, slip) that falls inside a step";
  case ToleranceClass::D:
    return "the scatter between random samples";
  }
  return "?";
}

std::string_view tolerance_class_rule(ToleranceClass t)
{
  switch (t)
  {
  case ToleranceClass::A:
    return "relative error at most 1e-12, or an argued count of round-off units (a solver's residual times a "
           "condition number, n steps of rounding)";
  case ToleranceClass::B:
    return "error at most a stated bound at the production step or mesh, and an observed order within 0.1 of the "
           "theoretical one at each of the two finest halvings (a check may ask less than 0.1). Two variants, each "
           "named in its metric's reason: where theory gives only a range of orders (a singular corner) the "
           "observed order must lie in that range, and where it gives only the slowest decay (a quadrature of a "
           "piecewise-smooth integrand) the errors must fall at least that fast";
  case ToleranceClass::C:
    return "error at most one step's worth of the measured quantity (v dt, dt / t_c, K v dt); no order claimed";
  case ToleranceClass::D:
    return "mean and 95 % confidence interval over at least five seeds; never a verdict from a single run";
  }
  return "?";
}

std::string_view tolerance_class_reasoning(ToleranceClass t)
{
  switch (t)
  {
  case ToleranceClass::A:
    return "The quantity is an algebraic identity or a step the scheme takes exactly (a constant force under "
           "centred differences, a sum over a spherical design, a count of pairs or breaks). Nothing but rounding "
           "separates it from the reference, so any larger error is a defect; where rounding accumulates (many "
           "steps, an iterative solver, a cancelling difference) the allowance is argued from that mechanism.";
  case ToleranceClass::B:
    return "The reference solves the continuous problem and the code a discretised one, so they differ by a "
           "truncation error that is known only in its form. A single number could pass by luck, so the bound at "
           "the step actually used is paired with the observed order of the error, which exposes a wrong term "
           "that a loose bound would hide. Order is claimed only for smooth problems without events.";
  case ToleranceClass::C:
    return "A contact or a bond changes state between two steps but is detected at a step, so the measured "
           "instant or displacement is off by up to one step whatever the scheme's order; refining the step "
           "shrinks the error erratically with the event's phase inside the step, so only the one-step bound is "
           "asserted.";
  case ToleranceClass::D:
    return "A random packing is one draw of many: a single run's error mixes the model's error with the sample's "
           "luck. Only a statistic over several seeds, with its uncertainty, can be compared with a reference.";
  }
  return "?";
}

std::string verification_catalogue()
{
  const std::vector<Check> &checks = check_registry();
  std::ostringstream o;
  o << "# demvv verification catalogue\n\n"
    << "Generated from the check registry (`verify/checks/checks_registry.cpp`) by `demvv catalogue --out "
       "docs/verification_catalogue.md`; do not edit by hand. A test fails when this file and the registry "
       "disagree.\n\n"
    << "Every check states one requirement (\"demvv shall ...\"), the reference it is measured against, its "
       "V&V category and the tolerance classes of its metrics. The tolerances themselves, with the reason for "
       "each, are computed when the check runs (many depend on the step or mesh of the run) and appear in the "
       "report of `demvv verify`. A metric whose value or reference is missing or not finite fails: nothing "
       "passes by default.\n\n";

  o << "## Categories\n\n"
    << "The four kinds of evidence of thesis §2.5, and between them a fifth, model comparison (two models of "
       "one material held to an identity between them); each check belongs to one.\n\n";
  for (Category c : all_categories)
    o << "- **" << category_name(c) << "**: " << category_definition(c) << "\n";

  o << "\n## Tolerance classes\n\n"
    << "Each metric carries the class of what limits its accuracy; the class fixes how its tolerance is set.\n\n"
    << "| class | what limits accuracy | pass rule |\n|---|---|---|\n";
  const ToleranceClass classes[] = {ToleranceClass::A, ToleranceClass::B, ToleranceClass::C, ToleranceClass::D};
  for (ToleranceClass t : classes)
    o << "| " << tolerance_class_letter(t) << " " << tolerance_class_name(t) << " | " << tolerance_class_limit(t)
      << " | " << tolerance_class_rule(t) << " |\n";
  o << "\n";
  for (ToleranceClass t : classes)
    o << "- **" << tolerance_class_letter(t) << "** (" << tolerance_class_name(t)
      << "): " << tolerance_class_reasoning(t) << "\n";
  o << "\nA metric that only guards that a check exercised what it claims (some bonds broke, the peak grows with "
       "the velocity) takes the class of the run it is read from.\n";

  std::map<Category, int> per_category;
  std::map<char, int> per_class;
  for (const Check &c : checks)
  {
    ++per_category[c.category];
    for (ToleranceClass t : c.tolerance_classes)
      ++per_class[tolerance_class_letter(t)];
  }
  o << "\n## Checks\n\n" << checks.size() << " checks:";
  const char *separator = " ";
  for (const auto &[category, count] : per_category)
  {
    o << separator << count << " " << category_name(category);
    separator = ", ";
  }
  o << ". Checks with metrics of class";
  separator = " ";
  for (ToleranceClass t : classes)
  {
    o << separator << tolerance_class_letter(t) << ": " << per_class[tolerance_class_letter(t)];
    separator = ", ";
  }
  o << ".\n\n| id | title | family | category | tolerance classes |\n|---|---|---|---|---|\n";
  for (const Check &c : checks)
    o << "| " << c.id << " | " << c.title << " | " << c.family << " | " << category_name(c.category) << " | "
      << tolerance_class_list(c.tolerance_classes) << " |\n";
  for (const Check &c : checks)
    o << "\n### " << c.id << ": " << c.title << "\n\n"
      << "- Requirement: " << c.requirement << "\n"
      << "- Category: " << category_name(c.category) << "\n"
      << "- Reference: " << c.reference << "\n"
      << "- Tolerance classes of its metrics: " << tolerance_class_list(c.tolerance_classes) << "\n";
  return o.str();
}

std::string committed_catalogue_path()
{
  return std::string(build_info::source_dir) + "/docs/verification_catalogue.md";
}
} // namespace demvv
