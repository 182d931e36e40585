#include "dem/contacts.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace dem
{
ContactParams ContactTable::pair_params(const ParticleStore &p, Index i, Index j)
{
  return {in_series(p.kn[i], p.kn[j]), in_series(p.ks[i], p.ks[j]), std::min(p.friction[i], p.friction[j])};
}

namespace
{
/// Whether two sets of constants are the same bit for bit (so that +0 and
/// -0 stay apart).
bool same_bits(const ContactParams &a, const ContactParams &b)
{
  const double x[3] = {a.kn, a.ks, a.friction}, y[3] = {b.kn, b.ks, b.friction};
  return std::memcmp(x, y, sizeof x) == 0;
}
} // namespace

ConstantsIndex ContactTable::constants_index(const ContactParams &params)
{
  // Most entries share the last set found; a table of few sets is searched
  // whole; beyond that a set is added unsearched (a sample whose pairs all
  // differ then costs its 24 bytes per entry, as without the list).
  constexpr std::size_t searched = 64;
  if (last_constants_ < constants_.size() && same_bits(constants_[last_constants_], params))
    return last_constants_;
  if (constants_.size() <= searched)
    for (std::size_t k = 0; k < constants_.size(); ++k)
      if (same_bits(constants_[k], params))
        return last_constants_ = static_cast<ConstantsIndex>(k);
  // The largest index stays free: compaction marks unused sets with it.
  if (constants_.size() >= std::numeric_limits<ConstantsIndex>::max())
    throw std::length_error("contact table: more than 2^32 - 1 sets of pair constants");
  last_constants_ = static_cast<ConstantsIndex>(constants_.size());
  constants_.push_back(params);
  return last_constants_;
}

void ContactTable::compact_constants()
{
  constexpr ConstantsIndex unused = std::numeric_limits<ConstantsIndex>::max();
  std::vector<ConstantsIndex> renumbered(constants_.size(), unused);
  std::vector<ContactParams> used;
  for (Contact &c : contacts_)
  {
    ConstantsIndex &to = renumbered[c.constants];
    if (to == unused)
    {
      to = static_cast<ConstantsIndex>(used.size());
      used.push_back(constants_[c.constants]);
    }
    c.constants = to;
  }
  constants_ = std::move(used);
  last_constants_ = 0;
}

void ContactTable::retire(const Contact &c)
{
  retired_.friction_work += c.state.friction_work;
  retired_.bond_energy += c.state.bond_energy;
}

void ContactTable::retire_energies(std::size_t c)
{
  ContactState &s = contacts_[c].state;
  retire(contacts_[c]);
  s.friction_work = 0;
  s.bond_energy = 0;
}

void ContactTable::rebuild(const std::vector<Pair> &candidates, const ParticleStore &particles)
{
  // In place, so that a rebuild holds no second copy of the table: a
  // forward walk keeps the entries that are candidates, touching or bonded
  // (moved down over the retired ones, which retire in increasing order)
  // and counts the new candidates; a backward walk over the kept entries and
  // the candidates then places every entry at its final index, writing
  // behind what it has still to read.
  const auto key = [](const Contact &c) { return Pair{c.first, c.second}; };
  std::size_t kept = 0, fresh = 0, old = 0;
  const auto keep = [&](std::size_t k)
  {
    contacts_[kept] = contacts_[k];
    if (law_slots_)
      law_states_[kept] = law_states_[k];
    ++kept;
  };
  const auto keep_or_retire_below = [&](const Pair *bound)
  {
    for (; old < contacts_.size() && (!bound || key(contacts_[old]) < *bound); ++old)
    {
      const Contact &c = contacts_[old];
      if (c.bonded || c.state.touching())
        keep(old);
      else
        retire(c);
    }
  };
  for (const Pair &pair : candidates)
  {
    keep_or_retire_below(&pair);
    if (old < contacts_.size() && key(contacts_[old]) == pair)
      keep(old++);
    else
      ++fresh;
  }
  keep_or_retire_below(nullptr);

  contacts_.resize(kept + fresh);
  if (law_slots_)
    law_states_.resize(kept + fresh);
  std::size_t next = kept + fresh, k = kept, c = candidates.size();
  while (next > 0)
  {
    --next;
    const bool from_kept = k > 0 && (c == 0 || !(key(contacts_[k - 1]) < candidates[c - 1]));
    if (from_kept)
    {
      --k;
      if (c > 0 && key(contacts_[k]) == candidates[c - 1])
        --c;
      contacts_[next] = contacts_[k];
      if (law_slots_)
        law_states_[next] = law_states_[k];
    }
    else
    {
      --c;
      Contact entry;
      entry.first = candidates[c].first;
      entry.second = candidates[c].second;
      entry.constants = constants_index(pair_params(particles, entry.first, entry.second));
      contacts_[next] = entry;
      if (law_slots_)
        law_states_[next] = LawState{};
    }
  }
  // Constants of pairs that left the table linger until they outnumber the
  // entries (only samples whose pairs differ make many).
  if (constants_.size() > 2 * contacts_.size() + 64)
    compact_constants();
  rebuild_adjacency(particles.size());
  changed_ = true;
}

void ContactTable::assign(const std::vector<ContactRecord> &contacts, std::vector<LawState> law_states,
                          const ParticleStore &particles, const RetiredContactEnergy &retired)
{
  if (!law_states.empty() && law_states.size() != contacts.size())
    throw std::invalid_argument("contact table: " + std::to_string(law_states.size()) + " law states for " +
                                std::to_string(contacts.size()) + " contacts");
  constants_.clear();
  contacts_.clear();
  contacts_.reserve(contacts.size());
  for (const ContactRecord &r : contacts)
  {
    Contact c;
    c.first = r.first;
    c.second = r.second;
    c.constants = constants_index(r.params);
    c.bonded = r.bonded;
    c.bond = r.bond;
    c.state = r.state;
    contacts_.push_back(c);
  }
  law_states_ = std::move(law_states);
  law_states_.resize(law_slots_ ? contacts_.size() : 0);
  retired_ = retired;
  rebuild_adjacency(particles.size());
  changed_ = true;
}

Contact &ContactTable::ensure(Index i, Index j, const ParticleStore &particles)
{
  if (i > j)
    std::swap(i, j);
  const Pair pair{i, j};
  auto it = std::lower_bound(contacts_.begin(), contacts_.end(), pair,
                             [](const Contact &c, const Pair &p) {
                               return Pair{c.first, c.second} < p;
                             });
  if (it == contacts_.end() || it->first != i || it->second != j)
  {
    Contact c;
    c.first = i;
    c.second = j;
    c.constants = constants_index(pair_params(particles, i, j));
    it = contacts_.insert(it, c);
    const auto pos = it - contacts_.begin();
    if (law_slots_)
      law_states_.insert(law_states_.begin() + pos, LawState{});
    rebuild_adjacency(particles.size());
    changed_ = true;
    it = contacts_.begin() + pos;
  }
  return *it;
}

std::vector<ContactRecord> ContactTable::records() const
{
  std::vector<ContactRecord> out;
  out.reserve(contacts_.size());
  for (const Contact &c : contacts_)
    out.push_back({c.first, c.second, params(c), c.bonded, c.bond, c.state});
  return out;
}

void ContactTable::keeps_law_states(bool keep)
{
  law_slots_ = keep;
  law_states_.assign(keep ? contacts_.size() : 0, LawState{});
  law_states_.shrink_to_fit();
}

const Contact *ContactTable::find(Index i, Index j) const
{
  if (i > j)
    std::swap(i, j);
  const Pair pair{i, j};
  auto it = std::lower_bound(contacts_.begin(), contacts_.end(), pair,
                             [](const Contact &c, const Pair &p) {
                               return Pair{c.first, c.second} < p;
                             });
  return (it != contacts_.end() && it->first == i && it->second == j) ? &*it : nullptr;
}

Contact *ContactTable::find(Index i, Index j)
{
  return const_cast<Contact *>(static_cast<const ContactTable *>(this)->find(i, j));
}

void ContactTable::rebuild_adjacency(Index particles)
{
  if (contacts_.size() > std::numeric_limits<EntryIndex>::max())
    throw std::length_error("contact table: " + std::to_string(contacts_.size()) +
                            " entries, more than its adjacency lists can index (2^32 - 1)");
  first_start_.assign(static_cast<std::size_t>(particles) + 1, 0);
  second_start_.assign(static_cast<std::size_t>(particles) + 1, 0);
  for (const Contact &c : contacts_)
  {
    ++first_start_[c.first + 1];
    ++second_start_[c.second + 1];
  }
  for (Index p = 0; p < particles; ++p)
  {
    first_start_[p + 1] += first_start_[p];
    second_start_[p + 1] += second_start_[p];
  }
  // Contacts of a second ball in increasing contact order: a fixed gather
  // order, hence the same sums whatever the thread count.  The fill counts
  // of each second ball borrow its start, restored by one shift afterwards.
  second_list_.resize(contacts_.size());
  for (std::size_t c = 0; c < contacts_.size(); ++c)
    second_list_[second_start_[contacts_[c].second]++] = static_cast<EntryIndex>(c);
  for (Index p = particles; p > 0; --p)
    second_start_[p] = second_start_[p - 1];
  second_start_[0] = 0;
}
} // namespace dem
