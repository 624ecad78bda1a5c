// Printing canonical commands in the form of LinuxCNC's `rs274 -g`, in program units.
#include <cstring>
#include <string>
#include <string_view>

#include "ncjoule/fixed_text.hpp"
#include "ncjoule/gcode.hpp"

namespace ncjoule {
namespace {

// Appends "%.4f" of each value, separated by ", " (fixed_text.hpp writes what printf would).
void append_fixed4(std::string& out, std::initializer_list<double> values) {
  bool first = true;
  for (const double v : values) {
    if (!first) out += ", ";
    first = false;
    append_fixed(out, v, 4);
  }
}

// The same into a buffer with room for them; nullptr when a value is one only printf writes.
char* put_fixed4(char* p, std::initializer_list<double> values) {
  bool first = true;
  for (const double v : values) {
    if (!first) *p++ = ',', *p++ = ' ';
    first = false;
    p = write_fixed_fast(p, v, 4);
    if (!p) return nullptr;
  }
  return p;
}

char* put_text(char* p, std::string_view text) {
  std::memcpy(p, text.data(), text.size());
  return p + text.size();
}

// Room for a move's line: a name, ten numbers and a rotation.
constexpr std::size_t kLineRoom = 64 + 10 * (kFixedFastChars + 2) + 16;

// NAME(v, v, ...) with each value in "%.4f". Moves are most of a program, and `ncjoule canon`
// prints every one: the line is made in a buffer and appended once.
void append_call(std::string& out, std::string_view name, std::initializer_list<double> values) {
  char buffer[kLineRoom];
  char* p = put_text(buffer, name);
  *p++ = '(';
  if ((p = put_fixed4(p, values))) {
    *p++ = ')';
    out.append(buffer, std::size_t(p - buffer));
    return;
  }
  out += name;
  out += '(';
  append_fixed4(out, values);
  out += ')';
}

// NAME(x, y, z, a, b, c) of a straight move, in program units.
void straight_line(std::string& out, std::string_view name, const Pose& e, double u) {
  append_call(out, name, {e.x / u, e.y / u, e.z / u, e.a, e.b, e.c});
}

// ARC_FEED(first, second, centre first, centre second, rotation, normal, a, b, c).
void arc_line(std::string& out, const CanonCommand& c, double u) {
  const Pose& e = c.end;
  double first = e.x, second = e.y, normal = e.z;
  if (c.plane == Plane::YZ) first = e.y, second = e.z, normal = e.x;
  if (c.plane == Plane::XZ) first = e.z, second = e.x, normal = e.y;
  const std::string rotation = std::to_string(c.rotation);
  char buffer[kLineRoom];
  char* p = put_text(buffer, "ARC_FEED(");
  if ((p = put_fixed4(p, {first / u, second / u, c.centre_first / u, c.centre_second / u}))) {
    p = put_text(p, ", ");
    p = put_text(p, rotation);
    p = put_text(p, ", ");
    if ((p = put_fixed4(p, {normal / u, e.a, e.b, e.c}))) {
      *p++ = ')';
      out.append(buffer, std::size_t(p - buffer));
      return;
    }
  }
  out += "ARC_FEED(";
  append_fixed4(out, {first / u, second / u, c.centre_first / u, c.centre_second / u});
  out += ", " + rotation + ", ";
  append_fixed4(out, {normal / u, e.a, e.b, e.c});
  out += ')';
}

} // namespace

void append_canon(std::string& out, const CanonCommand& c) {
  const double u = c.state.inch ? 25.4 : 1.0;
  const Pose& e = c.end;
  switch (c.kind) {
  case CanonKind::Traverse:
    return straight_line(out, "STRAIGHT_TRAVERSE", e, u);
  case CanonKind::Feed:
    if (c.text == "rigid tap") return append_call(out, "RIGID_TAP", {e.x / u, e.y / u, e.z / u});
    if (c.text == "rigid tap retract") return;
    return straight_line(out, "STRAIGHT_FEED", e, u);
  case CanonKind::Probe:
    return straight_line(out, "STRAIGHT_PROBE", e, u);
  case CanonKind::Arc:
    return arc_line(out, c, u);
  case CanonKind::Dwell:
    return append_call(out, "DWELL", {c.value});
  case CanonKind::SelectTool:
    out += "SELECT_TOOL(" + std::to_string(int(c.value)) + ")";
    return;
  case CanonKind::ChangeTool:
    out += "CHANGE_TOOL(" + std::to_string(int(c.value)) + ")";
    return;
  case CanonKind::SetFeedRate:
    return append_call(out, "SET_FEED_RATE", {c.value});
  case CanonKind::SetFeedMode:
    out += c.state.feed_mode == FeedMode::InverseTime          ? "SET_FEED_MODE(0, 1)"
           : c.state.feed_mode == FeedMode::UnitsPerRevolution ? "SET_FEED_MODE(0, 2)"
                                                               : "SET_FEED_MODE(0, 0)";
    return;
  case CanonKind::SpindleSpeed:
    out += "SET_SPINDLE_SPEED(0, ";
    append_fixed(out, c.value, 4);
    out += ')';
    return;
  case CanonKind::SpindleClockwise:
    out += "START_SPINDLE_CLOCKWISE(0)";
    return;
  case CanonKind::SpindleCounterClockwise:
    out += "START_SPINDLE_COUNTERCLOCKWISE(0)";
    return;
  case CanonKind::SpindleStop:
    out += "STOP_SPINDLE_TURNING(0)";
    return;
  case CanonKind::MistOn:
    out += "MIST_ON()";
    return;
  case CanonKind::FloodOn:
    out += "FLOOD_ON()";
    return;
  case CanonKind::MistOff:
    out += "MIST_OFF()";
    return;
  case CanonKind::FloodOff:
    out += "FLOOD_OFF()";
    return;
  case CanonKind::LengthUnits:
    out +=
        c.state.inch ? "USE_LENGTH_UNITS(CANON_UNITS_INCHES)" : "USE_LENGTH_UNITS(CANON_UNITS_MM)";
    return;
  case CanonKind::PlaneSelect:
    out += c.state.plane == Plane::XY   ? "SELECT_PLANE(CANON_PLANE_XY)"
           : c.state.plane == Plane::YZ ? "SELECT_PLANE(CANON_PLANE_YZ)"
                                        : "SELECT_PLANE(CANON_PLANE_XZ)";
    return;
  case CanonKind::PathControl:
    if (c.state.path_mode == PathMode::Continuous) {
      out += "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, ";
      append_fixed(out, c.state.path_tolerance / u, 6); // rs274 prints it with "%f"
      out += ')';
      return;
    }
    out += c.state.path_mode == PathMode::ExactPath ? "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)"
                                                    : "SET_MOTION_CONTROL_MODE(CANON_EXACT_STOP)";
    return;
  case CanonKind::ToolLengthOffset:
    out += "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 ";
    append_fixed(out, c.value / u, 4);
    out += ", 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)";
    return;
  case CanonKind::WorkOffset:
    out += "SET_G5X_OFFSET(" + std::to_string(int(c.value)) + ", ";
    append_fixed4(out, {e.x / u, e.y / u, e.z / u, e.a, e.b, e.c});
    out += ')';
    return;
  case CanonKind::AxisOffset:
    return append_call(out, "SET_G92_OFFSET", {e.x / u, e.y / u, e.z / u, e.a, e.b, e.c});
  case CanonKind::ProgramStop:
    out += "PROGRAM_STOP()";
    return;
  case CanonKind::OptionalStop:
    out += "OPTIONAL_PROGRAM_STOP()";
    return;
  case CanonKind::ProgramEnd:
    out += "PROGRAM_END()";
    return;
  case CanonKind::Message:
    out += "MESSAGE(\"" + c.text + "\")";
    return;
  case CanonKind::Comment:
    out += "COMMENT(\"" + c.text + "\")";
    return;
  case CanonKind::PlannerHint:
    out += "COMMENT(\"planner hint: " + c.text + "\")";
    return;
  }
}

std::string format_canon(const CanonCommand& c) {
  std::string out;
  append_canon(out, c);
  return out;
}

} // namespace ncjoule
