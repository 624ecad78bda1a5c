#include "machine_events.hpp"

#include <cmath>

namespace ncjoule::kinematics_detail {

double MachineEvents::ramp_to(double signed_rpm) {
  // A reversal passes through zero, so its ramp covers both speeds.
  const double change = std::abs(signed_rpm - running_rpm_);
  running_rpm_ = signed_rpm;
  return change / 1000.0 * machine_.spindle_s_per_1000rpm;
}

EventTiming MachineEvents::time(const CanonCommand& c) {
  EventTiming e;
  switch (c.kind) {
  case CanonKind::Dwell:
    e.duration_s = std::isfinite(c.value) && c.value > 0 ? c.value : 0.0;
    e.stops_motion = true;
    break;
  case CanonKind::ChangeTool:
    e.duration_s = machine_.tool_change_s;
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
    e.stops_motion = true;
    e.note = "M0 program stop: counted as zero time (the operator's wait is not predicted)";
    break;
  case CanonKind::OptionalStop:
    e.stops_motion = true;
    e.note = "M1 optional stop: counted as zero time";
    break;
  case CanonKind::ProgramEnd:
    e.stops_motion = true;
    break;
  case CanonKind::MistOn:
  case CanonKind::MistOff:
  case CanonKind::FloodOn:
  case CanonKind::FloodOff:
    // grbl (coolant_sync) and LinuxCNC (task waits for motion before coolant commands) switch
    // coolant with the machine at rest; Pavanaskar's analyzer ("next-feed") looked only at moves.
    e.stops_motion = machine_.junction_rule != JunctionRule::NextFeed;
    break;
  default: // state changes (feed, plane, offsets, comments): instantaneous, blended over
    break;
  }
  return e;
}

} // namespace ncjoule::kinematics_detail
