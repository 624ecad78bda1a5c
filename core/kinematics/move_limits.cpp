#include "move_limits.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

namespace ncjoule::kinematics_detail {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Direction components below this are treated as "the axis does not move".
constexpr double kNegligible = 1e-12;
// The slowest programmed speed a move is timed at (mm/s, or deg/s). The interpreter bounds F
// and every length, but G95 multiplies F by any spindle speed the program gives (S0.000001):
// below this a move could take longer than a double holds, and sums of times become infinite.
constexpr double kSlowestSpeed = 1e-9;

// The limits one move has to respect, gathered as caps and lowered one axis at a time.
struct Caps {
  double speed = kInfinity, accel = kInfinity, jerk = kInfinity;

  // An axis that moves `share` units per unit of path: its own limits divided by the share.
  void axis(double share, double axis_speed, double axis_accel, double axis_jerk) {
    share = std::abs(share);
    if (share <= kNegligible) return;
    speed = std::min(speed, axis_speed / share);
    accel = std::min(accel, axis_accel / share);
    if (axis_jerk > 0) jerk = std::min(jerk, axis_jerk / share);
  }
};

double axis_speed_limit(const AxisLimits& a, bool rapid) {
  return rapid ? a.rapid_mm_s : a.max_feed_mm_s;
}

Vec3 normalised(Vec3 v) {
  const double n = v.norm();
  if (n <= 0) return Vec3::Zero();
  return v / n;
}

// Plane axes as indices into (x, y, z): first, second and normal, as in arc_geometry.
std::array<int, 3> plane_axes(Plane plane) {
  switch (plane) {
  case Plane::XY:
    return {0, 1, 2};
  case Plane::YZ:
    return {1, 2, 0};
  case Plane::XZ:
    return {2, 0, 1};
  }
  return {0, 1, 2};
}

double component(const Pose& p, int axis) {
  return axis == 0 ? p.x : axis == 1 ? p.y : p.z;
}
// Tangent of an arc at angle phi around its centre: d(point)/d(sweep fraction).
Vec3 arc_tangent(const CanonCommand& arc, const ArcGeometry& g, double phi) {
  const auto [first, second, normal] = plane_axes(arc.plane);
  Vec3 t = Vec3::Zero();
  t[first] = -g.radius * g.sweep * std::sin(phi);
  t[second] = g.radius * g.sweep * std::cos(phi);
  t[normal] = g.axial;
  return normalised(t);
}

// The programmed path speed of a feed move (mm/s, or deg/s for rotary-only moves), before the
// machine's caps; <= 0 when the program gives none that can be used.
double programmed_speed(const CanonCommand& move, double length, Warnings& warnings) {
  const ModalState& s = move.state;
  switch (s.feed_mode) {
  case FeedMode::UnitsPerMinute:
    return s.feed / 60.0;
  case FeedMode::InverseTime:
    return length * s.feed / 60.0; // the move takes 60/F s at speed
  case FeedMode::UnitsPerRevolution:
    if (s.spindle == SpindleDir::Off || s.spindle_rpm <= 0) {
      warnings.add("G95 feed per revolution with the spindle stopped", move.line,
                   "G95 feed per revolution with the spindle stopped: timed at the maximum feed");
      return 0;
    }
    return s.feed * s.spindle_rpm / 60.0;
  }
  return 0;
}

void rotary_caps(Caps& caps, const CanonCommand& move, const Kinematics& k, double per_length,
                 Warnings& warnings) {
  const std::array<double, 3> deltas{move.end.a - move.start.a, move.end.b - move.start.b,
                                     move.end.c - move.start.c};
  for (double d : deltas) {
    if (std::abs(d) <= kNegligible) continue;
    if (k.rotary_rapid_deg_s <= 0 || k.rotary_accel_deg_s2 <= 0) {
      warnings.add_once(
          "rotary axis without limits", move.line,
          "the machine profile has no rotary axis limits: A/B/C motion is not limited");
      return;
    }
    caps.axis(d * per_length, k.rotary_rapid_deg_s, k.rotary_accel_deg_s2, 0);
  }
}

} // namespace

MoveLimits move_limits(const CanonCommand& move, const Kinematics& k, Warnings& warnings) {
  MoveLimits m;
  const bool rapid = move.kind == CanonKind::Traverse;
  m.traverse = rapid;
  const bool s_curve = k.feed_profile == FeedProfile::SCurve;
  Caps caps;
  // The path speed the linear axes' max feeds allow (mm/s), before acceleration caps: what a
  // control clamps a programmed feed to.
  double axes_speed = std::numeric_limits<double>::infinity();
  auto axis = [&](int i, double share) {
    const AxisLimits& a = k.axes[i];
    caps.axis(share, axis_speed_limit(a, rapid), a.accel_mm_s2, s_curve ? a.jerk_mm_s3 : 0);
  };

  if (move.kind == CanonKind::Arc) {
    const ArcGeometry g = arc_geometry(move);
    m.length = g.length;
    if (!(m.length > kMinMoveLength)) return MoveLimits{};
    const auto [first, second, normal] = plane_axes(move.plane);
    // The in-plane speed is the path speed times r*theta/L; each in-plane axis carries all of
    // it at some point of a sweep through its direction, so both are held to it.
    const double in_plane = std::abs(g.radius * g.sweep) / m.length;
    axis(first, in_plane);
    axis(second, in_plane);
    axis(normal, g.axial / m.length);
    axes_speed = caps.speed;
    // Centripetal acceleration (v * in_plane)^2 / r within the slower in-plane axis, and within
    // what the control allows on arcs where the profile says so.
    if (in_plane > kNegligible && g.radius > 0) {
      const double a_plane =
          std::min({k.axes[first].accel_mm_s2, k.axes[second].accel_mm_s2,
                    k.arc_accel_mm_s2.value_or(std::numeric_limits<double>::infinity())});
      caps.speed = std::min(caps.speed, std::sqrt(a_plane * g.radius) / in_plane);
    }
    const double phi0 = std::atan2(component(move.start, second) - move.centre_second,
                                   component(move.start, first) - move.centre_first);
    m.dir_in = arc_tangent(move, g, phi0);
    m.dir_out = arc_tangent(move, g, phi0 + g.sweep);
  } else {
    const Vec3 d(move.end.x - move.start.x, move.end.y - move.start.y, move.end.z - move.start.z);
    m.length = d.norm();
    if (m.length > kMinMoveLength) {
      m.dir_in = m.dir_out = d / m.length;
      for (int i = 0; i < 3; ++i)
        axis(i, m.dir_in[i]);
      axes_speed = caps.speed;
    } else {
      // Rotary axes only: the path is measured in degrees, as LinuxCNC does.
      const double da = move.end.a - move.start.a, db = move.end.b - move.start.b,
                   dc = move.end.c - move.start.c;
      m.length = std::sqrt(da * da + db * db + dc * dc);
      if (!(m.length > kMinMoveLength)) return MoveLimits{};
      m.rotary_only = true;
    }
  }
  rotary_caps(caps, move, k, 1.0 / m.length, warnings);

  // Rotary-only moves on a machine without rotary limits: fall back to the X axis's limits
  // (already warned about) so that the move still takes a finite, non-zero time.
  const AxisLimits& fallback = k.axes[0];
  if (!std::isfinite(caps.speed)) caps.speed = axis_speed_limit(fallback, rapid);
  if (!std::isfinite(caps.accel)) caps.accel = fallback.accel_mm_s2;
  m.jerk = std::isfinite(caps.jerk) ? caps.jerk : 0;
  m.accel = caps.accel;
  m.vmax = m.vmax_machine = caps.speed;
  if (!rapid) {
    double programmed = programmed_speed(move, m.length, warnings);
    if (programmed > 0 && programmed < kSlowestSpeed) {
      warnings.add("feed slower than 1e-9 mm/s", move.line,
                   "feed slower than 0.000000001 mm/s: timed at that speed");
      programmed = kSlowestSpeed;
    }
    if (programmed > 0 && std::isfinite(programmed)) {
      if (k.placeholder_rates && programmed > m.vmax_machine * (1 + 1e-9)) {
        char text[320];
        std::snprintf(text, sizeof text,
                      "the program feeds at %.0f mm/min here (the first such block), above this "
                      "profile's %.0f "
                      "mm/min; its rates are placeholders (its source gives no kinematics), not "
                      "the machine's: the time is counted at them and is no prediction; use a "
                      "profile of the machine the program was made for",
                      programmed * 60, m.vmax_machine * 60);
        warnings.add_once("feed above placeholder rates", move.line, text);
      } else if (std::isfinite(axes_speed) && programmed > axes_speed * (1 + 1e-6)) {
        // The control clamps the feed to what the axes allow; the time counts at that feed.
        char text[320];
        std::snprintf(text, sizeof text,
                      "the feed asked for here (%.0f mm/min) is above what the machine allows "
                      "on this path (%.0f mm/min, from the profile's max_feed per axis): the "
                      "control clamps it, and the time is counted at %.0f mm/min",
                      programmed * 60, axes_speed * 60, axes_speed * 60);
        warnings.add_counted("feed clamped", move.line, text);
      }
      m.vmax = std::min(m.vmax, programmed);
    } else if (move.state.feed_mode != FeedMode::UnitsPerRevolution) {
      warnings.add("feed move without a feed rate", move.line,
                   "feed move without a usable feed rate (F0): timed at the maximum feed");
    }
  }
  return m;
}

} // namespace ncjoule::kinematics_detail
