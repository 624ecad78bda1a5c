// Cutter radius compensation in the interpreter: G40/G41/G42 (G41.1/G42.1 with a D diameter,
// G41.2/G42.2 as wear), the entry move, corners and the exit, made as LinuxCNC's interpreter
// makes them (interp_convert.cc convert_straight_comp1/comp2, convert_arc_comp1/comp2, and the
// queue of interp_queue.cc), so that a compensated program runs here as rs274 runs it.
//
// What compensation cannot make (an entry move no longer than the radius, a concave corner the
// tool cannot reach, an arc too small for the tool inside it, G28/G53 with compensation on):
// LinuxCNC refuses the program there, and so does this interpreter when the program is in
// LinuxCNC's dialect (an error with its line and column). Other controls run many of these
// programs their own way (Fanuc and Haas start compensation over a shorter move, lift G28 out
// of it, ...): for them it is a warning, and the moves run as programmed (tool centre on the
// programmed path) from there until G40, since an estimate must not refuse a program the
// machine would run.
#include <cmath>
#include <numbers>

#include "codes.hpp"
#include "interpreter_impl.hpp"

namespace ncjoule::detail {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kHalfPi = std::numbers::pi / 2;

double direction(PlanePoint from, PlanePoint to) {
  return std::atan2(to.b - from.b, to.a - from.a);
}

} // namespace

std::optional<double> Interpreter::comp_radius_of(int number) const {
  const auto table = tools_.find(number);
  if (table != tools_.end() && g10_radius_tools_.count(number)) return table->second.diameter / 2;
  if (auto it = options_.comp_radius_mm.find(number); it != options_.comp_radius_mm.end())
    return it->second;
  if (table != tools_.end() && table->second.diameter != 0) return table->second.diameter / 2;
  return std::nullopt;
}

void Interpreter::comp_on(const BlockValues& v, int code) {
  const int column = v.g_column(code);
  const std::string name = g_name(code);
  if (comp_.on()) {
    // LinuxCNC refuses G41/G42 with compensation on; Fanuc-family controls change side or
    // offset there. Taken as a G40 and a new start.
    if (comp_strict()) {
      error(column, "cannot turn cutter radius compensation on when it is on");
      return;
    }
    comp_off(column);
    comp_.arc_not_allowed = false;
  }
  if (state_.plane == Plane::YZ) {
    const std::string what = "cutter radius compensation works only in the XY or XZ plane "
                             "(G17, G18)";
    if (comp_strict())
      error(column, what);
    else
      warning(column, what + ": the moves run as programmed");
  }
  CompSide side = code == 410 || code == 411 || code == 412 ? CompSide::Left : CompSide::Right;
  const std::optional<double> d = v['d'];
  // How the program was posted: given, the program's own word (G41.2, a CAM comment), the
  // machine's setting, else in control.
  CutterCompMode mode = CutterCompMode::Control;
  if (options_.cutter_compensation) {
    mode = *options_.cutter_compensation;
  } else if (code == 412 || code == 422) {
    mode = CutterCompMode::Wear;
  } else {
    if (!comp_hints_) comp_hints_ = scan_comp_mode_hints(source_, dialect_);
    const int d_number = d ? int(std::lround(*d)) : 0;
    if (auto hint = std::size_t(current_line_) < source_.lines.size()
                        ? comp_hints_->at(std::size_t(current_line_), d_number, state_.tool)
                        : std::nullopt)
      mode = hint->mode;
    else if (options_.default_cutter_compensation)
      mode = *options_.default_cutter_compensation;
  }
  double radius = 0;
  bool known = true;
  if (mode == CutterCompMode::Wear) {
    radius = 0; // the path is the tool centre; the D register's wear is not known here
  } else if (code == 411 || code == 421) {
    if (!d) {
      if (comp_strict()) {
        error(column, name + " with no D word");
        return;
      }
      warning(column, name + " with no D word (the tool diameter): the moves run as programmed");
    }
    radius = d ? *d * unit() / 2 : 0;
  } else {
    // D names a tool (LinuxCNC, Fanuc-family posts write D = T); none: the tool in the spindle.
    // Sinumerik's D is an edge of the tool in the spindle.
    int tool = state_.tool;
    if (d && !dialect_.sinumerik_words) {
      if (std::abs(*d - std::round(*d)) > 1e-9 || *d < 0) {
        if (comp_strict()) {
          error(v.column['d' - 'a'], name + " requires D word to be a whole number");
          return;
        }
      }
      tool = int(std::lround(*d));
    }
    if (const auto r = comp_radius_of(tool)) {
      radius = *r;
    } else {
      known = false;
      if (tool != 0) result_.comp_radius_unknown.insert(tool);
    }
  }
  (void)known;
  if (radius < 0)
    radius = -radius, side = side == CompSide::Left ? CompSide::Right : CompSide::Left;
  comp_.side = side;
  comp_.radius = radius;
  comp_.plane = state_.plane;
  comp_.first = true;
  comp_.suspended = state_.plane == Plane::YZ;
  comp_.tool = pos_;
}

void Interpreter::comp_off(int column) {
  if (comp_.offsetting() && !comp_.first) {
    // The last move ends where it was going; the next move leaves from there (the exit move).
    comp_move_end(plane_point(comp_.tool, comp_.plane), column);
    comp_.exit_from = comp_.tool;
    comp_.arc_not_allowed = true;
  }
  comp_release();
  comp_.side = CompSide::Off;
  comp_.radius = 0;
  comp_.first = true;
  comp_.suspended = false;
}

void Interpreter::comp_release() {
  comp_.queue.release([this](CanonCommand&& c) { sink_(c); });
}

bool Interpreter::comp_move_end(PlanePoint p, int column) {
  const std::string problem = comp_.queue.move_end_and_release(
      p, comp_.plane, unit(), [this](CanonCommand&& c) { sink_(c); });
  set_plane_point(comp_.tool, comp_.plane, p);
  if (problem.empty()) return true;
  comp_problem(column, problem);
  return false;
}

void Interpreter::comp_problem(int column, const std::string& what) {
  if (comp_strict())
    error(column, "cutter radius compensation: " + what);
  else
    warning(column, "cutter radius compensation: " + what +
                        " (LinuxCNC refuses this): the moves run as programmed until G40");
  comp_release();
  if (!comp_.first) comp_.exit_from = comp_.tool;
  comp_.suspended = true;
}

void Interpreter::comp_bypass(int column, const std::string& what) {
  if (!comp_.offsetting()) return;
  comp_problem(column, what + " with cutter radius compensation on");
}

void Interpreter::comp_hold(CanonCommand c, PlanePoint direction, double sweep) {
  // Through emit(), which holds every command while the queue holds one: the held move goes in
  // first, then what follows it.
  comp_next_ = CompQueue::Held{CanonCommand{}, direction, sweep};
  emit(std::move(c));
  comp_next_.reset();
}

void Interpreter::comp_hold_straight(CanonKind kind, const Pose& start, const Pose& end,
                                     PlanePoint tool_at, PlanePoint direction) {
  // The programmed end, with the tool's point in the plane: the other axes go as programmed.
  Pose tool_end = end;
  set_plane_point(tool_end, comp_.plane, tool_at);
  CanonCommand c = make(kind);
  c.start = start;
  c.end = tool_end;
  comp_.tool = tool_end;
  pos_ = end;
  comp_hold(std::move(c), direction, 0);
}

bool Interpreter::comp_straight(CanonKind kind, const Pose& end, int column) {
  const Plane plane = comp_.plane;
  const double r = comp_.radius;
  const bool left = comp_.side == CompSide::Left;
  const PlanePoint p = plane_point(end, plane), op = plane_point(pos_, plane);
  const PlanePoint cur = plane_point(comp_.tool, plane);
  if (comp_.first) {
    // The entry move (convert_straight_comp1): the tool ends a radius off the end, across the
    // move. A move with no motion in the plane cannot start compensation: LinuxCNC refuses it,
    // other controls start it on the next move in the plane.
    if (p.a == op.a && p.b == op.b && !comp_strict()) return false;
    const CompPoint e = straight_entry_end(cur, p, r, comp_.side);
    if (!e.error.empty()) {
      comp_problem(column, e.error);
      return false;
    }
    const double normal = direction(cur, p) + (left ? kHalfPi : -kHalfPi);
    comp_.queue.set_start(cur);
    const Pose start = comp_.exit_from.value_or(comp_.tool);
    comp_.exit_from.reset();
    comp_.first = false;
    comp_hold_straight(kind, start, end, e.point, {std::cos(normal), std::sin(normal)});
    return true;
  }
  // A later move (convert_straight_comp2).
  if (p.a == op.a && p.b == op.b) {
    // No motion in the plane: held with the move before it, whose end it shares.
    comp_hold_straight(kind, comp_.tool, end, cur, {0, 0});
    return true;
  }
  double theta = direction(op, cur), alpha = direction(op, p), beta = 0, gamma = 0;
  if (left) {
    if (theta < alpha) theta += 2 * kPi;
    beta = theta - alpha - kHalfPi;
    gamma = kHalfPi;
  } else {
    if (alpha < theta) alpha += 2 * kPi;
    beta = alpha - theta - kHalfPi;
    gamma = -kHalfPi;
  }
  const PlanePoint end_pt{p.a + r * std::cos(alpha + gamma), p.b + r * std::sin(alpha + gamma)};
  const PlanePoint mid{op.a + r * std::cos(alpha + gamma), op.b + r * std::sin(alpha + gamma)};
  const double small = kCornerTolerance;
  const CompQueue::Held* front = comp_.queue.front();
  const bool front_arc = front && front->command.kind == CanonKind::Arc;
  bool concave = beta < -small || beta > kPi + small;
  if (!concave && beta > kPi - small && front_arc &&
      ((!left && front->command.rotation > 0) || (left && front->command.rotation < 0)))
    concave = true;
  if (!concave && beta > small) {
    // Convex corner: the tool goes round it on an arc about the programmed corner (a traverse
    // straight to the next side for G0).
    if (!comp_move_end(cur, column)) return false;
    CanonCommand corner = make(kind == CanonKind::Traverse ? CanonKind::Traverse : CanonKind::Arc);
    corner.start = comp_.tool;
    corner.end = comp_.tool;
    set_plane_point(corner.end, plane, mid);
    corner.end.a = end.a, corner.end.b = end.b, corner.end.c = end.c;
    if (kind != CanonKind::Traverse) {
      corner.centre_first = op.a;
      corner.centre_second = op.b;
      corner.rotation = left ? -1 : 1;
    }
    comp_.tool = corner.end;
    emit(std::move(corner));
    comp_.queue.set_start(mid);
  } else if (concave) {
    // Concave corner: the move before stops where the tool touches both sides.
    PlanePoint stop;
    if (!front_arc) {
      const CompPoint q = concave_line_line(cur, theta + gamma, beta, r);
      if (!q.error.empty()) {
        comp_problem(column, q.error);
        return false;
      }
      stop = q.point;
    } else {
      const HeldArc held{plane_point(front->command.end, plane),
                         {front->command.centre_first, front->command.centre_second},
                         front->command.rotation};
      const CompPoint q = concave_arc_line(held, op, direction(op, p), r, comp_.side);
      if (!q.error.empty()) {
        comp_problem(column, q.error);
        return false;
      }
      stop = q.point;
    }
    if (!comp_move_end(stop, column)) return false;
  } else {
    comp_release();
    comp_.queue.set_start(cur);
  }
  comp_hold_straight(kind, comp_.tool, end, end_pt, {p.a - op.a, p.b - op.b});
  return true;
}

bool Interpreter::comp_arc(const CanonCommand& arc, int column) {
  const Plane plane = comp_.plane;
  const double r = comp_.radius;
  const bool left = comp_.side == CompSide::Left;
  const int turn = arc.rotation;
  const PlanePoint p = plane_point(arc.end, plane), op = plane_point(pos_, plane);
  const PlanePoint cur = plane_point(comp_.tool, plane);
  const PlanePoint centre{arc.centre_first, arc.centre_second};
  const double spiral_tolerance =
      state_.inch ? 2 * 0.001 * std::numbers::sqrt2 * 25.4 : 2 * 0.01 * std::numbers::sqrt2;
  if (comp_.first) {
    // The entry arc (convert_arc_comp1): from where the tool is to a radius off the end.
    const EntryArc e = arc_entry(cur, p, centre, turn, r, comp_.side, spiral_tolerance);
    if (!e.error.empty()) {
      comp_problem(column, e.error);
      return false;
    }
    comp_.queue.set_start(cur);
    CanonCommand c = arc;
    c.start = comp_.exit_from.value_or(comp_.tool);
    comp_.exit_from.reset();
    set_plane_point(c.end, plane, e.end);
    c.centre_first = e.centre.a;
    c.centre_second = e.centre.b;
    comp_.first = false;
    comp_.tool = c.end;
    pos_ = arc.end;
    comp_hold(std::move(c), {}, arc_sweep(cur, e.centre, turn, e.end));
    return true;
  }
  // A later arc (convert_arc_comp2).
  const double arc_radius = std::hypot(centre.a - p.a, centre.b - p.b);
  double theta = direction(op, cur);
  theta = left ? theta - kHalfPi : theta + kHalfPi;
  double delta = direction(op, centre);
  const double alpha = turn > 0 ? delta - kHalfPi : delta + kHalfPi;
  double beta = left ? theta - alpha : alpha - theta;
  beta = beta > 1.5 * kPi ? beta - 2 * kPi : beta < -kHalfPi ? beta + 2 * kPi : beta;
  const bool inside = tool_inside_arc(comp_.side, turn);
  double gamma;
  if (inside) {
    gamma = direction(p, centre);
    if (arc_radius <= r) {
      comp_problem(column, "the tool radius is not less than the arc's radius (the tool runs "
                           "inside it)");
      return false;
    }
  } else {
    gamma = direction(centre, p);
    delta += kPi;
  }
  const PlanePoint new_end{p.a + r * std::cos(gamma), p.b + r * std::sin(gamma)};
  const double small = kCornerTolerance;
  const CompQueue::Held* front = comp_.queue.front();
  const bool front_arc = front && front->command.kind == CanonKind::Arc;
  if (beta < -small || beta > kPi + small || (std::abs(beta - kPi) < small && !inside)) {
    // Concave corner.
    CompPoint q;
    if (!front_arc) {
      q = concave_line_arc(centre, arc_radius, turn, theta, beta, r, comp_.side);
    } else {
      const HeldArc held{plane_point(front->command.end, plane),
                         {front->command.centre_first, front->command.centre_second},
                         front->command.rotation};
      q = concave_arc_arc(held, centre, arc_radius, turn, r, comp_.side);
    }
    if (!q.error.empty()) {
      comp_problem(column, q.error);
      return false;
    }
    if (!comp_move_end(q.point, column)) return false;
  } else if (beta > small) {
    // Convex corner: an arc about the programmed corner first.
    const PlanePoint mid{op.a + r * std::cos(delta), op.b + r * std::sin(delta)};
    comp_release();
    CanonCommand corner = make(CanonKind::Arc);
    corner.start = comp_.tool;
    corner.end = comp_.tool;
    set_plane_point(corner.end, plane, mid);
    corner.end.a = arc.end.a, corner.end.b = arc.end.b, corner.end.c = arc.end.c;
    corner.centre_first = op.a;
    corner.centre_second = op.b;
    corner.rotation = left ? -1 : 1;
    comp_.tool = corner.end;
    emit(std::move(corner));
    comp_.queue.set_start(mid);
  } else {
    comp_release();
    comp_.queue.set_start(cur);
  }
  CanonCommand c = arc;
  c.start = comp_.tool;
  set_plane_point(c.end, plane, new_end);
  comp_.tool = c.end;
  pos_ = arc.end;
  comp_hold(std::move(c), {}, arc_sweep(op, centre, turn, p));
  return true;
}

} // namespace ncjoule::detail
