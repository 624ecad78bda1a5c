// What a line does (its kind), and where a program's time goes (TimeSplit).
#include "ncjoule/estimate.hpp"

namespace ncjoule {

const char* line_kind_name(LineKind kind) {
  switch (kind) {
  case LineKind::Setting:
    return "setting";
  case LineKind::Rapid:
    return "rapid";
  case LineKind::Feed:
    return "feed";
  case LineKind::Arc:
    return "arc";
  case LineKind::Probe:
    return "probe";
  case LineKind::Dwell:
    return "dwell";
  case LineKind::SelectTool:
    return "select_tool";
  case LineKind::ToolChange:
    return "tool_change";
  case LineKind::Spindle:
    return "spindle";
  case LineKind::Coolant:
    return "coolant";
  case LineKind::ProgramStop:
    return "program_stop";
  case LineKind::OptionalStop:
    return "optional_stop";
  case LineKind::ProgramEnd:
    return "program_end";
  case LineKind::Message:
    return "message";
  case LineKind::Comment:
    return "comment";
  }
  return "setting";
}

LineKind line_kind(CanonKind kind) {
  switch (kind) {
  case CanonKind::Traverse:
    return LineKind::Rapid;
  case CanonKind::Feed:
    return LineKind::Feed;
  case CanonKind::Arc:
    return LineKind::Arc;
  case CanonKind::Probe:
    return LineKind::Probe;
  case CanonKind::Dwell:
    return LineKind::Dwell;
  case CanonKind::SelectTool:
    return LineKind::SelectTool;
  case CanonKind::ChangeTool:
    return LineKind::ToolChange;
  case CanonKind::SpindleSpeed:
  case CanonKind::SpindleClockwise:
  case CanonKind::SpindleCounterClockwise:
  case CanonKind::SpindleStop:
    return LineKind::Spindle;
  case CanonKind::MistOn:
  case CanonKind::FloodOn:
  case CanonKind::MistOff:
  case CanonKind::FloodOff:
    return LineKind::Coolant;
  case CanonKind::ProgramStop:
    return LineKind::ProgramStop;
  case CanonKind::OptionalStop:
    return LineKind::OptionalStop;
  case CanonKind::ProgramEnd:
    return LineKind::ProgramEnd;
  case CanonKind::Message:
    return LineKind::Message;
  case CanonKind::Comment:
    return LineKind::Comment;
  default:
    return LineKind::Setting; // feed rate, units, plane, offsets, path control, ...
  }
}

std::string kind_name(CanonKind kind) {
  return line_kind_name(line_kind(kind));
}

void TimeSplit::add(CanonKind kind, double duration_s, bool removes_material, bool removal_known) {
  switch (kind) {
  case CanonKind::Traverse:
    rapid_s += duration_s;
    break;
  case CanonKind::Feed:
  case CanonKind::Arc:
  case CanonKind::Probe:
    feed_s += duration_s;
    if (removal_known && !removes_material) air_cut_s += duration_s;
    break;
  case CanonKind::ChangeTool:
    tool_change_s += duration_s;
    ++tool_changes;
    break;
  case CanonKind::Dwell:
    dwell_s += duration_s;
    break;
  case CanonKind::SpindleSpeed:
  case CanonKind::SpindleClockwise:
  case CanonKind::SpindleCounterClockwise:
  case CanonKind::SpindleStop:
    spindle_s += duration_s;
    break;
  default:
    other_s += duration_s;
    break;
  }
}

} // namespace ncjoule
