#include "app/kinds/continuum_material.h"

#include "continuum/homogenisation.h"

#include <fstream>
#include <limits>

namespace demvv
{
namespace
{

void declare_poisson(DeckSchema &s, double value, const std::string &help)
{
  s.real("poisson ratio", value, -1, 0.5, "-", help + " (0.5 is incompressible: the bulk modulus is infinite).",
         Interval::open);
}

continuum::BurgersChain read_contact_chain(const Deck &deck)
{
  return {deck.real("material/contact/maxwell stiffness"), deck.real("material/contact/maxwell viscosity"),
          deck.real("material/contact/kelvin stiffness"), deck.real("material/contact/kelvin viscosity")};
}

/// E and nu from a summary.json of an elastic run, or the deck's numbers.
void measured_elasticity(const Deck &deck, double &young, double &poisson, nlohmann::json &source)
{
  const std::string key = "material/calibrated/summary file";
  if (deck.text(key).empty())
  {
    young = deck.real("material/calibrated/young modulus");
    poisson = deck.real("material/calibrated/poisson ratio");
    source = "deck";
    return;
  }
  const std::string path = deck.file(key);
  std::ifstream in(path);
  nlohmann::json summary;
  try
  {
    in >> summary;
  }
  catch (const nlohmann::json::exception &)
  {
    deck.fail(key, "expected a readable summary.json (cannot read or parse " + path + ")");
  }
  for (const char *field : {"initial_modulus_pa", "poisson_ratio"})
    if (!summary.contains(field) || !summary[field].is_number())
      deck.fail(key,
                std::string("expected a summary.json with a number '") + field + "' (from a completed elastic run)");
  young = summary["initial_modulus_pa"].get<double>();
  poisson = summary["poisson_ratio"].get<double>();
  if (!(young > 0) || !(poisson > -1 && poisson < 0.5))
    deck.fail(key, "expected initial_modulus_pa > 0 and poisson_ratio in (-1, 0.5) in " + path + " (found " +
                     std::to_string(young) + " Pa, " + std::to_string(poisson) + ")");
  source = path;
}

nlohmann::json chain_json(const continuum::BurgersChain &c, const std::string &spring, const std::string &dashpot)
{
  return {{"maxwell_spring_" + spring, c.maxwell_spring},
          {"maxwell_dashpot_" + dashpot, c.maxwell_dashpot},
          {"kelvin_spring_" + spring, c.kelvin_spring},
          {"kelvin_dashpot_" + dashpot, c.kelvin_dashpot}};
}
} // namespace

void declare_continuum_material(DeckSchema &s)
{
  s.enter("material");
  s.choice("model", "same shape", {"same shape", "deviatoric"},
           "Volumetric response of the Burger's solid: 'same shape' (bulk chain = K/G x shear chain, constant "
           "Poisson's ratio; the uniaxial chain is the Young chain as typed) or 'deviatoric' (Burger's in shear, "
           "elastic bulk modulus E0 / (3 (1 - 2 nu))).  With 'deviatoric' the uniaxial response is NOT the typed "
           "Young-type chain: only E0 carries over, and the Maxwell viscosity, Kelvin modulus and Kelvin viscosity "
           "act 3 / (2 (1 + nu)) times as typed (1.15 at nu = 0.3); summary.json gives the chain that results "
           "under material/moduli/uniaxial_chain, which is the one to compare with a DEM bulk curve.");
  s.choice("source", "direct", {"direct", "affine", "calibrated"},
           "Where the moduli come from: 'direct' (subsection direct), 'affine' (contact constants and an affine "
           "packing, subsections contact and affine), 'calibrated' (contact constants and an elastic run's E and "
           "nu, subsections contact and calibrated).");
  s.enter("direct");
  s.real("young modulus", 1e9, 0, inf, "Pa", "Instantaneous Young's modulus E0 (Maxwell spring).",
         Interval::open_below);
  declare_poisson(s, 0.3, "Instantaneous Poisson's ratio nu.");
  s.real("maxwell viscosity", 2e9, 0, inf, "Pa s", "Young-type Maxwell viscosity eta_inf (shear: / 2(1 + nu)).",
         Interval::open_below);
  s.real("kelvin modulus", 5e8, 0, inf, "Pa", "Young-type Kelvin modulus E1.", Interval::open_below);
  s.real("kelvin viscosity", 5e8, 0, inf, "Pa s", "Young-type Kelvin viscosity eta1.", Interval::open_below);
  s.leave();
  s.enter("contact");
  s.real("maxwell stiffness", 5.5e6, 0, inf, "N/m", "Normal Maxwell stiffness K_m of a contact (thesis Table 7.3).",
         Interval::open_below);
  s.real("maxwell viscosity", 6e4, 0, inf, "N s/m", "Normal Maxwell viscosity C_m (Table 7.3: 0.06 MN s/m).",
         Interval::open_below);
  s.real("kelvin stiffness", 5.5e6, 0, inf, "N/m", "Normal Kelvin stiffness K_k (Table 7.3).", Interval::open_below);
  s.real("kelvin viscosity", 6e4, 0, inf, "N s/m", "Normal Kelvin viscosity C_k (Table 7.3).", Interval::open_below);
  s.real("shear ratio", 1, 0, inf, "-",
         "r: every shear constant is r times the normal one (the same-shape condition; Table 7.3 has r = 1).");
  s.leave();
  s.enter("affine");
  s.real("coordination number", 5.8, 0, inf, "-", "Z of the packing (thesis ch. 5: 5.8).", Interval::open_below);
  s.real("solid fraction", 0.635, 0, 1, "-", "phi of the packing (thesis ch. 5: 0.635).", Interval::open_below);
  s.real("particle radius", 0.885e-3, 0, inf, "m", "Radius R of the (monodisperse) particles.", Interval::open_below);
  s.leave();
  s.enter("calibrated");
  s.text("summary file", "",
         "summary.json of an elastic run (e.g. a uniaxial deck) whose initial_modulus_pa and poisson_ratio are "
         "the measured E and nu, relative to the deck; empty: use the two numbers below.");
  s.real("young modulus", 1e8, 0, inf, "Pa", "Measured Young's modulus E (used without a summary file).",
         Interval::open_below);
  declare_poisson(s, 0.2, "Measured Poisson's ratio (used without a summary file).");
  s.real("reference normal stiffness", 6e6, 0, inf, "N/m",
         "Normal contact stiffness k_n of the elastic run (the pair value; two balls of 1.2e7 N/m give 6e6).",
         Interval::open_below);
  s.leave();
  s.leave();
}

ContinuumMaterial parse_continuum_material(const Deck &deck)
{
  ContinuumMaterial m;
  const std::string source = deck.text("material/source");
  const std::string model = deck.text("material/model");
  const bool same_shape = model == "same shape";
  if (source != "direct" && !same_shape)
    deck.fail("material/model", "expected 'same shape' when material/source is '" + source +
                                  "' (contact constants map to one Burger's shape in shear and bulk)");
  if (source == "direct")
  {
    m.solid.young = {deck.real("material/direct/young modulus"), deck.real("material/direct/maxwell viscosity"),
                     deck.real("material/direct/kelvin modulus"), deck.real("material/direct/kelvin viscosity")};
    m.solid.poisson = deck.real("material/direct/poisson ratio");
    m.description = {{"source", "direct"}};
  }
  else if (source == "affine")
  {
    const continuum::PackingGeometry packing{deck.real("material/affine/coordination number"),
                                             deck.real("material/affine/solid fraction"),
                                             deck.real("material/affine/particle radius")};
    const double r = deck.real("material/contact/shear ratio");
    m.solid = continuum::affine_burgers_solid(read_contact_chain(deck), r, packing);
    m.description = {{"source", "affine (Voigt) homogenisation, check V18"},
                     {"coordination_number", packing.coordination},
                     {"solid_fraction", packing.solid_fraction},
                     {"particle_radius_m", packing.radius},
                     {"shear_ratio", r},
                     {"young_per_normal_stiffness_per_m", continuum::affine_moduli(packing, 1, r).young}};
  }
  else
  {
    double young = 0, poisson = 0;
    nlohmann::json measured_from;
    measured_elasticity(deck, young, poisson, measured_from);
    const double kn = deck.real("material/calibrated/reference normal stiffness");
    m.solid = continuum::calibrated_burgers_solid(read_contact_chain(deck), young, poisson, kn);
    m.description = {{"source", "calibrated from an elastic run, check V19"},
                     {"measured_from", measured_from},
                     {"measured_young_modulus_pa", young},
                     {"measured_poisson_ratio", poisson},
                     {"reference_normal_stiffness_n_per_m", kn},
                     {"young_per_normal_stiffness_per_m", young / kn}};
  }
  m.solid.bulk = same_shape ? continuum::BulkResponse::same_shape : continuum::BulkResponse::elastic;
  m.description["model"] = model;
  m.description["moduli"] = describe_solid(m.solid);
  return m;
}

nlohmann::json describe_solid(const continuum::BurgersSolid &solid)
{
  nlohmann::json j = {{"young_chain", chain_json(solid.young, "pa", "pa_s")},
                      {"shear_chain", chain_json(solid.shear(), "pa", "pa_s")},
                      {"uniaxial_chain", chain_json(solid.uniaxial(), "pa", "pa_s")},
                      {"poisson_ratio", solid.poisson},
                      {"bulk_modulus_pa", solid.bulk_modulus()}};
  if (solid.bulk == continuum::BulkResponse::same_shape)
  {
    j["bulk_chain"] = chain_json(solid.bulk_chain(), "pa", "pa_s");
    j["uniaxial_chain_note"] = "same shape: the uniaxial chain is the Young chain";
  }
  else
    j["uniaxial_chain_note"] = "deviatoric: the uniaxial chain is E0 with 3 / (2 (1 + nu)) times the Young-type "
                               "viscosities and Kelvin modulus (the shear chain x 3); the typed Young-type chain is "
                               "not the uniaxial response";
  return j;
}
} // namespace demvv
