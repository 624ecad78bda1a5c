// Turns the planner's timed commands (and the removal stage's step volumes) into a sequence of
// segments over which the machine's operating point changes linearly.
#include <algorithm>
#include <cmath>
#include <string>

#include "ncjoule/energy.hpp"

namespace ncjoule {
namespace {

// Below this a displacement along an axis counts as no motion (mm).
constexpr double kStillMm = 1e-9;

bool is_spindle_command(CanonKind kind) {
  return kind == CanonKind::SpindleClockwise || kind == CanonKind::SpindleCounterClockwise ||
         kind == CanonKind::SpindleSpeed || kind == CanonKind::SpindleStop;
}

double effective_rpm(const ModalState& s) {
  return s.spindle != SpindleDir::Off && s.spindle_rpm > 0 ? s.spindle_rpm : 0.0;
}

// Spindle and coolant as the command's modal state has them; nothing moves.
OperatingPoint state_point(const ModalState& s) {
  OperatingPoint op;
  op.spindle_rpm = effective_rpm(s);
  op.spindle_on = op.spindle_rpm > 0 ? 1.0 : 0.0;
  op.coolant_on = (s.mist || s.flood) ? 1.0 : 0.0;
  return op;
}

// Sets axis motion and cutting shares for a step along displacement d at path speed v, of a move
// whose axes travel `travel` in all. An axis the move travels keeps moving over a step that
// ends where it began: an arc's step across a quarter turn, where that axis turns back.
void set_motion(OperatingPoint& op, const std::array<double, 3>& d, double speed_mm_s,
                double mrr_mm3_s, const std::array<double, 3>& travel) {
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const double l1 = std::abs(d[0]) + std::abs(d[1]) + std::abs(d[2]);
  for (int i = 0; i < 3; ++i) {
    const bool moving = std::abs(d[i]) > kStillMm || travel[i] > kStillMm;
    op.axis_moving[i] = moving ? 1.0 : 0.0;
    op.axis_speed_mm_s[i] = moving && length > 0 ? speed_mm_s * std::abs(d[i]) / length : 0.0;
    op.cut_share[i] = mrr_mm3_s > 0 && l1 > 0 ? std::abs(d[i]) / l1 : 0.0;
  }
  op.mrr_mm3_s = mrr_mm3_s;
}

// The same point at another path speed along the same step: what set_motion(op, d, speed, ...)
// would give on a copy of `op` made by it for that step.
void set_speed(OperatingPoint& op, const std::array<double, 3>& d, double speed_mm_s) {
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (int i = 0; i < 3; ++i)
    op.axis_speed_mm_s[i] =
        op.axis_moving[i] > 0 && length > 0 ? speed_mm_s * std::abs(d[i]) / length : 0.0;
}

// The mean radial engagement of a step that removed `volume` at depth of cut `depth` over
// `across` mm of XY travel; 0 where the step has no depth or goes straight down.
double radial_width(double volume, double depth, double across) {
  constexpr double kLeastMm = 1e-6;
  return volume > 0 && depth > kLeastMm && across > kLeastMm ? volume / (depth * across) : 0.0;
}

std::array<double, 3> displacement(const Pose& a, const Pose& b) {
  return {b.x - a.x, b.y - a.y, b.z - a.z};
}

double norm(const std::array<double, 3>& d) {
  return std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

void add_move_segments(std::size_t index, const CanonCommand& cmd, const TimedCommand& tc,
                       const CommandRemoval* removal, const OperatingPoint& base,
                       std::vector<OperatingSegment>& out) {
  const auto& s = tc.samples;
  const auto whole = displacement(cmd.start, cmd.end);
  const auto travel = axis_travel(cmd);
  // Its two ends only (no removal asked for finer samples): their speeds are the entry and exit
  // speeds, 0 for a move from rest to rest, and a line between them would lose the cruise. The
  // mean speed over the move is exact for every term linear in speed.
  if (s.size() < 3) {
    // No samples: constant speed over the duration, the removed volume spread evenly. Each axis
    // runs at its travel over the duration: an arc's chord would leave out what its axes do in
    // between (a full circle's is zero).
    const double mrr = removal ? removal->removed_mm3 / tc.duration_s : 0.0;
    OperatingPoint op = base;
    if (norm(travel) > kStillMm) {
      set_motion(op, travel, norm(travel) / tc.duration_s, mrr, travel);
    } else {
      const double length = tc.length_mm > 0 ? tc.length_mm : norm(whole);
      set_motion(op, whole, length / tc.duration_s, mrr, travel);
    }
    out.push_back({index, tc.start_s, tc.start_s + tc.duration_s, op, op});
    return;
  }
  for (std::size_t k = 0; k + 1 < s.size(); ++k) {
    const double dt = s[k + 1].t_s - s[k].t_s;
    if (!(dt > 0)) continue;
    const auto step = displacement(s[k].position, s[k + 1].position);
    // Direction of a step too short to have its own: the move's.
    const auto& d = norm(step) <= kStillMm ? whole : step;
    double volume = 0;
    if (removal && k < removal->step_volume_mm3.size()) volume = removal->step_volume_mm3[k];
    const double mrr = std::max(0.0, volume) / dt;
    // Made in place, the end from the start: the two differ only in the speed.
    OperatingSegment& seg = out.emplace_back();
    seg.command = index;
    seg.t0_s = s[k].t_s;
    seg.t1_s = s[k + 1].t_s;
    seg.start = base;
    set_motion(seg.start, d, s[k].speed_mm_s, mrr, travel);
    seg.end = seg.start;
    set_speed(seg.end, d, s[k + 1].speed_mm_s);
    if (removal && k < removal->step_depth_mm.size()) {
      const double depth = removal->step_depth_mm[k];
      // The step's own travel across XY (not a stand-in's), where a width can come of it.
      const double across = volume > 0 && depth > 0 ? std::hypot(step[0], step[1]) : 0.0;
      seg.start.radial_width_mm = seg.end.radial_width_mm = radial_width(volume, depth, across);
    }
  }
}

} // namespace

void append_operating_segments(std::size_t index, const CanonCommand& cmd, const TimedCommand& tc,
                               const CommandRemoval* removal, double& previous_rpm,
                               std::vector<OperatingSegment>& out,
                               std::vector<Diagnostic>* diagnostics) {
  const OperatingPoint base = state_point(cmd.state);
  const double rpm = base.spindle_rpm;
  if (tc.duration_s > 0) {
    const double t0 = tc.start_s, t1 = tc.start_s + tc.duration_s;
    if (is_move(tc.kind)) {
      if (removal && !removal->step_volume_mm3.empty() && tc.samples.size() >= 2 &&
          removal->step_volume_mm3.size() != tc.samples.size() - 1 && diagnostics)
        diagnostics->push_back({Severity::Warning, "", tc.line + 1, 0,
                                "step volumes do not match the samples of this move"});
      add_move_segments(index, cmd, tc, removal, base, out);
    } else if (tc.kind == CanonKind::ChangeTool) {
      OperatingPoint op = base;
      op.spindle_on = 0; // the spindle stands while the tool is swapped
      op.spindle_rpm = 0;
      op.tool_change = 1;
      out.push_back({index, t0, t1, op, op});
    } else if (is_spindle_command(tc.kind)) {
      OperatingPoint from = base;
      from.spindle_rpm = previous_rpm;
      from.spindle_on = previous_rpm > 0 ? 1.0 : 0.0;
      out.push_back({index, t0, t1, from, base});
    } else {
      out.push_back({index, t0, t1, base, base});
    }
  }
  previous_rpm = rpm;
}

std::vector<OperatingSegment> operating_trace(const std::vector<CanonCommand>& commands,
                                              const Timeline& timeline,
                                              const RemovalResult* removal,
                                              std::vector<Diagnostic>* diagnostics) {
  auto warn = [&](int line, std::string message) {
    if (diagnostics) diagnostics->push_back({Severity::Warning, "", line + 1, 0, message});
  };
  if (removal && removal->commands.size() != timeline.commands.size()) {
    warn(0, "removal results do not match the timeline (" +
                std::to_string(removal->commands.size()) + " vs " +
                std::to_string(timeline.commands.size()) + " commands): removal ignored");
    removal = nullptr;
  }
  std::vector<OperatingSegment> trace;
  double previous_rpm = 0;
  for (std::size_t i = 0; i < timeline.commands.size(); ++i) {
    const TimedCommand& tc = timeline.commands[i];
    if (tc.command >= commands.size()) {
      warn(tc.line, "timed command refers to a command that does not exist");
      continue;
    }
    append_operating_segments(i, commands[tc.command], tc,
                              removal ? &removal->commands[i] : nullptr, previous_rpm, trace,
                              diagnostics);
  }
  return trace;
}

OperatingPoint operating_point_at(const std::vector<OperatingSegment>& trace, double t_s) {
  // First segment that ends after t.
  auto it = std::upper_bound(trace.begin(), trace.end(), t_s,
                             [](double t, const OperatingSegment& s) { return t < s.t1_s; });
  if (it == trace.end() || t_s < it->t0_s) {
    // Idle before, after, and in any gap: take the spindle and coolant of the nearest earlier
    // segment only inside the program; outside it the machine is at tare.
    if (it == trace.begin() || it == trace.end()) return OperatingPoint{};
    OperatingPoint held = std::prev(it)->end;
    held.axis_moving = {};
    held.axis_speed_mm_s = {};
    held.cut_share = {};
    held.mrr_mm3_s = 0;
    held.radial_width_mm = 0;
    held.tool_change = 0;
    return held;
  }
  const double span = it->t1_s - it->t0_s;
  const double w = span > 0 ? (t_s - it->t0_s) / span : 0.0;
  auto lerp = [w](double a, double b) { return a + (b - a) * w; };
  const OperatingPoint &a = it->start, &b = it->end;
  OperatingPoint op;
  op.spindle_on = lerp(a.spindle_on, b.spindle_on);
  op.spindle_rpm = lerp(a.spindle_rpm, b.spindle_rpm);
  op.coolant_on = lerp(a.coolant_on, b.coolant_on);
  for (int i = 0; i < 3; ++i) {
    op.axis_moving[i] = lerp(a.axis_moving[i], b.axis_moving[i]);
    op.axis_speed_mm_s[i] = lerp(a.axis_speed_mm_s[i], b.axis_speed_mm_s[i]);
    op.cut_share[i] = lerp(a.cut_share[i], b.cut_share[i]);
  }
  op.mrr_mm3_s = lerp(a.mrr_mm3_s, b.mrr_mm3_s);
  op.radial_width_mm = lerp(a.radial_width_mm, b.radial_width_mm);
  op.tool_change = lerp(a.tool_change, b.tool_change);
  return op;
}

} // namespace ncjoule
