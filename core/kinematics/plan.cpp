// plan(): the planner's three passes over the command stream.
//  1. Limits of every move and timing of every other command, and the junction speed wherever
//     one move flows into the next.
//  2. Look-ahead (lookahead.cpp) over the chain of moves.
//  3. A velocity profile per move, the running clock, and the sampled path.
#include <cmath>
#include "ncjoule/log.hpp"

#include "dog_leg.hpp"
#include "junction.hpp"
#include "lookahead.hpp"
#include "machine_events.hpp"
#include "move_limits.hpp"
#include "ncjoule/kinematics.hpp"
#include "sampling.hpp"
#include "velocity_profile.hpp"
#include "warnings.hpp"

namespace ncjoule {
namespace {

using namespace kinematics_detail;

// How a move is timed.
enum class MoveTiming : std::uint8_t {
  NotAMove,
  Point,      // no length: zero time, at the speed the path has there
  Chained,    // part of the look-ahead chain
  RestToRest, // starts and ends at rest on its own: probes (they stop at contact)
  DogLeg,     // rapid with each axis at its own rate
};

struct MovePlan {
  MoveTiming timing = MoveTiming::NotAMove;
  std::uint32_t item = 0; // index into the look-ahead items (Chained)
};

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
  std::vector<bool> item_rotary_only;

  // Pass 1.
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
      continue;
    }
    if (c.kind == CanonKind::Traverse && k.rapid_mode == RapidMode::DogLeg) {
      moves[i].timing = MoveTiming::DogLeg;
      previous_move = nullptr;
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
      continue;
    }
    if (previous_move)
      items.back().junction_after =
          junction_speed(previous_limits, limits, previous_move->state.path_mode,
                         previous_move->state.path_tolerance, k);
    moves[i] = MovePlan{MoveTiming::Chained, static_cast<std::uint32_t>(items.size())};
    items.push_back(SpeedPlanItem{limits.length, limits.vmax, limits.accel, limits.jerk});
    item_rotary_only.push_back(limits.rotary_only);
    previous_limits = limits;
    previous_move = &c;
  }

  // Pass 2.
  plan_speeds(items);

  // Pass 3.
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
      const VelocityProfile still = VelocityProfile::build(path_speed, path_speed, 0, 0, 1, 0);
      sample_move(c, still, 0, clock, options, out.samples);
      break;
    }
    case MoveTiming::Chained: {
      const SpeedPlanItem& item = items[moves[i].item];
      const VelocityProfile profile = VelocityProfile::build(item.entry, item.exit, item.vmax,
                                                             item.length, item.accel, item.jerk);
      const bool rotary_only = item_rotary_only[moves[i].item];
      out.duration_s = finite_or_zero(profile.duration(), c.line, warnings);
      out.length_mm = rotary_only ? 0 : item.length;
      out.entry_speed_mm_s = profile.entry_speed();
      out.exit_speed_mm_s = profile.exit_speed();
      out.peak_speed_mm_s = profile.peak_speed();
      sample_move(c, profile, out.length_mm, clock, options, out.samples);
      path_speed = out.exit_speed_mm_s;
      break;
    }
    case MoveTiming::RestToRest: {
      const MoveLimits limits = move_limits(c, k, warnings);
      const VelocityProfile profile =
          VelocityProfile::rest_to_rest(limits.vmax, limits.length, limits.accel, limits.jerk);
      out.duration_s = finite_or_zero(profile.duration(), c.line, warnings);
      out.length_mm = limits.rotary_only ? 0 : limits.length;
      out.peak_speed_mm_s = profile.peak_speed();
      sample_move(c, profile, out.length_mm, clock, options, out.samples);
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
