// Look-ahead over the whole motion stream: entry and exit speeds such that every move can slow
// down in time for everything after it (backward pass) and speed up only as fast as it can
// (forward pass).
#pragma once

#include <vector>

namespace ncjoule::kinematics_detail {

struct SpeedPlanItem {
  // Inputs.
  double length = 0;
  double vmax = 0;
  double accel = 0;
  double jerk = 0;
  double junction_after = 0; // highest speed at the junction with the next item; 0 = stop there
  bool linear_ramp = false;  // LinuxCNC rule: a ramp from entry to exit speed if it is short
  // Results.
  double entry = 0;
  double exit = 0;
};

// Items are consecutive moves; the first starts and the last ends at rest.
void plan_speeds(std::vector<SpeedPlanItem>& items);

} // namespace ncjoule::kinematics_detail
