// What the joins (linuxcnc_blend.cpp) and the blend arcs (linuxcnc_blend_arc.cpp) share: tp.c's
// and blendmath.c's constants, and the small helpers both use. Private to the planner.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "linuxcnc_blend.hpp"

namespace ncjoule::kinematics_detail::linuxcnc {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kAngleEpsilon = 1e-6;     // TP_ANGLE_EPSILON
inline constexpr double kPosEpsilon = 1e-12;      // TP_POS_EPSILON
inline constexpr double kMinArcLength = 1e-6;     // TP_MIN_ARC_LENGTH
inline constexpr double kMinArcAngle = 1e-6;      // ARC_MIN_ANGLE (spherical blend arcs)
inline constexpr double kSharpCornerDeg = 2.0;    // tpSetupTangent: reversals stop
inline constexpr double kMinBlendCosAngle = 1e-3; // TP_MIN_ARC_ANGLE in tpComputeBlendVelocity
inline constexpr double kMaxFeedScale = 1.0;      // [DISPLAY] MAX_FEED_OVERRIDE
inline constexpr double kKinkFactor = 0.25;       // BLEND_KINK_FACTOR

// Speed the segment may reach at full feed override (tcGetMaxTargetVel).
inline double max_target_vel(const Segment& s) {
  return std::min(s.reqvel * kMaxFeedScale, s.maxvel);
}

// Half the angle between the directions (findIntersectionAngle): pi/2 straight on, 0 reversal.
inline double intersection_angle(const Vec3& u1, const Vec3& u2) {
  return std::acos(std::clamp(-u1.dot(u2), -1.0, 1.0)) / 2;
}

// The largest circle centred on the origin inside the box of per-axis bounds, cut by the plane
// with this unit normal: the limit of a vector of any direction in that plane
// (calculateInscribedDiameter).
inline double inscribed_bound(const Vec3& normal, const Vec3& bounds) {
  double result = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const double b = bounds[i];
    if (b == 0) continue;
    const double n = normal[i];
    const double scale = std::max(std::sqrt(std::max(0.0, 1 - n * n)), kPosEpsilon);
    result = std::min(result, b / scale);
  }
  return std::isfinite(result) ? result : 0.0;
}

inline bool parallel_units(const Vec3& a, const Vec3& b) {
  const Vec3 d = a - b, s = a + b;
  const double tol = kAngleEpsilon * kAngleEpsilon;
  return d.squaredNorm() < tol || s.squaredNorm() < tol;
}

inline void set_term(Segment& prev, Segment& next, Term term) {
  prev.term = term;
  next.blend_prev = term == Term::Parabolic;
}

} // namespace ncjoule::kinematics_detail::linuxcnc
