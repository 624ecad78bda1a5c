// What one move may do: its length, the highest path speed its feed and the machine allow, the
// path acceleration and jerk the slowest axis along its direction allows, and its tangents at
// both ends (for the junction speeds between moves).
#pragma once

#include "ncjoule/gcode.hpp"
#include "ncjoule/machine.hpp"
#include "warnings.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry> // cross

namespace ncjoule::kinematics_detail {

// A vector of the linear axes X, Y, Z (Eigen's: no default value, so members start at Zero()).
using Vec3 = Eigen::Vector3d;

struct MoveLimits {
  double length = 0;       // mm along the path; degrees for a move of rotary axes only
  double vmax = 0;         // path speed cap (mm/s or deg/s)
  double vmax_machine = 0; // the same without the programmed feed: what the axes allow
  double accel = 0;        // path acceleration cap
  double jerk = 0;         // path jerk cap; 0 = none (trapezoid)
  Vec3 dir_in = Vec3::Zero(),
       dir_out = Vec3::Zero(); // unit tangents of the linear axes at the start and end
  bool rotary_only = false;
  bool traverse = false; // a rapid (G0)
};

// Limits of a Traverse, Feed, Arc or Probe command. Moves too short to matter get length 0.
MoveLimits move_limits(const CanonCommand& move, const Kinematics& machine, Warnings& warnings);

// Shortest move that takes any time (mm or degrees); shorter ones are points.
inline constexpr double kMinMoveLength = 1e-9;

} // namespace ncjoule::kinematics_detail
