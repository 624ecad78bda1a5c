// Durations as ncjoule writes them: the one place that turns seconds into hours, minutes and
// seconds. Negative, NaN and infinite durations read as 0; hours are never an integer type, so
// no duration overflows, and no number is written with an exponent (a 6e28 s move is
// "16700000000000000000000000 h", not a negative number and not "1.67e25").
#pragma once

#include <string>

namespace ncjoule {

struct ClockParts {
  double hours = 0;   // whole hours
  int minutes = 0;    // 0..59
  double seconds = 0; // 0..<60, rounded to the step asked for
};

// Splits `seconds` after rounding it to a multiple of `step` (1 s, 0.1 s, ...).
ClockParts split_duration(double seconds, double step);

// "12.3 s", "2 min 05.0 s", "1 h 02 min 03.0 s" (text summaries).
std::string duration_words(double seconds);
// "2:05", "1:02:03" (charts and tables).
std::string duration_clock(double seconds);
// Hours beyond what a clock face shows (1e9 and up), to three significant digits:
// "16700000000000000000000000" (with the caller's unit).
std::string huge_hours(double hours);

// A whole number written out in full, never with an exponent: exact below 9e15, beyond that
// rounded to `digits` significant digits and zeros ("1.67e25" -> "16700000000000000000000000").
std::string whole_number_text(double value, int digits);

} // namespace ncjoule
