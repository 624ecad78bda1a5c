// The geometry of cutter radius compensation and the queue of held moves (cutter_comp.hpp).
// Each construction is the one LinuxCNC's interpreter makes (interp_convert.cc, interp_queue.cc),
// so that a compensated program runs here as rs274 runs it.
#include "cutter_comp.hpp"

#include <cmath>
#include <numbers>

namespace ncjoule::detail {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kHalfPi = std::numbers::pi / 2;

PlanePoint along(PlanePoint from, double length, double angle) {
  return {from.a + length * std::cos(angle), from.b + length * std::sin(angle)};
}
double direction(PlanePoint from, PlanePoint to) {
  return std::atan2(to.b - from.b, to.a - from.a);
}
double distance(PlanePoint p, PlanePoint q) {
  return std::hypot(q.a - p.a, q.b - p.b);
}

const char* kGouge = "the tool cannot reach it without gouging";

} // namespace

PlanePoint plane_point(const Pose& p, Plane plane) {
  switch (plane) {
  case Plane::XZ:
    return {p.z, p.x};
  case Plane::YZ:
    return {p.y, p.z};
  case Plane::XY:
    break;
  }
  return {p.x, p.y};
}

void set_plane_point(Pose& p, Plane plane, PlanePoint q) {
  switch (plane) {
  case Plane::XZ:
    p.z = q.a, p.x = q.b;
    return;
  case Plane::YZ:
    p.y = q.a, p.z = q.b;
    return;
  case Plane::XY:
    break;
  }
  p.x = q.a, p.y = q.b;
}

double arc_sweep(PlanePoint start, PlanePoint centre, int turn, PlanePoint end) {
  if (turn == 0) return 0;
  double from = direction(centre, start), to = direction(centre, end);
  if (turn > 0) {
    if (to <= from) to += 2 * kPi;
    return to - from + (turn - 1) * 2 * kPi;
  }
  if (from <= to) from += 2 * kPi;
  return to - from + (turn + 1) * 2 * kPi;
}

CompPoint straight_entry_end(PlanePoint start, PlanePoint end, double radius, CompSide side) {
  if (distance(start, end) <= radius)
    return {{},
            "the entry move is not longer than the tool radius: no room to turn compensation "
            "on"};
  const double normal = direction(start, end) + (side == CompSide::Left ? kHalfPi : -kHalfPi);
  return {along(end, radius, normal), {}};
}

EntryArc arc_entry(PlanePoint start, PlanePoint end, PlanePoint centre, int turn, double radius,
                   CompSide side, double spiral_tolerance) {
  EntryArc out;
  if (distance(start, end) <= radius) {
    out.error = "the entry arc's chord is not longer than the tool radius: no room to turn "
                "compensation on";
    return out;
  }
  const bool inside = tool_inside_arc(side, turn);
  if (inside && distance(centre, start) <= radius) {
    out.error = "the tool radius is not less than the arc's radius (the tool runs inside it)";
    return out;
  }
  // The tool ends a radius off the programmed end, toward the centre when it runs inside.
  const double gamma = inside ? direction(end, centre) : direction(centre, end);
  out.end = along(end, radius, gamma);
  // The arc the tool takes passes through where it is and where it ends, its centre on the line
  // from its end toward the programmed centre.
  const double half_chord = distance(start, out.end) / 2;
  const double to_centre = direction(out.end, centre);
  const double corner = direction(out.end, start) - to_centre;
  if (std::abs(std::cos(corner)) < 1e-4) {
    out.error = "the tool radius is not less than the arc's radius";
    return out;
  }
  out.centre = along(out.end, half_chord / std::cos(corner), to_centre);
  if (std::abs(distance(out.centre, out.end) - distance(out.centre, start)) > spiral_tolerance)
    out.error = "the entry arc came out with two radii";
  return out;
}

CompPoint concave_line_line(PlanePoint tool, double back, double beta, double radius) {
  const double half_corner = (beta + kPi) / 2;
  if (half_corner == 0) return {{}, "a corner of zero degrees has no inside for the tool"};
  return {along(tool, radius / std::tan(half_corner), back), {}};
}

CompPoint concave_arc_line(const HeldArc& arc, PlanePoint from, double line_direction,
                           double radius, CompSide side) {
  const double arc_radius = distance(arc.centre, arc.end); // compensated
  const double normal = arc.turn > 0 ? line_direction + kHalfPi : line_direction - kHalfPi;
  const bool inside = tool_inside_arc(side, arc.turn);
  const double programmed_radius = inside ? arc_radius + radius : arc_radius - radius;
  // Distance of the arc's centre from the line, then from the tool's path along it.
  const double d = programmed_radius * std::cos(normal - direction(from, arc.centre));
  const double l = (inside ? d - radius : d + radius) / arc_radius;
  if (l > 1 || l < -1) return {{}, std::string("an arc then a straight make a corner ") + kGouge};
  const double swing = (arc.turn > 0) == inside ? -std::acos(l) : std::acos(l);
  return {along(arc.centre, arc_radius, normal + kPi + swing), {}};
}

CompPoint concave_line_arc(PlanePoint centre, double arc_radius, int turn, double theta,
                           double beta, double radius, CompSide side) {
  const double across = arc_radius * std::sin(beta - kHalfPi);
  const bool inside = tool_inside_arc(side, turn);
  const double from_centre = inside ? arc_radius - radius : arc_radius + radius;
  const double l = (inside ? across + radius : across - radius) / from_centre;
  if (l > 1 || l < -1) return {{}, std::string("a straight then an arc make a corner ") + kGouge};
  double angle;
  if (inside)
    angle = turn > 0 ? theta + std::asin(l) : theta - std::asin(l);
  else
    angle = turn > 0 ? theta + kPi - std::asin(l) : theta + kPi + std::asin(l);
  return {along(centre, from_centre, angle), {}};
}

CompPoint concave_arc_arc(const HeldArc& previous, PlanePoint centre, double arc_radius, int turn,
                          double radius, CompSide side) {
  const double old_radius = distance(previous.centre, previous.end);
  const double new_radius = tool_inside_arc(side, turn) ? arc_radius - radius : arc_radius + radius;
  const double centres = distance(previous.centre, centre);
  if (old_radius == 0 || centres == 0) return {{}, "two arcs about the same centre meet"};
  // The two compensated circles cross where the triangle of their radii and centres closes.
  const double c = (old_radius * old_radius + centres * centres - new_radius * new_radius) /
                   (2 * old_radius * centres);
  if (c > 1 || c < -1) return {{}, std::string("two arcs make a corner ") + kGouge};
  const double pullback = std::acos(c);
  const bool plus = tool_inside_arc(side, previous.turn) == (turn > 0);
  const double angle = direction(previous.centre, centre) + (plus ? pullback : -pullback);
  return {along(previous.centre, old_radius, angle), {}};
}

void CompQueue::release(const Release& out) {
  for (Held& item : items_)
    out(std::move(item.command));
  items_.clear();
  start_known_ = false;
}

std::string CompQueue::move_end_and_release(PlanePoint p, Plane plane, double unit,
                                            const Release& out) {
  if (items_.empty()) return {};
  std::string problem;
  std::optional<Pose> previous_end;
  for (Held& item : items_) {
    CanonCommand& c = item.command;
    if (!is_move(c.kind)) continue;
    if (previous_end) c.start = *previous_end;
    if (c.kind == CanonKind::Arc) {
      const PlanePoint centre{c.centre_first, c.centre_second};
      const double r1 = distance(centre, plane_point(c.end, plane));
      const double r2 = distance(centre, p);
      const double sweep = arc_sweep(start_, centre, c.rotation, p);
      if (std::abs(r1 - r2) > 0.01 * unit && problem.empty())
        problem = "an arc's end moved off its circle";
      if (item.sweep != 0 && start_known_ &&
          std::abs(sweep) > std::abs(item.sweep) + (unit > 1 ? 0.001 : 0.0254) && problem.empty())
        problem = std::string("an arc move in a concave corner: ") + kGouge;
    } else {
      const PlanePoint end = p;
      const double dot =
          item.direction.a * (end.a - start_.a) + item.direction.b * (end.b - start_.b);
      if (start_known_ && dot < 0 && problem.empty())
        problem =
            std::string(c.kind == CanonKind::Traverse ? "a straight traverse" : "a straight feed") +
            " in a concave corner would turn back: " + kGouge;
    }
    set_plane_point(c.end, plane, p);
    previous_end = c.end;
  }
  release(out);
  set_start(p);
  return problem;
}

} // namespace ncjoule::detail
