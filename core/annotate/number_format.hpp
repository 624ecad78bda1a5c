// Compact number formats for annotations (docs/annotation.md): short enough to sit on a block,
// precise enough to compare two blocks, and made of safe characters only (no exponent, no '+').
#pragma once

#include <string>
#include <string_view>

namespace ncjoule::annotation {

// `digits` significant digits, never more than `max_decimals` decimals, trailing zeros and a
// trailing point dropped: 34.5, 1.23, 0.0123, 1235. Rounds to "0" rather than "-0".
std::string format_significant(double value, int digits, int max_decimals);

// floor(log10(v)) for a finite v > 0, exactly as the library's log10 gives it (the place of the
// first significant digit), mostly without calling log10.
int decimal_magnitude(double v);

// Durations: "0.012s", "1.23s", "12.3s", "1m05s", "1h02m03s" (whole seconds from one minute on).
std::string format_duration(double seconds);

// A value with an SI prefix chosen so that it shows 3 significant digits: "450J", "1.23kJ",
// "4.5MJ", "850W", "1.2kW".
std::string format_si(double value, std::string_view unit);

// User text (an operation comment, a machine name) as one safe token: characters that are not
// letters, digits or . , - become '_', runs of '_' collapse, at most `max_length` characters.
std::string safe_token(std::string_view text, std::size_t max_length);

} // namespace ncjoule::annotation
