// The speed at which the path may pass from one move into the next without stopping.
#pragma once

#include "move_limits.hpp"

namespace ncjoule::kinematics_detail {

// `before` ends where `after` starts; `mode` and `tolerance` are the path control in force at
// the end of `before` (G61/G61.1 stop, G64 P<tolerance>; tolerance 0 = the profile's default).
double junction_speed(const MoveLimits& before, const MoveLimits& after, PathMode mode,
                      double tolerance, const Kinematics& machine);

} // namespace ncjoule::kinematics_detail
