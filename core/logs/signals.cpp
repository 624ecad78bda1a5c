// What a logged data item means: its signal, from its MTConnect type, subType and component.
// MTConnect renamed some types over its versions (LINE became LINE_NUMBER in 1.4, SPINDLE_SPEED
// became ROTARY_VELOCITY in 1.2, overrides moved from subType OVERRIDE to their own types): the
// old and the new names are both read.
#include <algorithm>
#include <array>
#include <cctype>

#include "ncjoule/logs.hpp"

namespace ncjoule {
namespace {

constexpr std::array<std::string_view, kLogSignalCount> kNames = {
    "line",          "block",         "program",        "execution",     "mode",
    "path_feedrate", "feed_override", "rapid_override", "spindle_speed", "spindle_override",
    "spindle_load",  "tool",          "power",          "current",       "availability",
    "emergency_stop"};

constexpr std::array<std::string_view, 4> kNumberings = {"auto", "file-line", "file-line-from-zero",
                                                         "n-word"};

bool is_spindle_component(std::string_view component, std::string_view name) {
  // A spindle is a Rotary axis (in SPINDLE mode) or, since MTConnect 1.4, a Spindle component;
  // NIST's Hurcos name theirs C, a Mazak S. Linear axes carry their own LOADs.
  std::string c(component), n(name);
  for (char& ch : c)
    ch = char(std::toupper(static_cast<unsigned char>(ch)));
  for (char& ch : n)
    ch = char(std::toupper(static_cast<unsigned char>(ch)));
  if (c == "SPINDLE" || c == "ROTARY") return true;
  return n.find("SPINDLE") != std::string::npos || n == "S" || n == "S1" || n == "SP";
}

} // namespace

std::string_view log_signal_name(LogSignal signal) {
  return kNames[static_cast<std::size_t>(signal)];
}

std::optional<LogSignal> log_signal_from_name(std::string_view name) {
  for (std::size_t i = 0; i < kNames.size(); ++i)
    if (kNames[i] == name) return static_cast<LogSignal>(i);
  return std::nullopt;
}

std::string_view line_numbering_name(LineNumbering numbering) {
  return kNumberings[static_cast<std::size_t>(numbering)];
}

std::optional<LineNumbering> line_numbering_from_name(std::string_view name) {
  for (std::size_t i = 0; i < kNumberings.size(); ++i)
    if (kNumberings[i] == name) return static_cast<LineNumbering>(i);
  return std::nullopt;
}

std::optional<LogSignal> signal_of(std::string_view type, std::string_view sub_type,
                                   std::string_view component, std::string_view component_name) {
  const bool actual = sub_type.empty() || sub_type == "ACTUAL";
  if (type == "LINE" || type == "LINE_LABEL") return LogSignal::Line;
  // INCREMENTAL counts the blocks run since the program started, not which one runs.
  if (type == "LINE_NUMBER")
    return sub_type == "INCREMENTAL" ? std::nullopt : std::optional(LogSignal::Line);
  if (type == "BLOCK") return LogSignal::Block;
  // PROGRAM's subTypes (2.x): MAIN and ACTIVE name what runs; SCHEDULE what is queued.
  if (type == "PROGRAM")
    return sub_type == "SCHEDULE" ? std::nullopt : std::optional(LogSignal::Program);
  if (type == "EXECUTION") return LogSignal::Execution;
  if (type == "CONTROLLER_MODE") return LogSignal::Mode;
  if (type == "PATH_FEEDRATE") {
    if (sub_type == "OVERRIDE") return LogSignal::FeedOverride; // MTConnect 1.2
    return actual ? std::optional(LogSignal::PathFeedrate) : std::nullopt;
  }
  if (type == "PATH_FEEDRATE_OVERRIDE") {
    if (sub_type == "RAPID") return LogSignal::RapidOverride;
    if (sub_type == "JOG") return std::nullopt;
    return LogSignal::FeedOverride; // PROGRAMMED, or no subType (1.3's agents)
  }
  if (type == "ROTARY_VELOCITY" || type == "SPINDLE_SPEED") {
    if (sub_type == "OVERRIDE") return LogSignal::SpindleOverride; // MTConnect 1.2
    return actual ? std::optional(LogSignal::SpindleSpeed) : std::nullopt;
  }
  if (type == "ROTARY_VELOCITY_OVERRIDE" || type == "SPINDLE_SPEED_OVERRIDE")
    return LogSignal::SpindleOverride;
  if (type == "LOAD")
    return is_spindle_component(component, component_name) ? std::optional(LogSignal::SpindleLoad)
                                                           : std::nullopt;
  if (type == "TOOL_NUMBER" || type == "TOOL_ID") return LogSignal::Tool;
  if (type == "WATTAGE") return actual ? std::optional(LogSignal::Power) : std::nullopt;
  if (type == "AMPERAGE") return actual ? std::optional(LogSignal::Current) : std::nullopt;
  if (type == "AVAILABILITY") return LogSignal::Availability;
  if (type == "EMERGENCY_STOP") return LogSignal::EmergencyStop;
  return std::nullopt;
}

} // namespace ncjoule
