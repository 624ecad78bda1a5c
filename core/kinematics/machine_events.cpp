#include "machine_events.hpp"

#include <cmath>

namespace ncjoule::kinematics_detail {
namespace {

// Seconds from rest to `rpm` on a measured curve (rpm, s): linear from rest to the first point
// and between points, at the last segment's rate past the last.
double time_from_rest(const std::vector<std::pair<double, double>>& curve, double rpm) {
  double rpm0 = 0, s0 = 0;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const auto [rpm1, s1] = curve[i];
    if (rpm <= rpm1 || i + 1 == curve.size()) return s0 + (s1 - s0) * (rpm - rpm0) / (rpm1 - rpm0);
    rpm0 = rpm1, s0 = s1;
  }
  return 0;
}

} // namespace

double MachineEvents::ramp_to(double signed_rpm) {
  const double from = running_rpm_;
  running_rpm_ = signed_rpm;
  if (!machine_.spindle_waits) return 0; // the ramp runs on while the path moves
  if (machine_.spindle_run_up.empty()) {
    // A reversal passes through zero, so its ramp covers both speeds.
    return std::abs(signed_rpm - from) / 1000.0 * machine_.spindle_s_per_1000rpm;
  }
  const auto& up = machine_.spindle_run_up;
  const auto& down = machine_.spindle_run_down.empty() ? up : machine_.spindle_run_down;
  const bool same_direction = (from >= 0) == (signed_rpm >= 0) || from == 0 || signed_rpm == 0;
  const double a = std::abs(from), b = std::abs(signed_rpm);
  if (!same_direction) return time_from_rest(down, a) + time_from_rest(up, b);
  return b >= a ? time_from_rest(up, b) - time_from_rest(up, a)
                : time_from_rest(down, a) - time_from_rest(down, b);
}

double MachineEvents::tool_change(int tool) {
  const bool first = spindle_tool_ < 0;
  const bool same = tool == spindle_tool_;
  spindle_tool_ = tool;
  // A control with a stop sequence leaves the spindle at rest: the next M3 runs it up from there.
  const double stop = running_rpm_ != 0 ? machine_.tool_change_spindle_stop_s : 0.0;
  if (stop > 0) running_rpm_ = 0;
  if (same && machine_.tool_change_same_tool_s) return *machine_.tool_change_same_tool_s + stop;
  return machine_.tool_change_s + (first ? machine_.tool_change_first_extra_s : 0.0) + stop;
}

EventTiming MachineEvents::time(const CanonCommand& c) {
  EventTiming e;
  switch (c.kind) {
  case CanonKind::Dwell:
    e.duration_s = std::isfinite(c.value) && c.value > 0 ? c.value : 0.0;
    e.stops_motion = true;
    break;
  case CanonKind::ChangeTool:
    e.duration_s = tool_change(std::isfinite(c.value) ? int(std::lround(c.value)) : 0);
    e.stops_motion = true;
    break;
  case CanonKind::SpindleSpeed:
    // A new S while the spindle turns changes its speed; the path waits for it (as controllers
    // wait for "at speed").
    programmed_rpm_ = std::isfinite(c.value) ? std::abs(c.value) : 0.0;
    if (running_rpm_ != 0)
      e.duration_s = ramp_to(running_rpm_ > 0 ? programmed_rpm_ : -programmed_rpm_);
    e.stops_motion = true;
    break;
  case CanonKind::SpindleClockwise:
    e.duration_s = ramp_to(programmed_rpm_);
    e.stops_motion = true;
    break;
  case CanonKind::SpindleCounterClockwise:
    e.duration_s = ramp_to(-programmed_rpm_);
    e.stops_motion = true;
    break;
  case CanonKind::SpindleStop:
    e.duration_s = ramp_to(0);
    e.stops_motion = true;
    break;
  case CanonKind::ProgramStop:
    e.duration_s = machine_.waits.program_stop_s;
    e.stops_motion = true;
    e.note = e.duration_s > 0 ? "M0 program stop: the control's own stop only (the operator's "
                                "wait is not predicted)"
                              : "M0 program stop: counted as zero time (the operator's wait is "
                                "not predicted)";
    break;
  case CanonKind::OptionalStop:
    e.duration_s = machine_.waits.optional_stop_s;
    e.stops_motion = true;
    e.note = e.duration_s > 0 ? "M1 optional stop: the control's own stop sequence (an "
                                "operator's wait, when it is on, is not predicted)"
                              : "M1 optional stop: counted as zero time";
    break;
  case CanonKind::ProgramEnd:
    e.duration_s = machine_.waits.program_end_s;
    e.stops_motion = true;
    break;
  case CanonKind::MistOn:
  case CanonKind::FloodOn:
    e.duration_s = machine_.waits.coolant_on_s;
    [[fallthrough]];
  case CanonKind::MistOff:
  case CanonKind::FloodOff:
    // grbl (coolant_sync) and LinuxCNC (task waits for motion before coolant commands) switch
    // coolant with the machine at rest; Pavanaskar's analyzer ("next-feed") looked only at moves.
    e.stops_motion = machine_.junction_rule != JunctionRule::NextFeed || e.duration_s > 0;
    break;
  default: // state changes (feed, plane, offsets, comments): instantaneous, blended over
    break;
  }
  return e;
}

} // namespace ncjoule::kinematics_detail
