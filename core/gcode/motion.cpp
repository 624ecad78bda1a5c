// Moves: straight lines, arcs and helices, G28/G30, and the offsets that move the program's
// coordinate system (G92, G10).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "interpreter_impl.hpp"

namespace ncjoule::detail {
namespace {

double* axis_ref(Pose& p, int i) {
  double* a[6] = {&p.x, &p.y, &p.z, &p.a, &p.b, &p.c};
  return a[i];
}
double axis(const Pose& p, int i) {
  const double a[6] = {p.x, p.y, p.z, p.a, p.b, p.c};
  return a[i];
}
constexpr char kAxisLetters[6] = {'x', 'y', 'z', 'a', 'b', 'c'};

// Arc tolerances of rs274ngc (LinuxCNC 2.9, checked against its rs274), in mm: an
// arc whose radius to the end differs from its radius to the start by more than the spiral
// tolerance, both absolutely and relatively, is refused; so is any difference over 100 times the
// absolute tolerance. Radii under the radius tolerance are zero. Here a refused arc is timed as a
// spiral with a warning: the control the program was posted for may well accept it.
struct ArcTolerances {
  double radius = 0;     // mm
  double spiral_abs = 0; // mm
  double spiral_rel = 0.001;
};
// rs274ngc's constants are per unit system: 0.00005 in for radii in both, and 2 * sqrt(2) *
// 0.001 in or 2 * sqrt(2) * 0.01 mm for the spiral.
ArcTolerances arc_tolerances(bool inch) {
  if (inch) return {0.00005 * 25.4, 2 * 0.001 * std::numbers::sqrt2 * 25.4};
  return {0.00005 * 25.4, 2 * 0.01 * std::numbers::sqrt2};
}
bool radii_agree(double r1, double r2, const ArcTolerances& t) {
  const double abs_err = std::abs(r1 - r2);
  const double rel_err = abs_err / std::max(r1, r2);
  return !(abs_err > 100 * t.spiral_abs || (rel_err > t.spiral_rel && abs_err > t.spiral_abs));
}

} // namespace

Pose Interpreter::target_from_words(const BlockValues& v, bool machine_coordinates) {
  Pose end = pos_;
  if (v.has('@') || v.has('^')) {
    // LinuxCNC polar words: radius @ and angle ^ (degrees) about the origin of the XY plane;
    // under G91 they add to the current point's own radius and angle.
    const double r0 = std::hypot(pos_.x, pos_.y);
    const double a0 = std::atan2(pos_.y, pos_.x) * 180.0 / std::numbers::pi;
    double r = v.has('@') ? *v['@'] * unit() : r0;
    double a = v.has('^') ? *v['^'] : a0;
    if (incremental_) {
      r = r0 + (v.has('@') ? *v['@'] * unit() : 0.0);
      a = a0 + (v.has('^') ? *v['^'] : 0.0);
    }
    end.x = r * std::cos(a * std::numbers::pi / 180.0);
    end.y = r * std::sin(a * std::numbers::pi / 180.0);
  }
  const Pose off = offset_total();
  // Under a Sinumerik programmable frame the words are in the frame's coordinates: start from
  // the current point seen in the frame, and map the result back.
  const bool framed = !machine_coordinates && frame_active();
  const double t = frame_rotation_deg_ * std::numbers::pi / 180.0;
  if (framed) {
    const double dx = end.x - frame_shift_.x, dy = end.y - frame_shift_.y;
    end.x = dx * std::cos(t) + dy * std::sin(t);
    end.y = -dx * std::sin(t) + dy * std::cos(t);
    end.z -= frame_shift_.z;
  }
  const Pose here = end;
  for (int i = 0; i < 6; ++i) {
    const auto value = v[kAxisLetters[i]];
    if (!value) continue;
    const double scale = i < 3 ? unit() : 1.0;
    double target = *value * scale;
    if (machine_coordinates) {
      target -= axis(off, i);
      if (i == 2) target -= tool_offset_z_;
    } else if (incremental_) {
      target += axis(here, i);
    }
    if (i < 3 && (machine_coordinates || !incremental_)) axes_being_set_ |= 1u << i;
    *axis_ref(end, i) = target;
  }
  if (framed) {
    const double fx = end.x, fy = end.y;
    end.x = fx * std::cos(t) - fy * std::sin(t) + frame_shift_.x;
    end.y = fx * std::sin(t) + fy * std::cos(t) + frame_shift_.y;
    end.z += frame_shift_.z;
  }
  return end;
}

std::uint8_t Interpreter::named_axes(const BlockValues& v) {
  return std::uint8_t((v.has('x') ? 1 : 0) | (v.has('y') ? 2 : 0) | (v.has('z') ? 4 : 0));
}

void Interpreter::straight(CanonKind kind, const Pose& end, std::string text,
                           std::uint8_t machine_axes) {
  if (comp_.offsetting()) {
    if (comp_motion_ && comp_straight(kind, end, comp_column_)) return;
    if (!comp_motion_)
      comp_bypass(comp_column_, "a move compensation does not offset (canned cycle, probe, "
                                "spline, G33)");
  }
  CanonCommand c = make(kind);
  if (comp_.exit_from) c.start = *comp_.exit_from, comp_.exit_from.reset();
  c.end = end;
  c.text = std::move(text);
  c.machine_axes = machine_axes;
  pos_ = end;
  emit(std::move(c));
}

void Interpreter::inverse_time_feed(double length_mm, const BlockValues& v) {
  // Under G93 the block must take 60/F seconds: the feed in units/min is length * F. rs274
  // reports it as a feed rate before the move, and so do we.
  if (state_.feed_mode != FeedMode::InverseTime || !v.has('f')) return;
  CanonCommand c = make(CanonKind::SetFeedRate);
  c.value = length_mm / unit() * *v['f'];
  emit(std::move(c));
}

void Interpreter::spline(const BlockValues& v, bool quadratic) {
  // LinuxCNC's G5 (cubic: I J = first control point from the start, P Q = second control point
  // from the end) and G5.1 (quadratic: I J = control point from the start), in the XY plane,
  // flattened into feed moves no more than 0.01 mm off the curve.
  if (state_.plane != Plane::XY) {
    error(v.column['g' - 'a'], "G5/G5.1 splines work only in the XY plane (G17)");
    return;
  }
  note(v.column['g' - 'a'], "spline flattened into feed moves within 0.01 mm of the curve");
  const Pose end = target_from_words(v, false);
  const double u = unit();
  const double x0 = pos_.x, y0 = pos_.y, x3 = end.x, y3 = end.y;
  double cx[4] = {x0, 0, 0, x3}, cy[4] = {y0, 0, 0, y3};
  if (quadratic) {
    const double qx = x0 + v['i'].value_or(0) * u, qy = y0 + v['j'].value_or(0) * u;
    // Degree elevation of the quadratic to a cubic.
    cx[1] = x0 + 2.0 / 3 * (qx - x0), cy[1] = y0 + 2.0 / 3 * (qy - y0);
    cx[2] = x3 + 2.0 / 3 * (qx - x3), cy[2] = y3 + 2.0 / 3 * (qy - y3);
  } else {
    cx[1] = x0 + v['i'].value_or(0) * u, cy[1] = y0 + v['j'].value_or(0) * u;
    cx[2] = x3 + v['p'].value_or(0) * u, cy[2] = y3 + v['q'].value_or(0) * u;
  }
  // The second difference bounds the chord error: n segments give error <= M / (8 n^2).
  const double m = std::max(std::hypot(cx[0] - 2 * cx[1] + cx[2], cy[0] - 2 * cy[1] + cy[2]),
                            std::hypot(cx[1] - 2 * cx[2] + cx[3], cy[1] - 2 * cy[2] + cy[3]));
  const double wanted = std::ceil(std::sqrt(6 * m / (8 * 0.01)));
  const int n = wanted >= 1 ? int(std::min(wanted, 10000.0)) : 1; // NaN (huge input) gives 1
  for (int k = 1; k <= n; ++k) {
    const double t = double(k) / n, s = 1 - t;
    Pose p = pos_;
    p.x = s * s * s * cx[0] + 3 * s * s * t * cx[1] + 3 * s * t * t * cx[2] + t * t * t * cx[3];
    p.y = s * s * s * cy[0] + 3 * s * s * t * cy[1] + 3 * s * t * t * cy[2] + t * t * t * cy[3];
    p.z = pos_.z + (end.z - pos_.z) / (n - k + 1);
    if (k == n) p = end;
    straight(CanonKind::Feed, p);
  }
}

void Interpreter::probe(const Pose& end) {
  note(0, "probe move: taken to reach its target without touching anything (no probe here), "
          "and timed as a feed move");
  straight(CanonKind::Probe, end);
  // Without a real probe, the probe is taken to reach its target without tripping, as rs274
  // reports it: #5061-#5066 hold the target, #5070 is 0.
  const double p[6] = {end.x / unit(), end.y / unit(), end.z / unit(), end.a, end.b, end.c};
  for (int i = 0; i < 6; ++i)
    params_.at(5061 + i) = p[i];
  params_.at(5070) = 0;
}

void Interpreter::spindle_synced(const BlockValues& v) {
  // G33 and G33.1: the feed follows the spindle, K units per revolution.
  if (!v.has('k')) {
    error(v.column['g' - 'a'], "G33/G33.1 needs a K word (distance per revolution)");
    return;
  }
  const ModalState saved = state_;
  state_.feed_mode = FeedMode::UnitsPerRevolution;
  state_.feed = *v['k'] * unit();
  if (motion_ == Motion::SpindleSynced) {
    straight(CanonKind::Feed, target_from_words(v, false));
  } else {
    // Rigid tapping goes down to the target and comes back out to where it started.
    const Pose start = pos_;
    straight(CanonKind::Feed, target_from_words(v, false), "rigid tap");
    straight(CanonKind::Feed, start, "rigid tap retract");
  }
  const Pose here = pos_;
  state_ = saved;
  pos_ = here;
}

void Interpreter::arc(const BlockValues& v, bool clockwise) {
  // Plane axes as (first, second, normal) indices, and the offset letters of each.
  int f = 0, s = 1, n = 2;
  char fo = 'i', so = 'j';
  if (state_.plane == Plane::YZ) f = 1, s = 2, n = 0, fo = 'j', so = 'k';
  if (state_.plane == Plane::XZ) f = 2, s = 0, n = 1, fo = 'k', so = 'i';
  const Pose end = target_from_words(v, false);
  const double u = unit();
  const double sf = axis(pos_, f), ss = axis(pos_, s);
  const double ef = axis(end, f), es = axis(end, s);
  const int col = v.column['g' - 'a'];
  int turns = 1;
  if (v.has('p')) {
    const double p = *v['p'];
    if (p < 1 || std::abs(p - std::round(p)) > 1e-9) {
      error(v.column['p' - 'a'], "P (number of turns) of an arc must be a positive integer");
      return;
    }
    if (options_.max_arc_turns && p > double(options_.max_arc_turns)) {
      error(v.column['p' - 'a'],
            "P (number of turns) of an arc is more than " + std::to_string(options_.max_arc_turns));
      return;
    }
    turns = int(std::lround(p));
  }
  double cf, cs;
  if (v.has('r')) {
    const double r = *v['r'] * u;
    const double abs_r = std::abs(r);
    if (std::abs(ef - sf) < 1e-12 && std::abs(es - ss) < 1e-12) {
      error(v.column['r' - 'a'], "R-form arc with its end at its start: a full circle needs I/J/K");
      return;
    }
    const double mf = (ef + sf) / 2, ms = (es + ss) / 2;
    double half = std::hypot(mf - ef, ms - es);
    const double tol = arc_tolerances(state_.inch).radius;
    if (half - abs_r > tol) {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "arc radius R%.4f is too small to reach the end point (half the chord is "
                    "%.4f): taken as a half circle",
                    abs_r / u, half / u);
      warning(v.column['r' - 'a'], buf);
      half = abs_r;
    }
    if (half / abs_r > 1 - 1e-12) half = abs_r;
    const double base = std::atan2(es - ss, ef - sf);
    const double theta = ((clockwise && r > 0) || (!clockwise && r < 0))
                             ? base - std::numbers::pi / 2
                             : base + std::numbers::pi / 2;
    const double offset = abs_r * std::cos(std::asin(half / abs_r));
    cf = mf + offset * std::cos(theta);
    cs = ms + offset * std::sin(theta);
  } else {
    const bool have_offsets = v.has(fo) || v.has(so);
    if (!have_offsets) {
      error(col, std::string("arc needs ") + char(std::toupper(fo)) + "/" + char(std::toupper(so)) +
                     " (centre) or R (radius) words in this plane");
      return;
    }
    const double of = v[fo].value_or(0) * u, os = v[so].value_or(0) * u;
    if (!arc_incremental_) {
      // G90.1: absolute centre, in program coordinates.
      cf = v.has(fo) ? of : sf;
      cs = v.has(so) ? os : ss;
      if (!radii_agree(std::hypot(sf - cf, ss - cs), std::hypot(ef - cf, es - cs),
                       arc_tolerances(state_.inch)))
        spiral_warning(col, sf, ss, ef, es, cf, cs);
    } else {
      arc_centre_from_offsets(v, sf, ss, ef, es, of, os, cf, cs);
    }
    const double min_radius = arc_tolerances(state_.inch).radius;
    if (std::hypot(sf - cf, ss - cs) < min_radius || std::hypot(ef - cf, es - cs) < min_radius) {
      const bool point = std::hypot(end.x - pos_.x, end.y - pos_.y, end.z - pos_.z) < min_radius;
      if (point && dialect_.zero_radius_circle_is_no_motion) {
        warning(col, "arc of zero radius: no motion (" + dialect_.name +
                         " passes over it; LinuxCNC would refuse it)");
        return;
      }
      error(col, "arc of zero radius");
      return;
    }
  }
  (void)n;
  CanonCommand c = make(CanonKind::Arc);
  c.end = end;
  c.centre_first = cf;
  c.centre_second = cs;
  c.rotation = clockwise ? -turns : turns;
  inverse_time_feed(arc_geometry(c).length, v);
  if (comp_.offsetting()) {
    if (comp_motion_ && comp_arc(c, col)) return;
    if (!comp_motion_) comp_bypass(col, "an arc compensation does not offset");
  }
  if (comp_.exit_from) c.start = *comp_.exit_from, comp_.exit_from.reset();
  pos_ = end;
  emit(std::move(c));
}

void Interpreter::arc_centre_from_offsets(const BlockValues& v, double sf, double ss, double ef,
                                          double es, double of, double os, double& cf, double& cs) {
  // I/J/K are the offset from the start to the centre. Some posts write the offset from the
  // centre to the start instead: when an arc fits only that way, and no arc before fitted only
  // the standard way, the program is read that way from then on, with one warning.
  const ArcTolerances t = arc_tolerances(state_.inch);
  const int col = v.column['g' - 'a'];
  const bool normal_fits =
      radii_agree(std::hypot(of, os), std::hypot(ef - sf - of, es - ss - os), t);
  const bool reversed_fits =
      radii_agree(std::hypot(of, os), std::hypot(ef - sf + of, es - ss + os), t);
  bool reversed = false;
  if (normal_fits && !reversed_fits) {
    ++arcs_fitting_only_standard_;
  } else if (reversed_fits && !normal_fits) {
    reversed = true;
    if (!arc_offsets_reversed_) {
      arc_offsets_reversed_ = true;
      warning(col, arcs_fitting_only_standard_ == 0
                       ? "arc centres fit only with I/J/K read from the centre to the start "
                         "(centre = start - IJK), as some posts write them: this program's arcs "
                         "are read that way"
                       : "this arc fits only with I/J/K read from the centre to the start "
                         "(centre = start - IJK): read that way");
    }
  } else if (normal_fits && reversed_fits) {
    reversed = arc_offsets_reversed_ && arcs_fitting_only_standard_ == 0;
  }
  cf = reversed ? sf - of : sf + of;
  cs = reversed ? ss - os : ss + os;
  if (!normal_fits && !reversed_fits) spiral_warning(col, sf, ss, ef, es, cf, cs);
}

void Interpreter::spiral_warning(int column, double sf, double ss, double ef, double es, double cf,
                                 double cs) {
  const double u = unit();
  const double r1 = std::hypot(sf - cf, ss - cs), r2 = std::hypot(ef - cf, es - cs);
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "radius to end of arc differs from radius to start: r1=%.4f r2=%.4f (program "
                "units), beyond rs274ngc's tolerance; timed as a spiral",
                r1 / u, r2 / u);
  warning(column, buf);
}

void Interpreter::go_home(const BlockValues& v, int base) {
  // With axis words: first to the intermediate point, then those axes home. Without: all axes.
  // LinuxCNC refuses G28/G30 with compensation on.
  comp_bypass(v.g_column(base == param::kG28 ? 280 : 300), "G28/G30");
  const Pose off = offset_total();
  Pose home_prog;
  for (int i = 0; i < 6; ++i) {
    double h = params_.at(base + i) - axis(off, i);
    if (i == 2) h -= tool_offset_z_;
    *axis_ref(home_prog, i) = h;
  }
  if (v.has_axis()) {
    const Pose mid = target_from_words(v, false);
    straight(CanonKind::Traverse, mid);
    Pose end = mid;
    for (int i = 0; i < 6; ++i)
      if (v.has(kAxisLetters[i])) {
        *axis_ref(end, i) = axis(home_prog, i);
        if (i < 3) axes_being_set_ |= 1u << i; // home is a known place
      }
    straight(CanonKind::Traverse, end, {}, named_axes(v));
  } else {
    axes_being_set_ = 7;
    straight(CanonKind::Traverse, home_prog, {}, 7);
  }
}

void Interpreter::set_axis_offsets(const BlockValues& v) {
  const int code = [&] {
    for (int c : v.g)
      if (c >= 920 && c <= 923) return c;
    return 920;
  }();
  Pose old = g92_;
  if (code == 920) {
    if (!v.has_axis()) {
      error(v.g_column(920), "G92 needs at least one axis word");
      return;
    }
    for (int i = 0; i < 6; ++i) {
      const auto value = v[kAxisLetters[i]];
      if (!value) continue;
      const double target = *value * (i < 3 ? unit() : 1.0);
      *axis_ref(g92_, i) = axis(pos_, i) + axis(old, i) - target;
    }
    params_.at(param::kG92Enabled) = 1;
  } else if (code == 921 || code == 922) {
    g92_ = Pose{};
    if (code == 921) params_.at(param::kG92Enabled) = 0;
  } else if (code == 923) {
    for (int i = 0; i < 6; ++i)
      *axis_ref(g92_, i) = params_.at(param::kG92 + i);
  }
  if (code != 922)
    for (int i = 0; i < 6; ++i)
      params_.at(param::kG92 + i) = axis(g92_, i);
  for (int i = 0; i < 6; ++i)
    *axis_ref(pos_, i) += axis(old, i) - axis(g92_, i);
  CanonCommand c = make(CanonKind::AxisOffset);
  c.end = g92_;
  emit(std::move(c));
}

void Interpreter::set_coordinate_data(const BlockValues& v) {
  const long l = std::lround(*v['l']);
  if (!v.has('p')) {
    error(v.g_column(100), "G10 L" + std::to_string(l) + " needs a P word (coordinate system)");
    return;
  }
  int p = int(std::lround(*v['p']));
  if (p == 0) p = g5x_index_;
  if (p < 1 || p > 9) {
    error(v.column['p' - 'a'], "G10 P must be 0 to 9");
    return;
  }
  if (v.has('r') && std::abs(*v['r']) > 1e-12)
    warning(v.column['r' - 'a'], "G10 R (coordinate system rotation) is not modelled: ignored");
  Pose neu = g5x_[p];
  for (int i = 0; i < 6; ++i) {
    const auto value = v[kAxisLetters[i]];
    if (!value) continue;
    const double target = *value * (i < 3 ? unit() : 1.0);
    if (l == 2) {
      *axis_ref(neu, i) = target;
    } else { // L20: the current position becomes `target` in system p
      const double machine = axis(pos_, i) + axis(g5x_[g5x_index_], i) + axis(g92_, i);
      *axis_ref(neu, i) = machine - axis(g92_, i) - target;
    }
  }
  if (p == g5x_index_)
    for (int i = 0; i < 6; ++i)
      *axis_ref(pos_, i) += axis(g5x_[p], i) - axis(neu, i);
  g5x_[p] = neu;
  for (int i = 0; i < 6; ++i)
    params_.at(param::kG54 + 20 * (p - 1) + i) = axis(neu, i);
  if (p == g5x_index_) {
    CanonCommand c = make(CanonKind::WorkOffset);
    c.value = p;
    c.end = neu;
    emit(std::move(c));
  }
}

void Interpreter::set_tool_data(const BlockValues& v) {
  const long l = v.has('l') ? std::lround(*v['l']) : 0;
  if (l != 1 && l != 10 && l != 11) {
    error(v.g_column(100), "G10 L" + std::to_string(l) + " is not supported (L1, L2, L10, L20)");
    return;
  }
  if (!v.has('p')) {
    error(v.g_column(100), "G10 L" + std::to_string(l) + " needs a P word (tool number)");
    return;
  }
  const int tool = int(std::lround(*v['p']));
  ToolEntry& e = tools_[tool];
  e.number = tool;
  if (l == 1) {
    if (v.has('z')) e.z_offset = *v['z'] * unit();
  } else if (v.has('z')) {
    // L10/L11: the offset that makes the current position read Z.
    const double machine_z = pos_.z + g5x_[g5x_index_].z + g92_.z + tool_offset_z_;
    e.z_offset = machine_z - g5x_[g5x_index_].z - g92_.z - *v['z'] * unit();
  }
  if (v.has('r')) {
    e.diameter = 2 * *v['r'] * unit();
    g10_radius_tools_.insert(tool);
  }
}

} // namespace ncjoule::detail
