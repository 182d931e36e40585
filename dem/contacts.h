// ContactTable: every ball-ball pair the engine must look at, with history.
//
// The table holds the neighbour candidates plus every pair that is touching
// or bonded, sorted by (first, second).  Each entry carries the index of its
// pair constants (ContactParams, fixed at creation) in the table's list of
// them (a sample of one kind of ball has a single set: four bytes per entry
// instead of 24), whether it is bonded, its bond and its history
// (ContactState).  The contact law's own history (LawState, contact.h) lives
// in a second array, parallel to the entries: structure of arrays, so that a
// law without such history (the linear law) never loads it in its contact
// pass.  When the neighbour list is rebuilt the table merges the new
// candidates with the old entries in place, by linear walks over two sorted
// lists, carrying both arrays: history survives rebuilds without hashing, a new
// pair starts with its law state at rest, and a bonded pair stays in the
// table however far its balls drift apart.
//
// A contact's load at a step follows from its state: the force on the
// second ball F = F_n n + F_s, the lever n x F_s of its torques
// T_first = -arm_first (n x F_s) and T_second = -arm_second (n x F_s), the
// arms R - U/2 (the contact point is at arm * n from the first centre and
// -arm * n from the second).  The force pass (contact_model.h) keeps the
// loads of its step and sums them into the balls; the table keeps none.
#pragma once

#include "dem/contact.h"
#include "dem/neighbors.h"

#include <cstdint>
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

/// Index of a set of pair constants in a table's list of distinct ones.
using ConstantsIndex = std::uint32_t;

/// An entry of the table (see header note).
struct Contact
{
  Index first = 0;
  Index second = 0;
  ConstantsIndex constants = 0; ///< its ContactParams: ContactTable::params
  bool bonded = false;          ///< its bond holds
  ContactBond bond;
  ContactState state;
  StabilityTerms stability;

  /// Removes its bond, strengths and all.
  void unbond()
  {
    bonded = false;
    bond = ContactBond{};
  }
};

/// A ball-ball contact with its own pair constants: the form snapshots and
/// sample files keep, independent of any table's list of constants.
struct ContactRecord
{
  Index first = 0;
  Index second = 0;
  ContactParams params;
  bool bonded = false; ///< its bond holds
  ContactBond bond;
  ContactState state;
};

/// Energy carried away by contacts that left the table.
struct RetiredContactEnergy
{
  double friction_work = 0; ///< J
  double bond_energy = 0;   ///< J
};

/// Index of a table entry in the adjacency lists: four bytes, so a table
/// holds at most 2^32 - 1 entries (a rebuild beyond that throws).
using EntryIndex = std::uint32_t;

class ContactTable
{
public:
  /// Pair constants of a new ball-ball pair: stiffnesses in series, the
  /// smaller friction coefficient.
  static ContactParams pair_params(const ParticleStore &p, Index i, Index j);

  /// Merges sorted candidates with the current entries (see header note).
  void rebuild(const std::vector<Pair> &candidates, const ParticleStore &particles);

  /// Replaces the table by saved contacts (sorted by pair), their law
  /// states (one per contact, or none: all at rest) and retired energy.
  void assign(const std::vector<ContactRecord> &contacts, std::vector<LawState> law_states,
              const ParticleStore &particles, const RetiredContactEnergy &retired);
  /// The entries as saved contacts, in table order.
  std::vector<ContactRecord> records() const;

  /// Pair constants of an entry of this table.
  const ContactParams &params(const Contact &c) const { return constants_[c.constants]; }
  /// Gives an entry of this table other pair constants.
  void set_params(Contact &c, const ContactParams &params) { c.constants = constants_index(params); }
  /// The pair constants the entries index: each set once while there are
  /// few (a sample of one kind of ball has one), and perhaps some that no
  /// entry uses any more (a rebuild drops them once they outnumber the
  /// entries).
  const std::vector<ContactParams> &distinct_params() const { return constants_; }

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
  /// rebuild, assign or ensure, which keep the two arrays parallel.  A
  /// table told that its law keeps no history (keeps_law_states(false): the
  /// linear law) holds no slots at all, 48 bytes less per pair.
  std::vector<LawState> &law_states() { return law_states_; }
  const std::vector<LawState> &law_states() const { return law_states_; }
  /// Whether entries carry a LawState slot (by default they do); turning
  /// the slots off drops them, turning them on starts them all at rest.
  void keeps_law_states(bool keep);
  /// Force of entry c on its second ball at the last force pass [N]
  /// (zero when it carried none).
  Vec3 force(std::size_t c) const
  {
    const ContactState &s = contacts_[c].state;
    return s.touching() ? Vec3(s.normal_force * s.normal + s.shear_force) : Vec3::Zero();
  }

  /// Contacts where p is the first ball: [first_begin(p), first_begin(p+1)).
  std::size_t first_begin(Index p) const { return first_start_[p]; }
  /// Contacts where p is the second ball: second_list()[second_begin(p) ...].
  std::size_t second_begin(Index p) const { return second_start_[p]; }
  const std::vector<EntryIndex> &second_list() const { return second_list_; }

  const RetiredContactEnergy &retired() const { return retired_; }
  /// Moves entry c's friction work and released bond energy to the retired
  /// totals (a contact that stopped carrying force; called in entry order).
  void retire_energies(std::size_t c);

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
  /// Index of these constants (bit for bit) in constants_, added if new
  /// (see contacts.cpp for when a set may be listed twice).
  ConstantsIndex constants_index(const ContactParams &params);
  /// Drops the constants no entry uses and renumbers the entries.
  void compact_constants();

  std::vector<Contact> contacts_;
  std::vector<ContactParams> constants_;
  ConstantsIndex last_constants_ = 0; ///< the last index found: most entries share one set
  std::vector<LawState> law_states_;
  std::vector<EntryIndex> first_start_, second_start_, second_list_;
  RetiredContactEnergy retired_;
  bool changed_ = false;
  bool law_slots_ = true;
};
} // namespace dem
