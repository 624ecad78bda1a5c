#include "test_helpers.hpp"

namespace ncjoule::test {

MachineProfile round_machine() {
  MachineProfile m;
  m.name = "round numbers";
  for (AxisLimits& a : m.kinematics.axes) {
    a.rapid_mm_s = 20000.0 / 60;
    a.max_feed_mm_s = 10000.0 / 60;
    a.accel_mm_s2 = 1000;
    a.jerk_mm_s3 = 0;
  }
  m.kinematics.path_tolerance_mm = 0.01;
  m.kinematics.tool_change_s = 5;
  m.kinematics.spindle_s_per_1000rpm = 0.5;
  return m;
}

Pose at(double x, double y, double z) {
  Pose p;
  p.x = x, p.y = y, p.z = z;
  return p;
}

CanonCommand feed(Pose from, Pose to, double feed_mm_min, PathMode mode, double tolerance) {
  CanonCommand c;
  c.kind = CanonKind::Feed;
  c.start = from;
  c.end = to;
  c.state.feed = feed_mm_min;
  c.state.path_mode = mode;
  c.state.path_tolerance = tolerance;
  return c;
}

CanonCommand rapid(Pose from, Pose to) {
  CanonCommand c = feed(from, to, 0);
  c.kind = CanonKind::Traverse;
  return c;
}

CanonCommand arc(Pose from, Pose to, double cx, double cy, int rotation, double feed_mm_min) {
  CanonCommand c = feed(from, to, feed_mm_min);
  c.kind = CanonKind::Arc;
  c.plane = Plane::XY;
  c.centre_first = cx;
  c.centre_second = cy;
  c.rotation = rotation;
  return c;
}

CanonCommand event(CanonKind kind, double value) {
  CanonCommand c;
  c.kind = kind;
  c.value = value;
  return c;
}

double trapezoid_time(double v0, double v1, double peak, double length, double accel) {
  const double d_up = (peak * peak - v0 * v0) / (2 * accel);
  const double d_down = (peak * peak - v1 * v1) / (2 * accel);
  return (peak - v0) / accel + (peak - v1) / accel + (length - d_up - d_down) / peak;
}

} // namespace ncjoule::test
