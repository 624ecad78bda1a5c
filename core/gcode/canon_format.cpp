// Printing canonical commands in the form of LinuxCNC's `rs274 -g`, in program units.
#include <charconv>
#include <cstdio>

#include "ncjoule/gcode.hpp"

namespace ncjoule {
namespace {

std::string printf_string(const char* format, auto... args) {
  char buffer[256];
  const int n = std::snprintf(buffer, sizeof buffer, format, args...);
  if (n < 0) return {};
  if (std::size_t(n) < sizeof buffer) return std::string(buffer, std::size_t(n));
  // Long output (values near 1e300 print hundreds of digits): size it exactly.
  std::string out(std::size_t(n), '\0');
  std::snprintf(out.data(), out.size() + 1, format, args...);
  return out;
}

// Appends "%.4f" of each value, separated by ", ". to_chars rounds exactly as printf does, and
// is several times faster: moves are most of a program, and `ncjoule canon` prints every one.
void append_fixed4(std::string& out, std::initializer_list<double> values) {
  bool first = true;
  for (const double v : values) {
    if (!first) out += ", ";
    first = false;
    char buffer[64];
    const auto r = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::fixed, 4);
    if (r.ec == std::errc())
      out.append(buffer, r.ptr);
    else
      out += printf_string("%.4f", v);
  }
}

// NAME(x, y, z, a, b, c) of a straight move, in program units.
std::string straight_line(const char* name, const Pose& e, double u) {
  std::string out;
  out.reserve(96);
  out += name;
  out += '(';
  append_fixed4(out, {e.x / u, e.y / u, e.z / u, e.a, e.b, e.c});
  out += ')';
  return out;
}

} // namespace

std::string format_canon(const CanonCommand& c) {
  const double u = c.state.inch ? 25.4 : 1.0;
  const Pose& e = c.end;
  switch (c.kind) {
  case CanonKind::Traverse:
    return straight_line("STRAIGHT_TRAVERSE", e, u);
  case CanonKind::Feed:
    if (c.text == "rigid tap")
      return printf_string("RIGID_TAP(%.4f, %.4f, %.4f)", e.x / u, e.y / u, e.z / u);
    if (c.text == "rigid tap retract") return {};
    return straight_line("STRAIGHT_FEED", e, u);
  case CanonKind::Probe:
    return straight_line("STRAIGHT_PROBE", e, u);
  case CanonKind::Arc: {
    double first = e.x, second = e.y, normal = e.z;
    if (c.plane == Plane::YZ) first = e.y, second = e.z, normal = e.x;
    if (c.plane == Plane::XZ) first = e.z, second = e.x, normal = e.y;
    std::string out = "ARC_FEED(";
    out.reserve(128);
    append_fixed4(out, {first / u, second / u, c.centre_first / u, c.centre_second / u});
    out += ", ";
    out += std::to_string(c.rotation);
    out += ", ";
    append_fixed4(out, {normal / u, e.a, e.b, e.c});
    out += ')';
    return out;
  }
  case CanonKind::Dwell:
    return printf_string("DWELL(%.4f)", c.value);
  case CanonKind::SelectTool:
    return printf_string("SELECT_TOOL(%d)", int(c.value));
  case CanonKind::ChangeTool:
    return printf_string("CHANGE_TOOL(%d)", int(c.value));
  case CanonKind::SetFeedRate:
    return printf_string("SET_FEED_RATE(%.4f)", c.value);
  case CanonKind::SetFeedMode:
    return printf_string("SET_FEED_MODE(0, %d)", c.state.feed_mode == FeedMode::InverseTime ? 1
                                                 : c.state.feed_mode == FeedMode::UnitsPerRevolution
                                                     ? 2
                                                     : 0);
  case CanonKind::SpindleSpeed:
    return printf_string("SET_SPINDLE_SPEED(0, %.4f)", c.value);
  case CanonKind::SpindleClockwise:
    return "START_SPINDLE_CLOCKWISE(0)";
  case CanonKind::SpindleCounterClockwise:
    return "START_SPINDLE_COUNTERCLOCKWISE(0)";
  case CanonKind::SpindleStop:
    return "STOP_SPINDLE_TURNING(0)";
  case CanonKind::MistOn:
    return "MIST_ON()";
  case CanonKind::FloodOn:
    return "FLOOD_ON()";
  case CanonKind::MistOff:
    return "MIST_OFF()";
  case CanonKind::FloodOff:
    return "FLOOD_OFF()";
  case CanonKind::LengthUnits:
    return c.state.inch ? "USE_LENGTH_UNITS(CANON_UNITS_INCHES)"
                        : "USE_LENGTH_UNITS(CANON_UNITS_MM)";
  case CanonKind::PlaneSelect:
    return c.state.plane == Plane::XY   ? "SELECT_PLANE(CANON_PLANE_XY)"
           : c.state.plane == Plane::YZ ? "SELECT_PLANE(CANON_PLANE_YZ)"
                                        : "SELECT_PLANE(CANON_PLANE_XZ)";
  case CanonKind::PathControl:
    if (c.state.path_mode == PathMode::Continuous)
      return printf_string("SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, %f)",
                           c.state.path_tolerance / u);
    return c.state.path_mode == PathMode::ExactPath ? "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)"
                                                    : "SET_MOTION_CONTROL_MODE(CANON_EXACT_STOP)";
  case CanonKind::ToolLengthOffset:
    return printf_string("USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 %.4f, 0.0000 0.0000 0.0000, "
                         "0.0000 0.0000 0.0000)",
                         c.value / u);
  case CanonKind::WorkOffset:
    return printf_string("SET_G5X_OFFSET(%d, %.4f, %.4f, %.4f, %.4f, %.4f, %.4f)", int(c.value),
                         e.x / u, e.y / u, e.z / u, e.a, e.b, e.c);
  case CanonKind::AxisOffset:
    return printf_string("SET_G92_OFFSET(%.4f, %.4f, %.4f, %.4f, %.4f, %.4f)", e.x / u, e.y / u,
                         e.z / u, e.a, e.b, e.c);
  case CanonKind::ProgramStop:
    return "PROGRAM_STOP()";
  case CanonKind::OptionalStop:
    return "OPTIONAL_PROGRAM_STOP()";
  case CanonKind::ProgramEnd:
    return "PROGRAM_END()";
  case CanonKind::Message:
    return "MESSAGE(\"" + c.text + "\")";
  case CanonKind::Comment:
    return "COMMENT(\"" + c.text + "\")";
  case CanonKind::PlannerHint:
    return "COMMENT(\"planner hint: " + c.text + "\")";
  }
  return {};
}

} // namespace ncjoule
