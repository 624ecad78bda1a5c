// The range checks of value_limits.hpp: which bound a word's letter has, and the checks of a
// command as it is emitted (the last stop before the planner).
#include "value_limits.hpp"

#include <cctype>
#include <cmath>

namespace ncjoule::detail {
namespace {

// The bound as it is written in a message: "99,999.999".
std::string bound_text(double bound) {
  if (bound == limit::kLengthMm || bound == limit::kAngleDeg || bound == limit::kDwellS)
    return "99,999.999";
  if (bound == limit::kLengthInch) return "9,999.9999";
  if (bound == limit::kOtherWord) return "99,999,999";
  return "1,000,000";
}

bool within(double value, double bound) {
  // The bound itself is in range, whatever the rounding of a product with it.
  return std::abs(value) <= bound * (1 + 1e-12);
}

} // namespace

std::optional<std::string> word_out_of_range(char letter, double value, bool inch) {
  // Made only for a message: every word of a program comes through here.
  auto word = [letter] {
    return std::string(1, char(std::toupper(static_cast<unsigned char>(letter))));
  };
  if (!std::isfinite(value)) return word() + " is not a finite number";
  switch (letter) {
  case 'x':
  case 'y':
  case 'z':
  case 'i':
  case 'j':
  case 'k':
  case 'r':
  case 'q':
  case 'u':
  case 'v':
  case 'w':
  case '@':
    if (within(value, max_length(inch))) return std::nullopt;
    return word() + " is out of range: lengths go to +-" + bound_text(max_length(inch)) +
           (inch ? " in" : " mm") + ", the most an industrial control takes";
  case 'a':
  case 'b':
  case 'c':
  case '^':
    if (within(value, limit::kAngleDeg)) return std::nullopt;
    return word() + " is out of range: angles go to +-99,999.999 degrees, the most an industrial "
                    "control takes";
  case 'f':
    if (value != 0 && std::abs(value) < limit::kSmallestFeed)
      return "F is out of range: a feed rate other than 0 is at least 0.0001";
    if (within(value, limit::kFeed)) return std::nullopt;
    return "F is out of range: feed rates go to 99,999,999 (eight digits)";
  case 's':
    if (within(value, limit::kSpindleRpm)) return std::nullopt;
    return "S is out of range: spindle speeds go to 1,000,000 rpm";
  default:
    if (within(value, limit::kOtherWord)) return std::nullopt;
    return word() + " is out of range: values go to +-99,999,999 (eight digits)";
  }
}

std::optional<std::string> command_out_of_range(const CanonCommand& c) {
  const double numbers[] = {c.start.x,
                            c.start.y,
                            c.start.z,
                            c.start.a,
                            c.start.b,
                            c.start.c,
                            c.end.x,
                            c.end.y,
                            c.end.z,
                            c.end.a,
                            c.end.b,
                            c.end.c,
                            c.centre_first,
                            c.centre_second,
                            c.value,
                            c.state.feed,
                            c.state.spindle_rpm,
                            c.state.path_tolerance};
  for (double v : numbers)
    if (!std::isfinite(v)) return "a value of this block is not a finite number";
  if (is_move(c.kind)) {
    const double bound = max_length_mm(c.state.inch);
    for (double v : {c.end.x, c.end.y, c.end.z})
      if (!within(v, bound))
        return std::string("the move goes out of range: positions go to +-") +
               bound_text(max_length(c.state.inch)) + (c.state.inch ? " in" : " mm") +
               ", the most an industrial control takes";
  }
  if (c.kind == CanonKind::Dwell && !within(c.value, limit::kDwellS))
    return "dwell out of range: dwells go to 99,999.999 s (P99999999 in ms), the most an "
           "industrial control takes";
  return std::nullopt;
}

} // namespace ncjoule::detail
