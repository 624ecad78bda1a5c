// Geometry of canonical moves: arc radius, sweep and length, and points along a move.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "ncjoule/gcode.hpp"

namespace ncjoule {
namespace {

// The plane's (first, second, normal) coordinates of a pose, in rs274's axis order:
// XY -> (x, y, z), YZ -> (y, z, x), XZ -> (z, x, y).
struct PlaneCoords {
  double first, second, normal;
};

PlaneCoords to_plane(const Pose& p, Plane plane) {
  switch (plane) {
  case Plane::XY:
    return {p.x, p.y, p.z};
  case Plane::YZ:
    return {p.y, p.z, p.x};
  case Plane::XZ:
    return {p.z, p.x, p.y};
  }
  return {p.x, p.y, p.z};
}

void from_plane(Pose& p, Plane plane, const PlaneCoords& c) {
  switch (plane) {
  case Plane::XY:
    p.x = c.first, p.y = c.second, p.z = c.normal;
    break;
  case Plane::YZ:
    p.y = c.first, p.z = c.second, p.x = c.normal;
    break;
  case Plane::XZ:
    p.z = c.first, p.x = c.second, p.y = c.normal;
    break;
  }
}

double lerp(double a, double b, double u) {
  return a + (b - a) * u;
}

} // namespace

ArcGeometry arc_geometry(const CanonCommand& arc) {
  const PlaneCoords s = to_plane(arc.start, arc.plane);
  const PlaneCoords e = to_plane(arc.end, arc.plane);
  const double cf = arc.centre_first, cs = arc.centre_second;
  ArcGeometry g;
  g.radius = std::hypot(s.first - cf, s.second - cs);
  // The angle between the radii to start and end, from their cross and dot products: accurate
  // for the smallest angles too (a 1 mm chord of a 1e13 mm radius is not a full circle).
  const double sx = s.first - cf, sy = s.second - cs, ex = e.first - cf, ey = e.second - cs;
  const double between = std::atan2(sx * ey - sy * ex, sx * ex + sy * ey); // (-pi, pi]
  const double chord = std::hypot(e.first - s.first, e.second - s.second);
  // An end point on the start is a full circle.
  const bool closed = std::abs(between) <= 1e-12 && chord <= 1e-7; // mm
  constexpr double two_pi = 2 * std::numbers::pi;
  const int turns = std::max(1, std::abs(arc.rotation));
  double sweep;
  if (arc.rotation >= 0) { // counter-clockwise: a positive sweep
    sweep = closed ? two_pi : (between > 0 ? between : between + two_pi);
    sweep += two_pi * (turns - 1);
  } else {
    sweep = closed ? -two_pi : (between < 0 ? between : between - two_pi);
    sweep -= two_pi * (turns - 1);
  }
  g.sweep = sweep;
  g.axial = e.normal - s.normal;
  g.length = std::hypot(g.radius * sweep, g.axial);
  return g;
}

void arc_bounds(const CanonCommand& arc, Pose& low, Pose& high) {
  const PlaneCoords s = to_plane(arc.start, arc.plane);
  const PlaneCoords e = to_plane(arc.end, arc.plane);
  const double cf = arc.centre_first, cs = arc.centre_second;
  // point_on_move's radius runs from the start's to the end's (a spiral), its normal coordinate
  // from the start's to the end's; each rounding stays far inside the margin.
  const double r =
      std::max(std::hypot(s.first - cf, s.second - cs), std::hypot(e.first - cf, e.second - cs));
  const double margin =
      1e-9 * (1 + std::abs(cf) + std::abs(cs) + r + std::abs(s.normal) + std::abs(e.normal));
  from_plane(low, arc.plane,
             {cf - r - margin, cs - r - margin, std::min(s.normal, e.normal) - margin});
  from_plane(high, arc.plane,
             {cf + r + margin, cs + r + margin, std::max(s.normal, e.normal) + margin});
}

Pose point_on_move(const CanonCommand& move, double u) {
  if (move.kind != CanonKind::Arc) {
    Pose p;
    p.x = lerp(move.start.x, move.end.x, u);
    p.y = lerp(move.start.y, move.end.y, u);
    p.z = lerp(move.start.z, move.end.z, u);
    p.a = lerp(move.start.a, move.end.a, u);
    p.b = lerp(move.start.b, move.end.b, u);
    p.c = lerp(move.start.c, move.end.c, u);
    return p;
  }
  const ArcGeometry g = arc_geometry(move);
  const PlaneCoords s = to_plane(move.start, move.plane);
  const PlaneCoords e = to_plane(move.end, move.plane);
  const double a0 = std::atan2(s.second - move.centre_second, s.first - move.centre_first);
  // The radius may differ slightly from start to end (within the controller's tolerance):
  // blend it linearly, as a spiral, so that both end points are hit exactly.
  const double r1 = std::hypot(e.first - move.centre_first, e.second - move.centre_second);
  const double r = lerp(g.radius, r1, u);
  const double angle = a0 + g.sweep * u;
  PlaneCoords c{move.centre_first + r * std::cos(angle), move.centre_second + r * std::sin(angle),
                lerp(s.normal, e.normal, u)};
  if (u >= 1.0) c = e;
  Pose p;
  p.a = lerp(move.start.a, move.end.a, u);
  p.b = lerp(move.start.b, move.end.b, u);
  p.c = lerp(move.start.c, move.end.c, u);
  from_plane(p, move.plane, c);
  return p;
}

double move_length(const CanonCommand& move) {
  if (move.kind == CanonKind::Arc) return arc_geometry(move).length;
  return std::sqrt((move.end.x - move.start.x) * (move.end.x - move.start.x) +
                   (move.end.y - move.start.y) * (move.end.y - move.start.y) +
                   (move.end.z - move.start.z) * (move.end.z - move.start.z));
}

std::array<double, 3> axis_travel(const CanonCommand& move) {
  auto add_step = [](std::array<double, 3>& travel, const Pose& a, const Pose& b) {
    travel[0] += std::abs(b.x - a.x);
    travel[1] += std::abs(b.y - a.y);
    travel[2] += std::abs(b.z - a.z);
  };
  std::array<double, 3> travel{};
  if (move.kind != CanonKind::Arc) {
    add_step(travel, move.start, move.end);
    return travel;
  }
  // Between two multiples of a quarter turn both in-plane coordinates are monotonic, and over a
  // whole quarter each moves by the radius (the helix axis is monotonic throughout): the partial
  // quarters at the ends are measured, the whole ones between counted, whatever P turns they
  // make. The spiral blend of a radius that differs from start to end (point_on_move) is
  // linear, so the whole quarters' mean radius is that of the first and the last crossing.
  const ArcGeometry g = arc_geometry(move);
  const PlaneCoords s = to_plane(move.start, move.plane);
  const double a0 = std::atan2(s.second - move.centre_second, s.first - move.centre_first);
  constexpr double quarter = std::numbers::pi / 2;
  const double a1 = a0 + g.sweep;
  // The first and the last quarter turn strictly inside (a0, a1), in the sweep's direction.
  const bool ccw = g.sweep > 0;
  const double first =
      ccw ? std::floor(a0 / quarter + 1) * quarter : std::ceil(a0 / quarter - 1) * quarter;
  const double last =
      ccw ? std::ceil(a1 / quarter - 1) * quarter : std::floor(a1 / quarter + 1) * quarter;
  if (g.sweep == 0 || (ccw ? first >= a1 : first <= a1)) {
    add_step(travel, move.start, move.end);
    return travel;
  }
  const double whole_quarters = std::round(std::abs(last - first) / quarter);
  const Pose p_first = point_on_move(move, (first - a0) / g.sweep);
  const Pose p_last = point_on_move(move, (last - a0) / g.sweep);
  add_step(travel, move.start, p_first);
  add_step(travel, p_last, move.end);
  auto radius = [&](const Pose& p) {
    const PlaneCoords c = to_plane(p, move.plane);
    return std::hypot(c.first - move.centre_first, c.second - move.centre_second);
  };
  const double in_plane = whole_quarters * (radius(p_first) + radius(p_last)) / 2;
  const double rise =
      std::abs(to_plane(p_last, move.plane).normal - to_plane(p_first, move.plane).normal);
  Pose between;
  from_plane(between, move.plane, {in_plane, in_plane, rise});
  travel[0] += between.x;
  travel[1] += between.y;
  travel[2] += between.z;
  return travel;
}

bool travels_in_xy(const CanonCommand& move) {
  constexpr double kMinXyMm = 1e-6;
  return move.kind == CanonKind::Arc ||
         std::hypot(move.end.x - move.start.x, move.end.y - move.start.y) > kMinXyMm;
}

} // namespace ncjoule
