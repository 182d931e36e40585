// Installing contact bonds (thesis §3.4.2, §5.3.3, §6.5, §7.4).
//
// Every touching ball pair (overlap U >= -tolerance, tolerance relative to
// the smaller radius so that exactly touching lattice spheres count) gets a
// PFC3D contact bond with normal strength phi_n and shear strength phi_s in
// newtons (eq. 6.1: phi = 4 sigma R^2).  Strengths may be Gaussian with a
// coefficient of variation (CoV 0, 25 %, 50 % in §6.5); a Gaussian draw can
// be negative, so draws below floor_fraction * mean are raised to that
// floor and counted, never hidden.  A chosen fraction of the bonds can then
// be removed at random to leave frictional contacts (§7.4).
//
// Random numbers come from GSL's MT19937 seeded by the deck, consumed in the
// table's pair order: the same sample and seed give the same bonds.
#pragma once

#include "dem/contacts.h"
#include "dem/particles.h"

#include <cstdint>

namespace dem
{
struct BondSettings
{
  double normal_strength = 0;    ///< N, mean phi_n
  double shear_strength = 0;     ///< N, mean phi_s
  double cov = 0;                ///< -, coefficient of variation of both strengths
  double floor_fraction = 0.01;  ///< -, lowest strength as a fraction of its mean
  double removed_fraction = 0;   ///< -, fraction of bonds removed after bonding
  double touch_tolerance = 1e-6; ///< -, gap allowed, relative to the smaller radius
  std::uint64_t seed = 1;
};

struct BondReport
{
  std::size_t bonded = 0;          ///< bonds installed and kept
  std::size_t removed = 0;         ///< bonds removed to leave frictional contacts
  std::size_t truncated_draws = 0; ///< strength draws raised to the floor
  double mean_normal_strength = 0; ///< N, of the kept bonds
  double mean_shear_strength = 0;  ///< N, of the kept bonds
};

/// Bonds every touching pair of the table (build the table first).
BondReport bond_touching_pairs(ContactTable &table, const ParticleStore &particles, const BondSettings &settings);

/// Multiplies the strengths of every intact bond (rate dependence, eq. 7.23).
void scale_bond_strengths(ContactTable &table, double factor);

/// Displacement criterion (appendix A): every intact bond breaks once its
/// centre distance exceeds the present one by delta_c [m].
void set_break_displacement(ContactTable &table, const ParticleStore &particles, double delta_c);

/// Bonds one pair with the given strengths, adding it to the table if needed.
void bond_pair(ContactTable &table, const ParticleStore &particles, Index i, Index j, double normal_strength,
               double shear_strength);
} // namespace dem
