// Canned drilling cycles (G73, G81, G82, G83, G85, G86, G89), expanded into the moves the
// machine makes, in the order LinuxCNC's interpreter makes them: rise to the R plane if below
// it, rapid over the hole, rapid down to R, the cycle's own moves, then retract to the clear
// height (the R plane under G99; under G98 the higher of R and the height the series of cycles
// began at).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "codes.hpp"
#include "interpreter_impl.hpp"

namespace ncjoule::detail {
namespace {

struct PlaneAxes {
  double Pose::*a;
  double Pose::*b;
  double Pose::*c; // the drilling axis
  char a_letter, b_letter, c_letter;
};

PlaneAxes plane_axes(Plane plane) {
  switch (plane) {
  case Plane::XY:
    return {&Pose::x, &Pose::y, &Pose::z, 'x', 'y', 'z'};
  case Plane::XZ:
    return {&Pose::z, &Pose::x, &Pose::y, 'z', 'x', 'y'};
  case Plane::YZ:
    return {&Pose::y, &Pose::z, &Pose::x, 'y', 'z', 'x'};
  }
  return {&Pose::x, &Pose::y, &Pose::z, 'x', 'y', 'z'};
}

} // namespace

void Interpreter::canned_cycle(Motion cycle, const BlockValues& v) {
  const PlaneAxes ax = plane_axes(state_.plane);
  const int col = v.column['g' - 'a'] ? v.column['g' - 'a'] : v.column[ax.a_letter - 'a'];
  const double u = unit();
  if (v.has('r')) cycle_r_ = *v['r'], have_cycle_r_ = true;
  if (v.has(ax.c_letter)) cycle_z_ = *v[ax.c_letter], have_cycle_z_ = true;
  if (v.has('q')) cycle_q_ = *v['q'];
  // A Q on a tapping block makes it peck tapping for the rest of the series; a Q left over from
  // a drilling cycle does not.
  const bool tapping = cycle == Motion::G84 || cycle == Motion::G74;
  if (tapping && v.has('q')) tap_peck_ = *v['q'];
  if (v.has('p')) cycle_p_ = *v['p'];
  if (!have_cycle_r_) {
    // Some posts drop R (FreeCAD's comparams writes only X Y Z I J F). rs274 refuses such a
    // block; here the cycle starts from where the tool is, so the program still runs.
    warning(col, "canned cycle without an R word (retract plane): R taken as the current height");
    cycle_r_ = incremental_ ? 0.0 : (pos_.*ax.c) / u;
    have_cycle_r_ = true;
  }
  if (!have_cycle_z_) {
    error(col, std::string("canned cycle without a ") + char(std::toupper(ax.c_letter)) +
                   " word (bottom of the hole): skipped");
    return;
  }
  if (state_.feed <= 0) error(col, "canned cycle with no feed rate (F word missing)");
  if (!have_cycle_initial_height_) {
    cycle_initial_height_ = pos_.*ax.c;
    have_cycle_initial_height_ = true;
  }
  // Under G98 the holes of a series are approached at, and retracted to, the series' initial
  // level; under G99 from wherever the last cycle left the tool (rs274 does the same).
  const double old_c = retract_to_r_ ? pos_.*ax.c : cycle_initial_height_;
  double r = cycle_r_ * u;
  double bottom = cycle_z_ * u;
  if (incremental_) {
    r += cycle_initial_height_; // R is relative to the height the series started from,
    bottom += r;                // the bottom relative to R.
  }
  if (r < bottom) {
    error(col, std::string("R is below ") + char(std::toupper(ax.c_letter)) +
                   " in a canned cycle: skipped");
    return;
  }
  int repeats = 1;
  if (v.has('l')) {
    const double count = std::round(*v['l']);
    // As loops are: a runaway count is refused before it runs, not after hours of it.
    const std::size_t cap = options_.max_cycle_repeats;
    if (count < 0) {
      error(v.column['l' - 'a'], "L must not be negative");
      repeats = 0;
    } else if (!(count <= (cap ? double(cap) : 2e9))) {
      error(v.column['l' - 'a'], "L" + number_text(count) + " repeats the cycle more than " +
                                     std::to_string(cap ? cap : std::size_t(2e9)) +
                                     " times: refused (runaway count?)");
      return;
    } else {
      repeats = static_cast<int>(count);
    }
  }
  double q = cycle_q_ * u;
  if ((cycle == Motion::G83 || cycle == Motion::G73) && q <= 0) {
    warning(col, "peck cycle needs a positive Q (peck depth): drilled in one go");
    q = r - bottom;
  }
  double dwell = cycle_p_;
  if (dialect_.dwell_p_in_ms) dwell /= 1000.0;
  const double clear = retract_to_r_ ? r : std::max(r, old_c);
  // Peck drilling's small moves: the machine's parameters, else its family's (mm).
  const double peck_clearance = options_.peck_clearance_mm.value_or(dialect_.peck_clearance_mm);
  const double chip_break_retract =
      options_.chip_break_retract_mm.value_or(dialect_.chip_break_retract_mm);

  auto at = [&](double a, double b, double c) {
    Pose p = pos_;
    p.*ax.a = a, p.*ax.b = b, p.*ax.c = c;
    return p;
  };
  auto traverse = [&](double a, double b, double c) { straight(CanonKind::Traverse, at(a, b, c)); };
  // A peck that is no step at R's height (Q4 at R1e117), or more pecks than a cycle may repeat,
  // would never end: refused before it runs. `step` in mm, `q_word` as the program wrote it.
  auto runaway_pecks = [&](double step, double q_word) {
    const std::size_t cap = options_.max_cycle_repeats ? options_.max_cycle_repeats : 2e9;
    if ((r - bottom) / step <= double(cap) && r - step != r) return false;
    error(v.column['q' - 'a'], "Q" + number_text(q_word) +
                                   " from R to the bottom makes more than " + std::to_string(cap) +
                                   " pecks: the cycle is refused");
    return true;
  };
  auto feed = [&](double a, double b, double c) { straight(CanonKind::Feed, at(a, b, c)); };

  double a = pos_.*ax.a, b = pos_.*ax.b;
  double hole_a = v.has(ax.a_letter) ? *v[ax.a_letter] * u : a;
  double hole_b = v.has(ax.b_letter) ? *v[ax.b_letter] * u : b;
  double step_a = 0, step_b = 0;
  if (incremental_) {
    step_a = v.has(ax.a_letter) ? *v[ax.a_letter] * u : 0;
    step_b = v.has(ax.b_letter) ? *v[ax.b_letter] * u : 0;
  }
  double height = old_c;
  if (height < r) {
    traverse(a, b, r);
    height = r;
  }
  // The cycle's own moves run in exact-path mode (G61), as LinuxCNC's interpreter runs them:
  // the path stops at every corner of the cycle. The mode in force comes back afterwards.
  const PathMode saved_mode = state_.path_mode;
  const double saved_tolerance = state_.path_tolerance;
  const bool switch_mode = saved_mode != PathMode::ExactPath;
  if (switch_mode) {
    state_.path_mode = PathMode::ExactPath;
    state_.path_tolerance = 0;
    emit_simple(CanonKind::PathControl, 0, "canned cycle");
  }
  const bool polar = state_.plane == Plane::XY && (v.has('@') || v.has('^'));
  for (int i = 0; i < repeats && !finished_; ++i) {
    if (polar) {
      // Polar hole positions (LinuxCNC): under G91 each repeat adds @ and ^ to the last hole's
      // radius and angle about the origin, e.g. a bolt circle with "G91 G81 ^60 L6".
      const double r0 = std::hypot(a, b), t0 = std::atan2(b, a) * 180.0 / std::numbers::pi;
      double r = v.has('@') ? *v['@'] * u : r0, t = v.has('^') ? *v['^'] : t0;
      if (incremental_) {
        r = r0 + (v.has('@') ? *v['@'] * u : 0.0);
        t = t0 + (v.has('^') ? *v['^'] : 0.0);
      }
      a = r * std::cos(t * std::numbers::pi / 180.0);
      b = r * std::sin(t * std::numbers::pi / 180.0);
    } else if (incremental_) {
      a += step_a;
      b += step_b;
    } else {
      a = hole_a;
      b = hole_b;
    }
    traverse(a, b, height);
    if (height != r) traverse(a, b, r);
    switch (cycle) {
    case Motion::G81:
      feed(a, b, bottom);
      traverse(a, b, clear);
      break;
    case Motion::G82:
      feed(a, b, bottom);
      emit_simple(CanonKind::Dwell, dwell);
      traverse(a, b, clear);
      break;
    case Motion::G83:
    case Motion::G73: {
      // G83 retracts to R after every peck; G73 only backs off to break the chip.
      if (runaway_pecks(q, q)) return;
      double depth = r - q;
      for (; depth > bottom && !finished_; depth -= q) {
        feed(a, b, depth);
        if (cycle == Motion::G83) traverse(a, b, r);
        traverse(a, b, depth + (cycle == Motion::G83 ? peck_clearance : chip_break_retract));
      }
      feed(a, b, bottom);
      traverse(a, b, clear);
      break;
    }
    case Motion::G85:
      feed(a, b, bottom);
      feed(a, b, r);
      if (clear > r) traverse(a, b, clear);
      break;
    case Motion::G86: {
      feed(a, b, bottom);
      emit_simple(CanonKind::Dwell, dwell);
      const SpindleDir dir = state_.spindle;
      state_.spindle = SpindleDir::Off;
      emit_simple(CanonKind::SpindleStop);
      traverse(a, b, clear);
      state_.spindle = dir;
      emit_simple(dir == SpindleDir::CounterClockwise ? CanonKind::SpindleCounterClockwise
                                                      : CanonKind::SpindleClockwise);
      break;
    }
    case Motion::G89:
      feed(a, b, bottom);
      emit_simple(CanonKind::Dwell, dwell);
      feed(a, b, clear);
      break;
    case Motion::G84:
    case Motion::G74: {
      // Tapping (Fanuc Operator's Manual, "Tapping cycle (G84)" and "Left-handed tapping cycle
      // (G74)"; Haas Mill Operator's Manual, "G84 Tapping Canned Cycle", "G74 Reverse Tap"):
      // feed down at F with the spindle turning (M3 for G84, M4 for G74), dwell P at the
      // bottom, reverse the spindle, feed back out to R, restore the spindle's direction.
      // With M29 (rigid tapping) the feed follows the spindle: the same moves at F = pitch x S.
      // Under G98 a rapid then takes the tool to the initial level.
      // With Q (peck tapping: Fanuc with parameter PCP = 1, Haas, Hurco): each peck taps Q
      // deeper from where the last ended, reverses and backs out to R, and taps back in along
      // the thread; the moves in and out of the tapped part run at the tapping feed.
      const char* how = rigid_tapping_ ? "rigid tap" : "tap";
      const SpindleDir dir =
          state_.spindle != SpindleDir::Off
              ? state_.spindle
              : (cycle == Motion::G84 ? SpindleDir::Clockwise : SpindleDir::CounterClockwise);
      const SpindleDir reversed =
          dir == SpindleDir::Clockwise ? SpindleDir::CounterClockwise : SpindleDir::Clockwise;
      auto turn = [&](SpindleDir d) {
        state_.spindle = d;
        emit_simple(d == SpindleDir::Clockwise ? CanonKind::SpindleClockwise
                                               : CanonKind::SpindleCounterClockwise);
      };
      const double peck = tap_peck_ * u;
      if (peck > 0 && runaway_pecks(peck, tap_peck_)) return;
      for (double depth = peck > 0 ? r - peck : bottom; depth > bottom && !finished_;
           depth -= peck) {
        straight(CanonKind::Feed, at(a, b, depth), std::string(how) + " peck");
        turn(reversed);
        straight(CanonKind::Feed, at(a, b, r), std::string(how) + " peck retract");
        turn(dir);
        straight(CanonKind::Feed, at(a, b, depth), std::string(how) + " peck return");
      }
      straight(CanonKind::Feed, at(a, b, bottom), how);
      if (dwell > 0) emit_simple(CanonKind::Dwell, dwell);
      turn(reversed);
      straight(CanonKind::Feed, at(a, b, r), std::string(how) + " retract");
      turn(dir);
      if (clear > r) traverse(a, b, clear);
      break;
    }
    default:
      break;
    }
    height = clear;
  }
  if (switch_mode) {
    state_.path_mode = saved_mode;
    state_.path_tolerance = saved_tolerance;
    emit_simple(CanonKind::PathControl, naivecam_tolerance_, "canned cycle");
  }
}

} // namespace ncjoule::detail
