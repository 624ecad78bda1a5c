// Data items are read by MTConnect type, in every version's names.
#include <doctest/doctest.h>

#include "ncjoule/logs.hpp"

using namespace ncjoule;

TEST_CASE("signals: types of MTConnect 1.2 to 2.x") {
  CHECK(signal_of("LINE", "", "Path", "path") == LogSignal::Line);
  CHECK(signal_of("LINE_NUMBER", "ABSOLUTE", "Path", "path") == LogSignal::Line);
  CHECK_FALSE(signal_of("LINE_NUMBER", "INCREMENTAL", "Path", "path"));
  CHECK(signal_of("EXECUTION", "", "Path", "") == LogSignal::Execution);
  CHECK(signal_of("PROGRAM", "MAIN", "Path", "") == LogSignal::Program);
  CHECK_FALSE(signal_of("PROGRAM", "SCHEDULE", "Path", ""));
  // Overrides: 1.3+ by their own type and subType, 1.2 as a subType of the rate.
  CHECK(signal_of("PATH_FEEDRATE_OVERRIDE", "RAPID", "Path", "") == LogSignal::RapidOverride);
  CHECK(signal_of("PATH_FEEDRATE_OVERRIDE", "PROGRAMMED", "Path", "") == LogSignal::FeedOverride);
  CHECK(signal_of("PATH_FEEDRATE_OVERRIDE", "", "Path", "") == LogSignal::FeedOverride);
  CHECK_FALSE(signal_of("PATH_FEEDRATE_OVERRIDE", "JOG", "Path", ""));
  CHECK(signal_of("PATH_FEEDRATE", "OVERRIDE", "Path", "") == LogSignal::FeedOverride);
  CHECK(signal_of("PATH_FEEDRATE", "ACTUAL", "Path", "") == LogSignal::PathFeedrate);
  CHECK_FALSE(signal_of("PATH_FEEDRATE", "PROGRAMMED", "Path", ""));
  CHECK(signal_of("SPINDLE_SPEED", "", "Rotary", "C") == LogSignal::SpindleSpeed);
  CHECK(signal_of("ROTARY_VELOCITY", "ACTUAL", "Rotary", "C") == LogSignal::SpindleSpeed);
  CHECK(signal_of("ROTARY_VELOCITY_OVERRIDE", "", "Rotary", "C") == LogSignal::SpindleOverride);
  // A LOAD is the spindle's only on a spindle's component; an axis's is not.
  CHECK(signal_of("LOAD", "", "Rotary", "C") == LogSignal::SpindleLoad);
  CHECK(signal_of("LOAD", "", "Spindle", "main") == LogSignal::SpindleLoad);
  CHECK_FALSE(signal_of("LOAD", "", "Linear", "X"));
  CHECK(signal_of("WATTAGE", "ACTUAL", "Electric", "") == LogSignal::Power);
  CHECK(signal_of("TOOL_NUMBER", "", "Path", "") == LogSignal::Tool);
  CHECK_FALSE(signal_of("POSITION", "ACTUAL", "Linear", "X"));
}

TEST_CASE("signals: names of the mapping file's keys read back") {
  for (std::size_t i = 0; i < kLogSignalCount; ++i) {
    const auto s = static_cast<LogSignal>(i);
    CHECK(log_signal_from_name(log_signal_name(s)) == s);
  }
  CHECK_FALSE(log_signal_from_name("feed"));
  CHECK(line_numbering_from_name("n-word") == LineNumbering::NWord);
  CHECK_FALSE(line_numbering_from_name("lines"));
}
