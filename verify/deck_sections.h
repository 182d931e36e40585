// Deck sections shared by several kinds: the contact law, the motion
// settings and the bonds.  Each section has a declare_* function (schema)
// and a read_* function (deck -> engine settings), side by side, so that a
// key is declared and read in one place.
#pragma once

#include "deck.h"

#include "bonds.h"
#include "contact_model.h"
#include "simulation.h"

#include <memory>

namespace verify
{
/// subsection "contact law": the keyword of a registered law.
void declare_contact_law(DeckSchema &s);
std::unique_ptr<dem::ContactModel> read_contact_law(const Deck &d);

/// subsection "motion": gravity, damping, time step, neighbour skin.
void declare_motion(DeckSchema &s, const std::string &default_gravity, double default_damping);
dem::SimulationSettings read_motion(const Deck &d);

/// subsection "bonds": how bonds are installed and their strengths.
/// `modes` lists the allowed values of "install" (first is the default).
void declare_bonds(DeckSchema &s, const std::vector<std::string> &modes);
dem::BondSettings read_bond_settings(const Deck &d);

/// subsection "balls": per-ball contact properties and density.
void declare_ball_properties(DeckSchema &s);
/// Fills density, kn, ks, friction of a ball from the deck.
void apply_ball_properties(const Deck &d, dem::BallSpec &b);

/// Per-wall contact properties (inside the current subsection).
void declare_wall_properties(DeckSchema &s, double kn, double ks, double friction);
dem::WallProps read_wall_properties(const Deck &d, const std::string &section);

/// "x, y, z" deck entry as a vector.
dem::Vec3 read_vec3(const Deck &d, const std::string &key);
} // namespace verify
