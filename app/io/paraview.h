// ParaView output (VTK XML PolyData, ASCII) for DEM runs.
//
// Each frame writes three files, each atomically, and refreshes the .pvd
// collections that let ParaView step through time:
//   particles_NNNNN.vtp  ball centres with radius [m], velocity [m/s],
//                        spin [rad/s], force [N], id (the ball's row in the
//                        user's particle file; use a Glyph filter with a
//                        sphere scaled by radius);
//   contacts_NNNNN.vtp   one line per force-carrying contact between ball
//                        centres, with normal_force_n (> 0 compression),
//                        shear_force_n, state (+1 compression, -1 tension)
//                        and bonded (1/0): colour by state for the
//                        compression/tension network;
//   breaks_NNNNN.vtp     every bond broken so far, at the contact point where
//                        it broke, with mode (1 tension, 2 shear) and time_s.
#pragma once

#include "dem/simulation.h"

#include <nlohmann/json.hpp>
#include <string>

#include <vector>

namespace demvv
{
class ParaviewWriter
{
public:
  explicit ParaviewWriter(std::string dir);
  /// Records bond breaks (call with each batch taken from the simulation).
  void add_breaks(const std::vector<dem::BondBreak> &breaks);
  void write_frame(const dem::Simulation &sim, double time);
  /// The id each ball's frames carry: its row in the user's file where the
  /// run renumbered the balls (dem/spatial_order.h); by default its index.
  void set_ball_ids(std::vector<dem::Index> ids) { ids_ = std::move(ids); }

  /// What a resumed run needs to continue the frames where they stopped
  /// (frame count and times, bonds broken so far), exact.
  nlohmann::json state() const;
  void restore(const nlohmann::json &state);

private:
  struct BrokenBond
  {
    dem::Vec3 point;
    int mode;
    double time;
  };
  std::string dir_;
  int frame_ = 0;
  std::vector<double> times_;
  std::vector<BrokenBond> broken_;
  std::vector<dem::Index> ids_;
};
} // namespace demvv
