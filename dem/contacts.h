// ContactTable: every ball-ball pair the engine must look at, with history.
//
// The table holds the neighbour candidates plus every pair that is touching
// or bonded, sorted by (first, second).  Each entry carries its pair
// constants (ContactParams, fixed at creation), its bond and its history
// (ContactState).  The contact law's own history (LawState, contact.h) lives
// in a second array, parallel to the entries: structure of arrays, so that a
// law without such history (the linear law) never loads it in its contact
// pass.  When the neighbour list is rebuilt the table merges the new
// candidates with the old entries by one linear walk over two sorted lists,
// carrying both arrays: history survives rebuilds without hashing, a new
// pair starts with its law state at rest, and a bonded pair stays in the
// table however far its balls drift apart.
//
// The per-step results (force on the second ball, torques on both, the
// stability-bound contributions) live in a separate array of ContactLoad:
// the contact pass writes one entry per contact and the particle pass gathers
// them in a fixed order, so no two threads ever write the same particle.
#pragma once

#include "dem/contact.h"
#include "dem/neighbors.h"

#include <vector>

namespace dem
{
/// Stability-bound row terms of a contact while its arms are at most the
/// radii (any compressive contact), precomputed because they depend only on
/// constants of the pair (stability.h); tension recomputes them.
struct StabilityTerms
{
  double first = 0;  ///< 1/s^2
  double second = 0; ///< 1/s^2
};

struct Contact
{
  Index first = 0;
  Index second = 0;
  ContactParams params;
  ContactBond bond;
  ContactState state;
  StabilityTerms stability;
};

/// What one contact contributes to its two balls at this step.  Torques
/// follow from the lever: the contact point lies at arm * n from the first
/// centre and -arm * n from the second, so T_first = -arm_first (n x F_s)
/// and T_second = -arm_second (n x F_s).
struct ContactLoad
{
  Vec3 force = Vec3::Zero();         ///< N, on the second ball (the first gets -force)
  Vec3 lever = Vec3::Zero();         ///< N, n x F_s
  double arm_first = 0;              ///< m
  double arm_second = 0;             ///< m
  double bound_first = 0;            ///< 1/s^2, stability-bound row term of the first ball
  double bound_second = 0;           ///< 1/s^2, same for the second ball
  BreakMode broke = BreakMode::none; ///< the bond broke at this step

  Vec3 torque_first() const { return -arm_first * lever; }
  Vec3 torque_second() const { return -arm_second * lever; }
};

/// Energy carried away by contacts that left the table.
struct RetiredContactEnergy
{
  double friction_work = 0; ///< J
  double bond_energy = 0;   ///< J
};

class ContactTable
{
public:
  /// Pair constants of a new ball-ball pair: stiffnesses in series, the
  /// smaller friction coefficient.
  static ContactParams pair_params(const ParticleStore &p, Index i, Index j);

  /// Merges sorted candidates with the current entries (see header note).
  void rebuild(const std::vector<Pair> &candidates, const ParticleStore &particles);

  /// Replaces the table by saved entries (sorted by pair), their law states
  /// (one per entry, or none: all at rest) and retired energy.
  void assign(std::vector<Contact> entries, std::vector<LawState> law_states, const ParticleStore &particles,
              const RetiredContactEnergy &retired);

  /// Adds pair (i, j) if absent, its law state at rest, and returns its
  /// entry.  For set-up only (O(n)).
  Contact &ensure(Index i, Index j, const ParticleStore &particles);
  /// Entry of pair (i, j) or nullptr; binary search.
  Contact *find(Index i, Index j);
  const Contact *find(Index i, Index j) const;

  std::size_t size() const { return contacts_.size(); }
  Contact &operator[](std::size_t c) { return contacts_[c]; }
  const Contact &operator[](std::size_t c) const { return contacts_[c]; }
  std::vector<Contact> &entries() { return contacts_; }
  const std::vector<Contact> &entries() const { return contacts_; }
  /// The contact law's own history of entry c is law_states()[c].  The
  /// entries may be edited in place; adding or removing them goes through
  /// rebuild, assign or ensure, which keep the two arrays parallel.
  std::vector<LawState> &law_states() { return law_states_; }
  const std::vector<LawState> &law_states() const { return law_states_; }
  std::vector<ContactLoad> &loads() { return loads_; }
  const std::vector<ContactLoad> &loads() const { return loads_; }
  /// Entry c's trial forces, valid where loads()[c].broke is set.
  std::vector<BreakForces> &break_forces() { return break_forces_; }
  const std::vector<BreakForces> &break_forces() const { return break_forces_; }

  /// Contacts where p is the first ball: [first_begin(p), first_begin(p+1)).
  std::size_t first_begin(Index p) const { return first_start_[p]; }
  /// Contacts where p is the second ball: second_list()[second_begin(p) ...].
  std::size_t second_begin(Index p) const { return second_start_[p]; }
  const std::vector<std::size_t> &second_list() const { return second_list_; }

  const RetiredContactEnergy &retired() const { return retired_; }

  /// True once after entries were added or the table rebuilt: pair
  /// constants that depend on the balls (stability terms) must be refreshed.
  bool take_changed()
  {
    const bool c = changed_;
    changed_ = false;
    return c;
  }

private:
  void rebuild_adjacency(Index particles);
  void retire(const Contact &c);

  std::vector<Contact> contacts_, scratch_;
  std::vector<LawState> law_states_, scratch_states_;
  std::vector<ContactLoad> loads_;
  std::vector<BreakForces> break_forces_;
  std::vector<std::size_t> first_start_, second_start_, second_list_, scratch_positions_;
  RetiredContactEnergy retired_;
  bool changed_ = false;
};
} // namespace dem
