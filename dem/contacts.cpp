#include "dem/contacts.h"

#include <algorithm>

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
  origin_.clear();
  const auto key = [](const Contact &c) { return Pair{c.first, c.second}; };
  std::size_t old = 0;
  const auto keep_old = [&](std::size_t k) {
    scratch_.push_back(contacts_[k]);
    origin_.push_back(static_cast<std::ptrdiff_t>(k));
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
      origin_.push_back(-1);
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
  rebuild_adjacency(particles.size());
  changed_ = true;
}

void ContactTable::assign(std::vector<Contact> entries, const ParticleStore &particles,
                          const RetiredContactEnergy &retired)
{
  contacts_ = std::move(entries);
  retired_ = retired;
  origin_.assign(contacts_.size(), -1);
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
    origin_.resize(contacts_.size());
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(contacts_.size()); ++k)
      origin_[k] = k < pos ? k : (k == pos ? -1 : k - 1);
    rebuild_adjacency(particles.size());
    changed_ = true;
    it = contacts_.begin() + pos;
  }
  return *it;
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
  loads_.resize(contacts_.size());
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
