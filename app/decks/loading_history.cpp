#include "app/decks/loading_history.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace demvv
{
namespace
{
constexpr double two_pi = 6.283185307179586;

const std::vector<std::string> history_names = {"constant rate", "creep", "relaxation", "cyclic"};
} // namespace

void LoadingHistory::declare(DeckSchema &s)
{
  s.choice("history", "constant rate", history_names,
           "'constant rate': the platens approach at the loading rate to the final strain; 'creep': the axial "
           "stress rises linearly to the hold stress over the ramp time, then is held (DEM: a servo-controlled "
           "top platen); 'relaxation': the strain rises at the loading rate to the hold strain, then is held; "
           "'cyclic': the strain rises to the mean strain, then oscillates about it.  Every history starts "
           "with the speed ramp of the ramp time.");
  s.real("hold stress", 1e6, 0, inf, "Pa", "Creep: the axial stress held (compression positive).",
         Interval::open_below);
  s.real("hold strain", 0.002, 0, 1, "-", "Relaxation: the axial strain held.", Interval::open_below);
  s.real("hold time", 0.01, 0, inf, "s", "Creep and relaxation: how long the stress or strain is held.",
         Interval::open_below);
  s.real("mean strain", 0.002, 0, 1, "-", "Cyclic: the axial strain the cycles are centred on.", Interval::open_below);
  s.real("strain amplitude", 0.001, 0, 1, "-",
         "Cyclic: amplitude of the sinusoid about the mean strain (at most the mean strain, so the platens "
         "stay in compression).",
         Interval::open_below);
  s.real("frequency", 100, 0, inf, "Hz",
         "Cyclic: frequency f of the sinusoid.  With 2 pi f a equal to the loading rate (a the amplitude) the "
         "platens enter the cycles at the ramp's speed; otherwise their speed jumps there.",
         Interval::open_below);
  s.integer("cycles", 2, 1, 1000000, "Cyclic: number of cycles after the mean strain is reached.");
  s.real("servo relaxation", 0.5, 0, inf, "-",
         "Creep in DEM: alpha of the platen servo (thesis eq. 3.15), the fraction of the stress error one step "
         "may correct; below 1 for a stable servo.",
         Interval::open_below);
}

LoadingHistory LoadingHistory::parse(const Deck &d)
{
  LoadingHistory h;
  const std::string name = d.text("loading/history");
  h.kind = static_cast<Kind>(std::find(history_names.begin(), history_names.end(), name) - history_names.begin());
  h.strain_rate = d.real("loading/strain rate");
  h.ramp_time = d.real("loading/ramp time");
  h.final_strain = d.real("loading/final strain");
  h.hold_stress = d.real("loading/hold stress");
  h.hold_strain = d.real("loading/hold strain");
  h.hold_time = d.real("loading/hold time");
  h.mean_strain = d.real("loading/mean strain");
  h.strain_amplitude = d.real("loading/strain amplitude");
  h.frequency = d.real("loading/frequency");
  h.cycles = d.integer("loading/cycles");
  h.servo_relaxation = d.real("loading/servo relaxation");
  if (h.kind == Kind::creep && !(h.ramp_time > 0))
    d.fail("loading/ramp time", "creep needs the stress to rise over a ramp (a servo or a force-controlled platen "
                                "cannot follow a step): expected a ramp time > 0");
  if (h.kind == Kind::creep && h.servo_relaxation >= 1)
    d.fail("loading/servo relaxation",
           "an unstable servo: with alpha >= 1 one step corrects more than the stress error and the platen "
           "oscillates with growing amplitude; expected a value in (0, 1), e.g. 0.5");
  if (h.kind == Kind::cyclic && h.strain_amplitude > h.mean_strain)
    d.fail("loading/strain amplitude", "the platens would pull on the sample: expected an amplitude at most the "
                                       "mean strain (" +
                                         format_number(h.mean_strain) + ")");
  return h;
}

double LoadingHistory::ramp_time_to(double e) const
{
  return e <= 0.5 * strain_rate * ramp_time ? std::sqrt(2 * ramp_time * e / strain_rate)
                                            : e / strain_rate + 0.5 * ramp_time;
}

double LoadingHistory::hold_start() const
{
  switch (kind)
  {
  case Kind::creep:
    return ramp_time;
  case Kind::relaxation:
    return ramp_time_to(hold_strain);
  case Kind::cyclic:
    return ramp_time_to(mean_strain);
  case Kind::constant_rate:
    break;
  }
  return 0;
}

double LoadingHistory::duration() const
{
  switch (kind)
  {
  case Kind::creep:
  case Kind::relaxation:
    return hold_start() + hold_time;
  case Kind::cyclic:
    return hold_start() + double(cycles) / frequency;
  case Kind::constant_rate:
    break;
  }
  return ramp_time_to(final_strain);
}

double LoadingHistory::axial_strain(double t) const
{
  const double ramped = t < ramp_time ? 0.5 * strain_rate * t * t / ramp_time : strain_rate * (t - 0.5 * ramp_time);
  switch (kind)
  {
  case Kind::relaxation:
    return std::min(ramped, hold_strain);
  case Kind::cyclic:
    return t < hold_start() ? ramped
                            : mean_strain + strain_amplitude * std::sin(two_pi * frequency * (t - hold_start()));
  case Kind::constant_rate:
  case Kind::creep:
    break;
  }
  return ramped;
}

double LoadingHistory::rate_on_piece(double t, double piece_start) const
{
  if (kind == Kind::creep)
    return piece_start < ramp_time ? hold_stress / ramp_time : 0.0;
  if (kind != Kind::constant_rate && piece_start >= hold_start())
    return kind == Kind::relaxation
             ? 0.0
             : strain_amplitude * two_pi * frequency * std::cos(two_pi * frequency * (t - hold_start()));
  return piece_start < ramp_time ? strain_rate * t / ramp_time : strain_rate;
}

std::vector<double> LoadingHistory::kinks() const
{
  std::vector<double> k;
  if (ramp_time > 0 && (kind == Kind::constant_rate || kind == Kind::creep || ramp_time < hold_start()))
    k.push_back(ramp_time);
  if (kind == Kind::relaxation || kind == Kind::cyclic)
    k.push_back(hold_start());
  return k;
}

double LoadingHistory::largest_prescribed() const
{
  switch (kind)
  {
  case Kind::creep:
    return hold_stress;
  case Kind::relaxation:
    return hold_strain;
  case Kind::cyclic:
    return mean_strain + strain_amplitude;
  case Kind::constant_rate:
    break;
  }
  return final_strain;
}

double LoadingHistory::axial_stress(double t) const { return hold_stress * std::min(1.0, t / ramp_time); }

std::string LoadingHistory::name() const { return history_names[static_cast<std::size_t>(kind)]; }

nlohmann::json LoadingHistory::to_json() const
{
  nlohmann::json j = {
    {"history", name()}, {"strain_rate_per_s", strain_rate}, {"ramp_time_s", ramp_time}, {"duration_s", duration()}};
  switch (kind)
  {
  case Kind::constant_rate:
    j["final_strain"] = final_strain;
    break;
  case Kind::creep:
    j["hold_stress_pa"] = hold_stress;
    j["hold_time_s"] = hold_time;
    j["servo_relaxation"] = servo_relaxation;
    break;
  case Kind::relaxation:
    j["hold_strain"] = hold_strain;
    j["hold_time_s"] = hold_time;
    break;
  case Kind::cyclic:
    j["mean_strain"] = mean_strain;
    j["strain_amplitude"] = strain_amplitude;
    j["frequency_hz"] = frequency;
    j["cycles"] = cycles;
    break;
  }
  j["hold_start_s"] = hold_start();
  return j;
}
} // namespace demvv
