#include "dem/contacts.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace dem
{
ContactParams ContactTable::pair_params(const ParticleStore &p, Index i, Index j)
{
  return {in_series(p.kn[i], p.kn[j]), in_series(p.ks[i], p.ks[j]),
          std::min(p.friction[i], p.friction[j])};
}

void ContactTable::retire(const Contact &c)
{
  retired_.friction_work += c.state.friction_work;
  retired_.bond_energy += c.state.bond_energy;
}

void ContactTable::rebuild(const std::vector<Pair> &candidates, const ParticleStore &particles)
{
  scratch_.clear();
  scratch_states_.clear();
  const auto key = [](const Contact &c) { return Pair{c.first, c.second}; };
  std::size_t old = 0;
  const auto keep_old = [&](std::size_t k) {
    scratch_.push_back(contacts_[k]);
    if (law_slots_)
      scratch_states_.push_back(law_states_[k]);
  };
  for (const Pair &pair : candidates)
  {
    while (old < contacts_.size() && key(contacts_[old]) < pair)
    {
      const Contact &c = contacts_[old];
      if (c.bond.intact || c.state.touching)
        keep_old(old);
      else
        retire(c);
      ++old;
    }
    if (old < contacts_.size() && key(contacts_[old]) == pair)
    {
      keep_old(old);
      ++old;
    }
    else
    {
      Contact c;
      c.first = pair.first;
      c.second = pair.second;
      c.params = pair_params(particles, pair.first, pair.second);
      scratch_.push_back(c);
      if (law_slots_)
        scratch_states_.emplace_back();
    }
  }
  for (; old < contacts_.size(); ++old)
  {
    if (contacts_[old].bond.intact || contacts_[old].state.touching)
      keep_old(old);
    else
      retire(contacts_[old]);
  }
  contacts_.swap(scratch_);
  law_states_.swap(scratch_states_);
  rebuild_adjacency(particles.size());
  changed_ = true;
}

void ContactTable::assign(std::vector<Contact> entries, std::vector<LawState> law_states,
                          const ParticleStore &particles, const RetiredContactEnergy &retired)
{
  if (!law_states.empty() && law_states.size() != entries.size())
    throw std::invalid_argument("contact table: " + std::to_string(law_states.size()) + " law states for " +
                                std::to_string(entries.size()) + " contacts");
  contacts_ = std::move(entries);
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
                             [](const Contact &c, const Pair &p) { return Pair{c.first, c.second} < p; });
  if (it == contacts_.end() || it->first != i || it->second != j)
  {
    Contact c;
    c.first = i;
    c.second = j;
    c.params = pair_params(particles, i, j);
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

void ContactTable::keeps_law_states(bool keep)
{
  law_slots_ = keep;
  law_states_.assign(keep ? contacts_.size() : 0, LawState{});
  law_states_.shrink_to_fit();
  scratch_states_ = {};
}

const Contact *ContactTable::find(Index i, Index j) const
{
  if (i > j)
    std::swap(i, j);
  const Pair pair{i, j};
  auto it = std::lower_bound(contacts_.begin(), contacts_.end(), pair,
                             [](const Contact &c, const Pair &p) { return Pair{c.first, c.second} < p; });
  return (it != contacts_.end() && it->first == i && it->second == j) ? &*it : nullptr;
}

Contact *ContactTable::find(Index i, Index j)
{
  return const_cast<Contact *>(static_cast<const ContactTable *>(this)->find(i, j));
}

void ContactTable::rebuild_adjacency(Index particles)
{
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
  // order, hence the same sums whatever the thread count.
  second_list_.resize(contacts_.size());
  std::vector<std::size_t> &fill = scratch_positions_;
  fill.assign(second_start_.begin(), second_start_.end() - 1);
  for (std::size_t c = 0; c < contacts_.size(); ++c)
    second_list_[fill[contacts_[c].second]++] = c;
}
} // namespace dem
