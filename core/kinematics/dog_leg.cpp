#include "dog_leg.hpp"

#include <algorithm>
#include <cmath>

namespace ncjoule::kinematics_detail {
namespace {

std::array<double, 6> components(const Pose& p) {
  return {p.x, p.y, p.z, p.a, p.b, p.c};
}

} // namespace

DogLegMove::DogLegMove(const CanonCommand& move, const Kinematics& k) : start_(move.start) {
  const std::array<double, 6> from = components(move.start), to = components(move.end);
  const bool s_curve = k.feed_profile == FeedProfile::SCurve;
  for (int i = 0; i < kAxes; ++i) {
    const double delta = to[i] - from[i];
    direction_[i] = delta < 0 ? -1.0 : 1.0;
    double speed, accel, jerk = 0;
    if (i < 3) {
      speed = k.axes[i].rapid_mm_s;
      accel = k.axes[i].accel_mm_s2;
      if (s_curve) jerk = k.axes[i].jerk_mm_s3;
    } else if (k.rotary_rapid_deg_s > 0 && k.rotary_accel_deg_s2 > 0) {
      speed = k.rotary_rapid_deg_s;
      accel = k.rotary_accel_deg_s2;
    } else { // no rotary limits in the profile: as the X axis (see move_limits)
      speed = k.axes[0].rapid_mm_s;
      accel = k.axes[0].accel_mm_s2;
    }
    profiles_[i] = VelocityProfile::rest_to_rest(speed, std::abs(delta), accel, jerk);
    duration_ = std::max(duration_, profiles_[i].duration());
  }
  // The path speed peaks where one of the axes changes piece; try every such instant.
  for (int i = 0; i < 3; ++i)
    for (int p = 0; p < profiles_[i].piece_count(); ++p) {
      peak_ = std::max(peak_, speed_at(profiles_[i].piece_start(p)));
      peak_ = std::max(peak_, speed_at(std::nextafter(profiles_[i].piece_start(p), 0.0)));
    }
}

Pose DogLegMove::position_at(double t) const {
  std::array<double, 6> c = components(start_);
  for (int i = 0; i < kAxes; ++i)
    c[i] += direction_[i] * profiles_[i].distance_at(t);
  return Pose{c[0], c[1], c[2], c[3], c[4], c[5]};
}

double DogLegMove::speed_at(double t) const {
  double sum = 0;
  for (int i = 0; i < 3; ++i) {
    const double v = profiles_[i].speed_at(t);
    sum += v * v;
  }
  return std::sqrt(sum);
}

} // namespace ncjoule::kinematics_detail
