// Building blocks for planner tests: a machine with round numbers, and canonical commands made
// by hand, so that every expected value can be worked out on paper.
#pragma once

#include <vector>

#include "ncjoule/kinematics.hpp"

namespace ncjoule::test {

// Every axis: rapid 20000 mm/min, max feed 10000 mm/min, 1000 mm/s^2; trapezoid, linear rapids,
// tolerance junctions with 0.01 mm.
MachineProfile round_machine();

Pose at(double x, double y, double z = 0);

CanonCommand feed(Pose from, Pose to, double feed_mm_min, PathMode mode = PathMode::Continuous,
                  double tolerance = 0);
CanonCommand rapid(Pose from, Pose to);
// Arc in XY around (cx, cy); rotation +1 counter-clockwise, -1 clockwise.
CanonCommand arc(Pose from, Pose to, double cx, double cy, int rotation, double feed_mm_min);
CanonCommand event(CanonKind kind, double value = 0);

// Rest-to-rest or between given speeds, trapezoid with peak speed `peak`: the textbook formula.
double trapezoid_time(double v0, double v1, double peak, double length, double accel);

} // namespace ncjoule::test
