// Dog-leg rapids: each axis travels at its own rapid rate under its own ramp, so the tool
// follows a bent path and the move lasts as long as its slowest axis.
#pragma once

#include <array>

#include "ncjoule/gcode.hpp"
#include "ncjoule/machine.hpp"
#include "velocity_profile.hpp"

namespace ncjoule::kinematics_detail {

class DogLegMove {
public:
  DogLegMove(const CanonCommand& move, const Kinematics& machine);

  double duration() const { return duration_; }
  double peak_speed() const { return peak_; } // of the linear axes, mm/s
  Pose position_at(double t) const;
  double speed_at(double t) const;

private:
  static constexpr int kAxes = 6; // X Y Z A B C
  std::array<VelocityProfile, kAxes> profiles_{};
  std::array<double, kAxes> direction_{}; // +1 or -1
  Pose start_;
  double duration_ = 0, peak_ = 0;
};

} // namespace ncjoule::kinematics_detail
