// The linear law's ordinary step for eight contacts at once.
//
// Most entries of a slow compression do the same thing at every step: an
// unbonded contact that touched at the last pass still touches and sticks.
// For eight such entries of the table, one AVX-512 instruction per
// operation (eight doubles) does what resolve_contact (contact_resolve.h)
// does for each of them with the linear law (thesis §3.4.1):
//
//   geometry:  d = x_j - x_i, n = d / |d|, U = R_i + R_j - |d| > 0,
//              arms R - U/2;
//   shear:     F_s turned with the contact plane (rotate_with_contact_plane,
//              about the mean of the old and new normals), then
//              F_s <- F_s - K^s V_s dt                          (eq. 3.3-3.4);
//   normal:    F_n = K^n U                                      (eq. 3.2);
//   friction:  the contact sticks, |F_s|^2 < (1 - 1e-12) (mu F_n)^2;
//   loads:     F = F_n n + F_s on the second ball, lever n x F_s.
//
// A lane whose entry is bonded, did not touch at the last pass, separates
// now (U <= 0) or slips is not resolved here: the block returns which lanes
// it resolved, and the pass gives the others to resolve_contact, which
// handles every case.  The pass queues the candidates (unbonded, touching
// at the last pass) as it meets them and hands them over eight at a time,
// so a bonded sample, whose few candidates lie far apart, fills its blocks
// as a loose packing does.  The entries are read where they are, in the
// table (each field gathered with its stride), and the caller writes the
// new state back: the table stays the only copy of every contact's state.
//
// The arithmetic is resolve_contact's, operation for operation; only the
// rounding can differ, where the compiler fuses a multiply and an add in
// one path and not in the other (a test bounds the difference at a few
// units in the last place of the forces; the dot products add as Eigen's
// do, x + (y + z)).  So which path an entry takes must depend on the entry
// alone, never on the entries beside it: a block holds whichever
// candidates came together (fewer than eight at the end of a thread's
// range), and each lane's arithmetic is its own.  A run then gives the
// same results on any thread count, and whatever the table holds beside an
// entry (candidates of a wider or narrower skin).  On the identical-work
// scene this path resolves about 83 % of the entries (BENCHMARKS.md,
// "Eight contacts per instruction").
//
// Built only where the compiler targets AVX-512 (DEMVV_NATIVE on such a
// CPU); elsewhere contact_lanes is false and the pass resolves every entry
// one by one.  Used only where a run asks for it
// (SimulationSettings::contacts_in_lanes): a scene without bonds does;
// where bonds break, their contacts mostly slip, are tried here and then
// resolved again, and the blocks cost more than they save.
#pragma once

#include "dem/contacts.h"
#include "dem/particles.h"

#include <cstdint>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace dem
{
/// What a block leaves for each lane it resolved (the same layout in every
/// build, so that every file sees one PassEvents, whatever its flags).
struct LaneResults
{
  alignas(64) double normal_x[8], normal_y[8], normal_z[8]; ///< unit normal n
  alignas(64) double shear_x[8], shear_y[8], shear_z[8];    ///< N, F_s
  alignas(64) double normal_force[8];                       ///< N, F_n
  alignas(64) double overlap[8];                            ///< m, U
  alignas(64) double force_x[8], force_y[8], force_z[8];    ///< N, F on the second ball
  alignas(64) double lever_x[8], lever_y[8], lever_z[8];    ///< N, n x F_s
  alignas(64) double bound_first[8], bound_second[8];       ///< 1/s^2, the entries' stability terms

  /// Writes lane l's new state into its entry.
  void commit(int l, ContactState &s) const
  {
    s.shear_force = Vec3(shear_x[l], shear_y[l], shear_z[l]);
    s.normal = Vec3(normal_x[l], normal_y[l], normal_z[l]);
    s.normal_force = normal_force[l];
    s.overlap = overlap[l];
  }
};

/// Whether entry e may be ordinary at this pass: unbonded and touching at
/// the last pass.  The pass queues such entries for the blocks, and a block
/// resolves no other.
inline bool lane_candidate(const Contact &e) { return !e.bonded && e.state.touching(); }

#if defined(__AVX512F__)
inline constexpr bool contact_lanes = true;

namespace lanes
{
using Reals = __m512d;

inline Reals gather(__m256i index, const double *base)
{
  return _mm512_mask_i32gather_pd(_mm512_setzero_pd(), 0xFF, index, base, 8);
}
inline Reals gather(__m512i index, const double *base)
{
  return _mm512_mask_i64gather_pd(_mm512_setzero_pd(), 0xFF, index, base, 8);
}
inline __m256i times_three(__m256i i) { return _mm256_add_epi32(i, _mm256_add_epi32(i, i)); }

/// A 3-vector per lane.
struct Vectors
{
  Reals x, y, z;
};
inline Vectors gather3(__m256i index3, const double *base)
{
  return {gather(index3, base), gather(index3, base + 1), gather(index3, base + 2)};
}
inline Vectors operator-(const Vectors &a, const Vectors &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vectors operator+(const Vectors &a, const Vectors &b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vectors operator*(Reals s, const Vectors &a) { return {s * a.x, s * a.y, s * a.z}; }
inline Reals dot(const Vectors &a, const Vectors &b) { return a.x * b.x + (a.y * b.y + a.z * b.z); }
inline Vectors cross(const Vectors &a, const Vectors &b)
{
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline __mmask8 positive(Reals a) { return _mm512_cmp_pd_mask(a, _mm512_setzero_pd(), _CMP_GT_OQ); }
} // namespace lanes

/// The ordinary step of entries queued[0 .. count-1] of `entries` (count 1
/// to 8; see header note) at the current positions, dt the step that produced
/// the displacement since the last pass; `params` the table's pair
/// constants.  Returns the mask of the lanes it resolved, whose new state
/// and loads are in `out`; it writes no entry.
inline __mmask8 linear_block(const ParticleStore &p, const ContactParams *params, const Contact *entries,
                             const std::size_t *queued, int count, double dt, LaneResults &out)
{
  using namespace lanes;
  static_assert(sizeof(Contact) % sizeof(double) == 0, "entries are read as doubles with their stride");
  constexpr long long stride = sizeof(Contact) / sizeof(double);
  // Lanes past `count` read the first lane's entry again and are never
  // resolved.  A lane may be ordinary if its entry is unbonded and touched
  // at the last pass (the pass queues only such entries; a block without
  // one stops here).
  unsigned candidates = 0;
  for (int l = 0; l < count; ++l)
  {
    const Contact &e = entries[queued[l]];
    candidates |= unsigned(lane_candidate(e)) << l;
  }
  if (!candidates)
    return 0;
  alignas(32) std::int32_t first[8], second[8], constants[8];
  alignas(64) long long at_entry[8];
  for (int l = 0; l < 8; ++l)
  {
    const std::size_t c = queued[l < count ? l : 0];
    const Contact &e = entries[c];
    first[l] = e.first;
    second[l] = e.second;
    constants[l] = static_cast<std::int32_t>(e.constants);
    at_entry[l] = static_cast<long long>(c) * stride;
  }
  // The state's fields as doubles from the first entry's shear force.
  const double *state = entries[0].state.shear_force.data();
  const long long at_normal = entries[0].state.normal.data() - state;
  const long long at_stability = &entries[0].stability.first - state;
  const __m512i entry = _mm512_load_si512(at_entry);
  const Vectors old_normal{gather(entry, state + at_normal), gather(entry, state + at_normal + 1),
                           gather(entry, state + at_normal + 2)};
  __mmask8 ordinary = static_cast<__mmask8>(candidates);

  const __m256i i = _mm256_load_si256(reinterpret_cast<const __m256i *>(first));
  const __m256i j = _mm256_load_si256(reinterpret_cast<const __m256i *>(second));
  const __m256i i3 = times_three(i), j3 = times_three(j);
  const Vectors d = gather3(j3, p.position[0].data()) - gather3(i3, p.position[0].data());
  const Reals radius_i = gather(i, p.radius.data()), radius_j = gather(j, p.radius.data());
  const Reals distance = _mm512_maskz_sqrt_pd(0xFF, dot(d, d));
  ordinary &= positive(distance);
  const Vectors normal = (_mm512_set1_pd(1.0) / distance) * d;
  const Reals overlap = radius_i + radius_j - distance;
  ordinary &= positive(overlap);
  if (!ordinary)
    return 0;

  const Reals half = _mm512_set1_pd(0.5), step = _mm512_set1_pd(dt);
  const Reals arm_i = radius_i - half * overlap, arm_j = radius_j - half * overlap;
  const Vectors velocity_difference = gather3(j3, p.velocity[0].data()) - gather3(i3, p.velocity[0].data());
  const Vectors spin_i = gather3(i3, p.spin[0].data()), spin_j = gather3(j3, p.spin[0].data());
  // The pair constants: most blocks share one set.
  const __m256i k = _mm256_load_si256(reinterpret_cast<const __m256i *>(constants));
  const double *constant = &params[0].kn;
  Reals kn, ks, friction;
  if (_mm256_movemask_epi8(_mm256_cmpeq_epi32(k, _mm256_set1_epi32(constants[0]))) == -1)
  {
    const ContactParams &pair = params[constants[0]];
    kn = _mm512_set1_pd(pair.kn);
    ks = _mm512_set1_pd(pair.ks);
    friction = _mm512_set1_pd(pair.friction);
  }
  else
  {
    const Vectors all = gather3(times_three(k), constant);
    kn = all.x;
    ks = all.y;
    friction = all.z;
  }

  // Contact-point velocities along the mean normal, and the twist.
  const Vectors mid_normal = half * (old_normal + normal);
  const Vectors relative_velocity = velocity_difference - cross(arm_j * spin_j + arm_i * spin_i, mid_normal);
  const Reals twist = half * dot(spin_i + spin_j, mid_normal) * step;
  // The old shear force turned with the contact plane (rotate_with_contact_plane).
  const Vectors old_shear{gather(entry, state), gather(entry, state + 1), gather(entry, state + 2)};
  const Vectors phi = cross(old_normal, normal) + (half * twist) * (old_normal + normal);
  const Vectors turn = cross(phi, old_shear);
  const Vectors turned = old_shear + turn + half * cross(phi, turn);
  const Vectors rotated = turned - dot(turned, normal) * normal;
  const Vectors increment = step * (relative_velocity - dot(relative_velocity, normal) * normal);
  const Reals normal_force = _mm512_maskz_max_pd(0xFF, kn * overlap, _mm512_setzero_pd());
  const Vectors shear = rotated - ks * increment;
  const Reals limit = friction * normal_force;
  const Reals limit_squared = limit * limit;
  ordinary &= _mm512_cmp_pd_mask(limit_squared, _mm512_set1_pd(1e-290), _CMP_GT_OQ) &
              _mm512_cmp_pd_mask(dot(shear, shear), _mm512_set1_pd(1.0 - 1e-12) * limit_squared, _CMP_LT_OQ);
  if (!ordinary)
    return 0;

  const Vectors force = normal_force * normal + shear;
  const Vectors lever = cross(normal, shear);
  _mm512_store_pd(out.normal_x, normal.x);
  _mm512_store_pd(out.normal_y, normal.y);
  _mm512_store_pd(out.normal_z, normal.z);
  _mm512_store_pd(out.shear_x, shear.x);
  _mm512_store_pd(out.shear_y, shear.y);
  _mm512_store_pd(out.shear_z, shear.z);
  _mm512_store_pd(out.normal_force, normal_force);
  _mm512_store_pd(out.overlap, overlap);
  _mm512_store_pd(out.force_x, force.x);
  _mm512_store_pd(out.force_y, force.y);
  _mm512_store_pd(out.force_z, force.z);
  _mm512_store_pd(out.lever_x, lever.x);
  _mm512_store_pd(out.lever_y, lever.y);
  _mm512_store_pd(out.lever_z, lever.z);
  // In compression the precomputed stability terms hold (contact_model.h).
  _mm512_store_pd(out.bound_first, gather(entry, state + at_stability));
  _mm512_store_pd(out.bound_second, gather(entry, state + at_stability + 1));
  return ordinary;
}
#else
inline constexpr bool contact_lanes = false;
#endif
} // namespace dem
