// The timing keys of a machine profile that logs can tell, how they are written in a profile and
// how they are read from and written to a MachineProfile.
#include <algorithm>
#include <array>

#include "ncjoule/calibrate_timing.hpp"

namespace ncjoule {
namespace {

using K = TimingKey;

constexpr std::array<TimingKeyInfo, kTimingKeyCount> kKeys = {{
    {K::AccelX, "kinematics.x", "accel", "m_s2", 1e-3, false},
    {K::AccelY, "kinematics.y", "accel", "m_s2", 1e-3, false},
    {K::AccelZ, "kinematics.z", "accel", "m_s2", 1e-3, false},
    {K::RapidX, "kinematics.x", "rapid", "mm_min", 60, false},
    {K::RapidY, "kinematics.y", "rapid", "mm_min", 60, false},
    {K::RapidZ, "kinematics.z", "rapid", "mm_min", 60, false},
    {K::TransitionRatio, "kinematics", "transition_speed_ratio", "", 1, false},
    {K::Settle, "kinematics", "settle", "s", 1, true},
    {K::SettleRapid, "kinematics", "settle_rapid", "s", 1, true},
    {K::ToolChange, "kinematics", "tool_change", "s", 1, true},
    {K::ToolChangeFirstExtra, "kinematics", "tool_change_first_extra", "s", 1, true},
    {K::ToolChangeSameTool, "kinematics", "tool_change_same_tool", "s", 1, true},
    {K::ToolChangeSpindleStop, "kinematics", "tool_change_spindle_stop", "s", 1, true},
    {K::OptionalStop, "kinematics.waits", "optional_stop", "s", 1, true},
    {K::ProgramEnd, "kinematics.waits", "program_end", "s", 1, true},
    {K::CoolantOn, "kinematics.waits", "coolant_on", "s", 1, true},
    {K::SpindleRamp, "kinematics", "spindle_ramp", "s_per_1000rpm", 1, true},
    {K::ArcAccel, "kinematics", "arc_accel", "m_s2", 1e-3, false},
}};

} // namespace

const TimingKeyInfo& timing_key_info(TimingKey key) {
  return kKeys[static_cast<std::size_t>(key)];
}

std::string timing_key_name(TimingKey key) {
  const TimingKeyInfo& i = timing_key_info(key);
  std::string name = std::string(i.table) + "." + std::string(i.stem);
  if (!i.unit.empty()) name += "_" + std::string(i.unit);
  return name;
}

double timing_key_value(const MachineProfile& m, TimingKey key) {
  const Kinematics& k = m.kinematics;
  switch (key) {
  case K::AccelX:
  case K::AccelY:
  case K::AccelZ:
    return k.axes[std::size_t(key) - std::size_t(K::AccelX)].accel_mm_s2;
  case K::RapidX:
  case K::RapidY:
  case K::RapidZ:
    return k.axes[std::size_t(key) - std::size_t(K::RapidX)].rapid_mm_s;
  case K::TransitionRatio:
    return k.transition_speed_ratio;
  case K::Settle:
    return k.settle_s;
  case K::SettleRapid:
    return k.settle_rapid_s.value_or(k.settle_s);
  case K::ToolChange:
    return k.tool_change_s;
  case K::ToolChangeFirstExtra:
    return k.tool_change_first_extra_s;
  case K::ToolChangeSameTool:
    return k.tool_change_same_tool_s.value_or(k.tool_change_s);
  case K::ToolChangeSpindleStop:
    return k.tool_change_spindle_stop_s;
  case K::OptionalStop:
    return k.waits.optional_stop_s;
  case K::ProgramEnd:
    return k.waits.program_end_s;
  case K::CoolantOn:
    return k.waits.coolant_on_s;
  case K::SpindleRamp:
    return k.spindle_s_per_1000rpm;
  case K::ArcAccel: // not given: the XY plane's, where arcs run
    return k.arc_accel_mm_s2.value_or(std::min(k.axes[0].accel_mm_s2, k.axes[1].accel_mm_s2));
  }
  return 0;
}

void set_timing_key(MachineProfile& m, TimingKey key, double value) {
  Kinematics& k = m.kinematics;
  switch (key) {
  case K::AccelX:
  case K::AccelY:
  case K::AccelZ:
    k.axes[std::size_t(key) - std::size_t(K::AccelX)].accel_mm_s2 = value;
    break;
  case K::RapidX:
  case K::RapidY:
  case K::RapidZ:
    k.axes[std::size_t(key) - std::size_t(K::RapidX)].rapid_mm_s = value;
    break;
  case K::TransitionRatio:
    k.transition_speed_ratio = value;
    break;
  case K::Settle:
    k.settle_s = value;
    break;
  case K::SettleRapid:
    k.settle_rapid_s = value;
    break;
  case K::ToolChange:
    k.tool_change_s = value;
    break;
  case K::ToolChangeFirstExtra:
    k.tool_change_first_extra_s = value;
    break;
  case K::ToolChangeSameTool:
    k.tool_change_same_tool_s = value;
    break;
  case K::ToolChangeSpindleStop:
    k.tool_change_spindle_stop_s = value;
    break;
  case K::OptionalStop:
    k.waits.optional_stop_s = value;
    break;
  case K::ProgramEnd:
    k.waits.program_end_s = value;
    break;
  case K::CoolantOn:
    k.waits.coolant_on_s = value;
    break;
  case K::SpindleRamp:
    k.spindle_s_per_1000rpm = value;
    break;
  case K::ArcAccel:
    k.arc_accel_mm_s2 = value;
    break;
  }
}

} // namespace ncjoule
