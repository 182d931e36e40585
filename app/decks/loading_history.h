// The loading history of a compression test, one description for the DEM
// platens and the continuum cylinder alike (both read the same keys of the
// "loading" section, so one deck drives both sides of a comparison).
//
// Every history starts from rest with the loading ramp of thesis §6.1: the
// platen approach speed rises linearly from zero over the ramp time T_r to
// the loading rate, so the prescribed axial strain (compression positive) is
//   g(t) = rate t^2 / (2 T_r)        for t < T_r,
//   g(t) = rate (t - T_r / 2)        after,
// and then
//   constant rate  eps(t) = g(t) until the final strain;
//   relaxation     eps(t) = min(g(t), eps_h), held for the hold time once
//                  eps_h is reached (ramp and hold of the axial strain);
//   cyclic         eps(t) = g(t) up to the mean strain eps_m (reached at
//                  t_m), then eps_m + a sin(2 pi f (t - t_m)) for N cycles;
//   creep          the axial stress is prescribed instead: it rises
//                  linearly to sigma_h over T_r (T_r > 0), then is held for
//                  the hold time (a servo-controlled platen in DEM, a
//                  force-controlled platen in the continuum).
// Times [s], strains [-], stresses [Pa], compression positive.
#pragma once

#include "app/decks/deck.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace demvv
{
struct LoadingHistory
{
  enum class Kind
  {
    constant_rate,
    creep,
    relaxation,
    cyclic,
  };
  Kind kind = Kind::constant_rate;
  double strain_rate = 0;        ///< 1/s, loading rate after the ramp (set by the kind once the height is known)
  double ramp_time = 0;          ///< s, T_r
  double final_strain = 0;       ///< -, constant rate: the test stops there
  double hold_stress = 0;        ///< Pa, creep
  double hold_strain = 0;        ///< -, relaxation
  double hold_time = 0;          ///< s, creep and relaxation
  double mean_strain = 0;        ///< -, cyclic
  double strain_amplitude = 0;   ///< -, cyclic
  double frequency = 0;          ///< Hz, cyclic
  long cycles = 0;               ///< cyclic
  double servo_relaxation = 0.5; ///< alpha of the DEM creep servo (eq. 3.15)

  /// Declares the history entries of the current ("loading") subsection;
  /// the kinds declare "strain rate", "ramp time" and "final strain" themselves.
  static void declare(DeckSchema &s);
  /// Reads and cross-checks them; the strain rate is read too, when the
  /// deck has one under "loading/strain rate".
  static LoadingHistory parse(const Deck &d);

  bool stress_controlled() const { return kind == Kind::creep; }
  /// Prescribed axial strain at time t (not for creep) [-].
  double axial_strain(double t) const;
  /// Prescribed axial stress at time t (creep only) [Pa].
  double axial_stress(double t) const;
  /// d/dt of the prescribed quantity (strain, or stress for creep) at t on
  /// the smooth piece of the history that begins at piece_start [1/s or Pa/s].
  double rate_on_piece(double t, double piece_start) const;
  /// Times in (0, duration) where the prescribed quantity's derivative jumps [s].
  std::vector<double> kinks() const;
  /// Largest prescribed strain (or stress, for creep) over the test.
  double largest_prescribed() const;
  /// Time at which the test ends [s].
  double duration() const;
  /// Time at which the hold (creep, relaxation) or the cycling begins [s]; 0 for constant rate.
  double hold_start() const;
  std::string name() const;
  nlohmann::json to_json() const;

private:
  /// Time at which g(t) reaches the strain e [s].
  double ramp_time_to(double e) const;
};
} // namespace demvv
