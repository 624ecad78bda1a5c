// Internal: the range of values a program's words may take, and of what they make (positions,
// dwells). Beyond them a value is no machining a control would do: industrial controls refuse
// such input (Fanuc's 8-digit address format: X, Y, Z, I, J, K, R, Q within +-99,999.999 mm or
// +-9,999.9999 in, A, B, C within +-99,999.999 deg; Heidenhain TNC: positions within
// +-99,999.9999 mm, feed rates and spindle speeds to 99,999.999, dwells to 3,600 s; Mazak:
// feeds to 200,000 mm/min). Feed rates are the exception: LinuxCNC's own sample 3D_Chips.ngc
// programs F2250000 to run fast, and the machine's limits cap any feed, so F only has to fit
// eight digits. Here they are errors with the word's column, so that no infinite,
// NaN or absurd value reaches the planner (an arc of radius 1e300 took 0 s, a dwell of 1e300 s
// was printed with 63 digits). README "Limits" lists them.
#pragma once

#include <optional>
#include <string>

#include "ncjoule/gcode.hpp"

namespace ncjoule::detail {

namespace limit {
constexpr double kLengthMm = 99'999.999;   // X Y Z I J K R Q U V W @, and positions, in G21
constexpr double kLengthInch = 9'999.9999; // the same in G20
constexpr double kAngleDeg = 99'999.999;   // A B C ^
constexpr double kFeed = 99'999'999;       // F: eight digits (LinuxCNC's 3D_Chips.ngc: F2250000)
constexpr double kSmallestFeed = 0.0001;   // F other than 0: the least input increment (in)
constexpr double kSpindleRpm = 1'000'000;  // S
constexpr double kDwellS = 99'999.999;     // G4 and the dwells of cycles: P99999999 in ms
constexpr double kOtherWord = 99'999'999;  // P L H D T E ...: eight digits
} // namespace limit

// The largest length in the program's units, and in mm.
inline double max_length(bool inch) {
  return inch ? limit::kLengthInch : limit::kLengthMm;
}
inline double max_length_mm(bool inch) {
  return inch ? limit::kLengthInch * 25.4 : limit::kLengthMm;
}

// Why a word's value (finite, in program units) is out of range, or nothing when it is not.
std::optional<std::string> word_out_of_range(char letter, double value, bool inch);

// Why a command about to be emitted holds a value no control would take (not finite, a
// position or dwell out of range), or nothing.
std::optional<std::string> command_out_of_range(const CanonCommand& c);

} // namespace ncjoule::detail
