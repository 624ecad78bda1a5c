// plan(): the planner's three passes over the command stream.
//  1. Limits of every move and timing of every other command, and the junction speed wherever
//     one move flows into the next. Under the LinuxCNC rule, linuxcnc_path.cpp builds the path
//     LinuxCNC would run instead (blend arcs, merged moves) and says which part of it each move
//     is charged with.
//  2. Look-ahead (lookahead.cpp) over the chain of moves.
//  3. A velocity profile per move (or per stretch it is charged with), the running clock, and
//     the sampled path.
#include <cmath>
#include <optional>

#include "ncjoule/log.hpp"

#include "dog_leg.hpp"
#include "junction.hpp"
#include "linuxcnc_path.hpp"
#include "lookahead.hpp"
#include "machine_events.hpp"
#include "move_limits.hpp"
#include "ncjoule/kinematics.hpp"
#include "sampling.hpp"
#include "timed_span.hpp"
#include "velocity_profile.hpp"
#include "warnings.hpp"

namespace ncjoule {
namespace {

using namespace kinematics_detail;

// How a move is timed.
enum class MoveTiming : std::uint8_t {
  NotAMove,
  Point,      // no length: zero time, at the speed the path has there
  Chained,    // part of the look-ahead chain: charged with `count` items from `item`
  RestToRest, // starts and ends at rest on its own: probes (they stop at contact)
  DogLeg,     // rapid with each axis at its own rate
};

struct MovePlan {
  MoveTiming timing = MoveTiming::NotAMove;
  std::uint16_t count = 1;  // Chained: items charged (a blend arc and the move's own segment)
  std::uint32_t item = 0;   // Chained: index of the first into the look-ahead items
  float begin = 0, end = 1; // Chained: the share of those items' length charged
};

// The speed profile of one look-ahead item once its entry and exit speeds are known. Under the
// LinuxCNC rule, a segment that lasts less than its ramp cutoff is a linear ramp between them
// (tpActivateSegment), never faster in between.
VelocityProfile item_profile(const SpeedPlanItem& item) {
  if (item.linear_ramp && item.entry + item.exit > 0 &&
      2 * item.length / (item.entry + item.exit) < linuxcnc::kRampCutoff_s)
    return VelocityProfile::ramp(item.entry, item.exit, item.length);
  return VelocityProfile::build(item.entry, item.exit, item.vmax, item.length, item.accel,
                                item.jerk);
}

double finite_or_zero(double value, int line, Warnings& warnings) {
  if (std::isfinite(value) && value >= 0) return value;
  warnings.add("invalid time", line, "the planner computed an invalid time; counted as zero",
               Severity::Error);
  return 0;
}

} // namespace

Timeline plan(const std::vector<CanonCommand>& commands, const MachineProfile& machine,
              const PlanOptions& options) {
  const Kinematics& k = machine.kinematics;
  Warnings warnings;
  Timeline timeline;
  timeline.commands.resize(commands.size());
  std::vector<MovePlan> moves(commands.size());
  std::vector<SpeedPlanItem> items;

  // Pass 1.
  const bool linuxcnc_rule = k.junction_rule == JunctionRule::LinuxCnc29;
  std::optional<linuxcnc::PathBuilder> linuxcnc_path;
  if (linuxcnc_rule)
    linuxcnc_path.emplace(k, items, [&](std::size_t command, const linuxcnc::Charge& charge) {
      moves[command] =
          MovePlan{MoveTiming::Chained, charge.count, charge.first, charge.begin, charge.end};
    });
  // LinuxCNC rule: its task takes a few ms to run each code it waits on, with the machine at
  // rest after the last move (which LinuxCNC charges with that time). Counted only once motion
  // resumes: after the last move, and before the first, its runs are not timed.
  std::vector<std::pair<std::size_t, double>> rest_after; // move index -> seconds, in order
  std::size_t last_move = commands.size();
  double waiting = 0; // task time of codes since the last move
  MachineEvents events(k);
  MoveLimits previous_limits;
  const CanonCommand* previous_move = nullptr; // last chained move, while the path flows
  for (std::size_t i = 0; i < commands.size(); ++i) {
    const CanonCommand& c = commands[i];
    TimedCommand& out = timeline.commands[i];
    out.command = i;
    out.line = c.line;
    out.kind = c.kind;
    if (!is_move(c.kind)) {
      EventTiming e = events.time(c);
      out.duration_s = finite_or_zero(e.duration_s, c.line, warnings);
      out.note = std::move(e.note);
      if (e.stops_motion) previous_move = nullptr;
      if (linuxcnc_path && linuxcnc_path->event(c)) waiting += linuxcnc::kTaskLatency_s;
      continue;
    }
    if (c.kind == CanonKind::Traverse && k.rapid_mode == RapidMode::DogLeg) {
      moves[i].timing = MoveTiming::DogLeg;
      previous_move = nullptr;
      if (linuxcnc_path) linuxcnc_path->stop();
      continue;
    }
    const MoveLimits limits = move_limits(c, k, warnings);
    if (!(limits.length > kMinMoveLength)) {
      moves[i].timing = MoveTiming::Point;
      continue;
    }
    if (c.kind == CanonKind::Probe) {
      moves[i].timing = MoveTiming::RestToRest;
      previous_move = nullptr;
      if (linuxcnc_path) linuxcnc_path->stop();
      continue;
    }
    if (linuxcnc_path) {
      moves[i].timing = MoveTiming::Chained; // its charge arrives once its segment is settled
      moves[i].count = 0;
      linuxcnc_path->move(i, c);
      if (waiting > 0 && last_move < commands.size()) rest_after.emplace_back(last_move, waiting);
      waiting = 0;
      last_move = i;
      continue;
    }
    if (previous_move)
      items.back().junction_after =
          junction_speed(previous_limits, limits, previous_move->state.path_mode,
                         previous_move->state.path_tolerance, k);
    moves[i] = MovePlan{MoveTiming::Chained, 1, static_cast<std::uint32_t>(items.size())};
    items.push_back(SpeedPlanItem{limits.length, limits.vmax, limits.accel, limits.jerk});
    previous_limits = limits;
    previous_move = &c;
  }
  if (linuxcnc_path) linuxcnc_path->finish();

  // Pass 2.
  plan_speeds(items);

  // Pass 3.
  std::size_t next_rest = 0;
  double clock = 0;
  double path_speed = 0; // speed of the path at the current point (for zero-length moves)
  for (std::size_t i = 0; i < commands.size(); ++i) {
    const CanonCommand& c = commands[i];
    TimedCommand& out = timeline.commands[i];
    out.start_s = clock;
    switch (moves[i].timing) {
    case MoveTiming::NotAMove:
      if (out.duration_s > 0 || c.kind == CanonKind::ProgramStop ||
          c.kind == CanonKind::OptionalStop || c.kind == CanonKind::ProgramEnd)
        path_speed = 0;
      break;
    case MoveTiming::Point: {
      out.entry_speed_mm_s = out.exit_speed_mm_s = out.peak_speed_mm_s = path_speed;
      const TimedSpan still(VelocityProfile::build(path_speed, path_speed, 0, 0, 1, 0));
      sample_move(c, still, 0, clock, options, out.samples);
      break;
    }
    case MoveTiming::Chained: {
      const MovePlan& plan = moves[i];
      TimedSpan span;
      for (std::uint32_t j = 0; j < plan.count; ++j)
        span.add(item_profile(items[plan.item + j]));
      if (plan.count == 0) // run as part of the next move's blend arc
        span.add(VelocityProfile::build(path_speed, path_speed, 0, 0, 1, 0));
      if (plan.begin > 0 || plan.end < 1) span.restrict(plan.begin, plan.end);
      out.duration_s = finite_or_zero(span.duration(), c.line, warnings);
      out.length_mm = move_length(c);
      out.entry_speed_mm_s = span.entry_speed();
      out.exit_speed_mm_s = span.exit_speed();
      out.peak_speed_mm_s = span.peak_speed();
      sample_move(c, span, out.length_mm, clock, options, out.samples);
      path_speed = out.exit_speed_mm_s;
      if (next_rest < rest_after.size() && rest_after[next_rest].first == i) {
        // The codes after this move run with the machine at rest (LinuxCNC rule).
        out.duration_s += rest_after[next_rest++].second;
        out.samples.push_back(MotionSample{clock + out.duration_s, 1.0, c.end, 0.0});
      }
      break;
    }
    case MoveTiming::RestToRest: {
      const MoveLimits limits = move_limits(c, k, warnings);
      const VelocityProfile profile =
          VelocityProfile::rest_to_rest(limits.vmax, limits.length, limits.accel, limits.jerk);
      out.duration_s = finite_or_zero(profile.duration(), c.line, warnings);
      out.length_mm = limits.rotary_only ? 0 : limits.length;
      out.peak_speed_mm_s = profile.peak_speed();
      sample_move(c, TimedSpan(profile), out.length_mm, clock, options, out.samples);
      path_speed = 0;
      break;
    }
    case MoveTiming::DogLeg: {
      const DogLegMove dog_leg(c, k);
      out.duration_s = finite_or_zero(dog_leg.duration(), c.line, warnings);
      out.length_mm = move_length(c);
      out.peak_speed_mm_s = dog_leg.peak_speed();
      sample_dog_leg(c, dog_leg, clock, options, out.samples);
      path_speed = 0;
      break;
    }
    }
    clock += out.duration_s;
  }
  timeline.total_s = clock;
  timeline.diagnostics = warnings.take();
  logger().debug("planned {} commands ({} chained moves): {:.3f} s", commands.size(), items.size(),
                 clock);
  return timeline;
}

} // namespace ncjoule
