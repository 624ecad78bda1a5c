// The planner, as a stream of commands in and timed commands out, in three steps:
//  1. As a command arrives: the limits of a move and the junction speed wherever one move flows
//     into the next (under the LinuxCNC rule, linuxcnc_path.cpp builds the path LinuxCNC would
//     run instead, blend arcs and merged moves, and says which part of it each move is charged
//     with), or the timing of any other command.
//  2. Look-ahead (lookahead.cpp) over the moves waiting, which makes their speeds final up to
//     the last point whose speed nothing later can change.
//  3. For each command in turn, once its speeds are final: a velocity profile (or one per
//     stretch it is charged with), the running clock and the sampled path; then it goes out.
// Memory holds the commands and items between the last timed command and the newest one.
#include <algorithm>
#include <cmath>
#include <deque>
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
#include "slot_queue.hpp"
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
  std::uint32_t item = 0;   // Chained: number of the first look-ahead item charged
  float begin = 0, end = 1; // Chained: the share of those items' length charged
  bool charged = true;      // Chained: false until the LinuxCNC path has said what it is charged
};

// A command between arriving and going out timed.
struct WaitingCommand {
  CanonCommand command;
  TimedCommand timed;
  MovePlan plan;
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

struct Planner::Impl {
  Impl(const MachineProfile& machine, const PlanOptions& options, Sink sink);

  void add(const CanonCommand& c);
  double finish();

  void limit_and_chain(WaitingCommand& w);
  void come_to_rest();
  void look_ahead(bool at_end);
  bool ready(const WaitingCommand& w) const;
  void time(WaitingCommand& w);
  void settle(const CanonCommand& c, TimedCommand& out) const;
  void send_ready();

  const Kinematics& k;
  PlanOptions options;
  Sink sink;
  Warnings warnings;
  ItemWindow items;
  SpeedPlanFront front;
  std::size_t batch;           // options.look_ahead_batch, at least 1
  std::size_t next_look_ahead; // pending items at which to look ahead again
  SlotQueue<WaitingCommand> waiting;
  std::size_t first_waiting = 0; // number of the command at the front of `waiting`
  std::size_t next_number = 0;   // number the next command gets
  bool finished = false;
  std::optional<linuxcnc::PathBuilder> linuxcnc_path;
  // LinuxCNC rule: its task takes a few ms to run each code it waits on, with the machine at
  // rest after the last move (which LinuxCNC charges with that time). Counted only once motion
  // resumes: after the last move, and before the first, its runs are not timed.
  std::deque<std::pair<std::size_t, double>> rest_after; // move number -> seconds, in order
  std::size_t last_move = kNone;
  double task_waiting = 0; // task time of codes since the last move
  MachineEvents events;
  MoveLimits previous_limits;
  bool previous_flows = false; // the last chained move flows into the next one
  std::size_t off_path = 0;    // commands since the last chained move
  PathMode previous_mode = PathMode::ExactPath;
  double previous_tolerance = 0;
  double lookahead_mm = 0; // length of the last k.lookahead_blocks items (the control's view)
  // Step 3's running state.
  double clock = 0;
  double path_speed = 0; // speed of the path at the current point (for zero-length moves)
  Planner::Work work;
  std::vector<std::vector<MotionSample>> spare_samples; // reuse_samples(): memory for samples

  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
};

Planner::Impl::Impl(const MachineProfile& machine, const PlanOptions& o, Sink s)
    : k(machine.kinematics), options(o), sink(std::move(s)),
      batch(std::max<std::size_t>(o.look_ahead_batch, 1)), next_look_ahead(batch),
      events(machine.kinematics) {
  if (k.junction_rule == JunctionRule::LinuxCnc29)
    linuxcnc_path.emplace(k, items, [this](std::size_t command, const linuxcnc::Charge& charge) {
      // at(): a charge for a command already sent would be a fault of the path builder; it
      // throws (the estimate fails with an error) rather than write where the command was.
      waiting.at(command - first_waiting).plan =
          MovePlan{MoveTiming::Chained, charge.count, charge.first, charge.begin, charge.end, true};
    });
}

void Planner::Impl::add(const CanonCommand& c) {
  WaitingCommand& w = waiting.push_back(WaitingCommand{c, TimedCommand{}, MovePlan{}});
  w.timed.command = next_number++;
  w.timed.line = c.line;
  w.timed.kind = c.kind;
  limit_and_chain(w);
  off_path = w.plan.timing == MoveTiming::Chained ? 0 : off_path + 1;
  if (options.max_commands_off_path && off_path == options.max_commands_off_path) come_to_rest();
  if (!options.look_ahead_whole_program && items.size() - front.final_items >= next_look_ahead) {
    const std::size_t before = front.final_items;
    look_ahead(false);
    // A long stretch with no fixed point: look again only once it has doubled, so that the
    // work stays linear in the program.
    const std::size_t pending = items.size() - front.final_items;
    next_look_ahead = front.final_items > before ? batch : std::max(batch, 2 * pending);
  }
  send_ready();
}

// Step 1 for one command.
void Planner::Impl::limit_and_chain(WaitingCommand& w) {
  const CanonCommand& c = w.command;
  const std::size_t i = w.timed.command;
  if (!is_move(c.kind)) {
    EventTiming e = events.time(c);
    w.timed.duration_s = finite_or_zero(e.duration_s, c.line, warnings);
    w.timed.note = std::move(e.note);
    if (e.stops_motion) previous_flows = false;
    if (linuxcnc_path && linuxcnc_path->event(c)) task_waiting += linuxcnc::kTaskLatency_s;
    return;
  }
  if (c.kind == CanonKind::Traverse && k.rapid_mode == RapidMode::DogLeg) {
    w.plan.timing = MoveTiming::DogLeg;
    previous_flows = false;
    if (linuxcnc_path) linuxcnc_path->stop();
    return;
  }
  const MoveLimits limits = move_limits(c, k, warnings);
  if (!(limits.length > kMinMoveLength)) {
    w.plan.timing = MoveTiming::Point;
    return;
  }
  if (c.kind == CanonKind::Probe) {
    w.plan.timing = MoveTiming::RestToRest;
    previous_flows = false;
    if (linuxcnc_path) linuxcnc_path->stop();
    return;
  }
  if (linuxcnc_path) {
    w.plan.timing = MoveTiming::Chained; // its charge arrives once its segment is settled
    w.plan.count = 0;
    w.plan.charged = false;
    if (task_waiting > 0 && last_move != kNone) rest_after.emplace_back(last_move, task_waiting);
    task_waiting = 0;
    last_move = i;
    linuxcnc_path->move(i, c, &limits);
    return;
  }
  if (previous_flows)
    items.back().junction_after =
        junction_speed(previous_limits, limits, previous_mode, previous_tolerance, k);
  w.plan = MovePlan{MoveTiming::Chained, 1, static_cast<std::uint32_t>(items.size())};
  items.push_back(SpeedPlanItem{limits.length, limits.vmax, limits.accel, limits.jerk});
  if (const std::size_t depth = k.lookahead_blocks; depth > 0) {
    // The item `depth` before this one leaves the control's view; at its end the control has
    // read up to this one and must be able to stop by this one's end. It is not final yet
    // (plan_speeds holds the last `depth` items back).
    lookahead_mm += limits.length;
    if (items.size() > depth) {
      SpeedPlanItem& leaving = items[items.size() - 1 - depth];
      lookahead_mm -= leaving.length;
      leaving.junction_after = std::min(
          leaving.junction_after, reachable_speed(0, lookahead_mm, leaving.accel, leaving.jerk));
    }
  }
  previous_limits = limits;
  previous_flows = true;
  previous_mode = c.state.path_mode;
  previous_tolerance = c.state.path_tolerance;
}

// A long run of commands off the path: the last move ends at rest, as when a code stops motion,
// and what waited for the move after it is timed. What the look-ahead holds then ends at rest
// too, so it is planned to its end.
void Planner::Impl::come_to_rest() {
  previous_flows = false;
  if (linuxcnc_path) {
    linuxcnc_path->stop();
    if (task_waiting > 0 && last_move != kNone) rest_after.emplace_back(last_move, task_waiting);
    task_waiting = 0;
    last_move = kNone; // its task time is known: timed with it
  }
  if (!options.look_ahead_whole_program) {
    look_ahead(true);
    next_look_ahead = batch;
  }
}

void Planner::Impl::look_ahead(bool at_end) {
  work.items_planned += plan_speeds(items, front, at_end, k.lookahead_blocks);
}

// Whether a command's timing is final: a move's speeds are, and so is what LinuxCNC's task adds
// after it (known once the next move has arrived).
bool Planner::Impl::ready(const WaitingCommand& w) const {
  if (w.plan.timing != MoveTiming::Chained) return true;
  if (!w.plan.charged) return false;
  if (w.plan.item + w.plan.count > front.final_items) return false;
  return !linuxcnc_path || finished || w.timed.command != last_move;
}

void Planner::Impl::send_ready() {
  work.most_items = std::max(work.most_items, items.size() - items.first());
  work.most_waiting = std::max(work.most_waiting, waiting.size());
  for (;;) {
    ++work.commands_examined;
    if (waiting.empty() || !ready(waiting.front())) break;
    WaitingCommand& w = waiting.front();
    time(w);
    sink(w.command, w.timed);
    waiting.pop_front();
    ++first_waiting;
  }
  // Items no waiting command is, or may yet be, charged with. Only the front need be looked at,
  // never the whole queue (zero-length moves pile up behind a move waiting for the next one, and
  // a scan of them on every command made such a run quadratic): what is not ready is a chained
  // move, charges come in program order and items in path order, so the front's charge is the
  // oldest; and what the moves not charged yet may be charged with, the path builder says.
  std::size_t in_use = front.final_items;
  ++work.commands_examined;
  if (!waiting.empty() && waiting.front().plan.timing == MoveTiming::Chained &&
      waiting.front().plan.charged)
    in_use = std::min<std::size_t>(in_use, waiting.front().plan.item);
  if (linuxcnc_path) in_use = std::min(in_use, linuxcnc_path->oldest_item_in_use());
  items.drop_before(in_use);
}

// Step 3 for one command.
void Planner::Impl::time(WaitingCommand& w) {
  const CanonCommand& c = w.command;
  TimedCommand& out = w.timed;
  const std::size_t i = out.command;
  out.start_s = clock;
  if (w.plan.timing != MoveTiming::NotAMove && !spare_samples.empty()) {
    out.samples = std::move(spare_samples.back());
    out.samples.clear();
    spare_samples.pop_back();
  }
  switch (w.plan.timing) {
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
    const MovePlan& plan = w.plan;
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
    while (!rest_after.empty() && rest_after.front().first < i)
      rest_after.pop_front();
    if (!rest_after.empty() && rest_after.front().first == i) {
      // The codes after this move run with the machine at rest (LinuxCNC rule).
      out.duration_s += rest_after.front().second;
      rest_after.pop_front();
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
  settle(c, out);
  clock += out.duration_s;
}

// A control that checks position at every stop waits there before the next block.
void Planner::Impl::settle(const CanonCommand& c, TimedCommand& out) const {
  const double settle_s =
      c.kind == CanonKind::Traverse ? k.settle_rapid_s.value_or(k.settle_s) : k.settle_s;
  if (!(settle_s > 0) || !is_move(c.kind) || !(out.duration_s > 0) || out.exit_speed_mm_s > 0)
    return;
  out.duration_s += settle_s;
  out.samples.push_back(MotionSample{clock + out.duration_s, 1.0, c.end, 0.0});
}

double Planner::Impl::finish() {
  if (finished) return clock;
  if (linuxcnc_path) linuxcnc_path->finish();
  finished = true;
  look_ahead(true);
  send_ready();
  logger().debug("planned {} commands ({} look-ahead items): {:.3f} s", next_number, items.size(),
                 clock);
  return clock;
}

Planner::Planner(const MachineProfile& machine, const PlanOptions& options, Sink sink)
    : impl_(std::make_unique<Impl>(machine, options, std::move(sink))) {}

Planner::~Planner() = default;

void Planner::add(const CanonCommand& command) {
  impl_->add(command);
}

void Planner::reuse_samples(std::vector<MotionSample>&& spent) {
  if (spent.capacity() > 0 && impl_->spare_samples.size() < kMaxSpareSamples)
    impl_->spare_samples.push_back(std::move(spent));
}

double Planner::finish() {
  return impl_->finish();
}

std::vector<Diagnostic> Planner::take_diagnostics() {
  return impl_->warnings.take();
}

Planner::Work Planner::work() const {
  return impl_->work;
}

Timeline plan(const std::vector<CanonCommand>& commands, const MachineProfile& machine,
              const PlanOptions& options) {
  Timeline timeline;
  timeline.commands.reserve(commands.size());
  Planner planner(machine, options, [&timeline](const CanonCommand&, TimedCommand& timed) {
    timeline.commands.push_back(std::move(timed));
  });
  for (const CanonCommand& c : commands)
    planner.add(c);
  timeline.total_s = planner.finish();
  timeline.diagnostics = planner.take_diagnostics();
  return timeline;
}

} // namespace ncjoule
