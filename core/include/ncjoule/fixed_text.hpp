// Numbers with a fixed count of decimals, written as printf's "%.Nf" writes them, byte for byte,
// without printf: the canonical stream (`ncjoule canon`) and the annotations print one or more
// numbers for every block of a program, and printf's parsing of its format and its exact decimal
// expansion were most of their time.
#pragma once

#include <string>

namespace ncjoule {

// Appends `value` with `decimals` digits after the point, exactly as std::snprintf with "%.*f"
// (round to nearest, ties to even, on the exact binary value; "-0.0000" for a negative value
// that rounds to zero; "nan", "inf" and "-inf" as printf spells them). Any `decimals` >= 0.
void append_fixed(std::string& out, double value, int decimals);

// The fast path of append_fixed, for callers that build a line in a buffer of their own: writes
// the text at `out` (which must have room for kFixedFastChars characters, all of which it may
// overwrite; the text is shorter) and returns where the text ends, or nullptr,
// writing nothing, for what only printf writes right (decimals past 9, magnitudes from 2^40 /
// 10^decimals up, a value a hair from a rounding half, and non-finite values).
inline constexpr int kFixedFastChars = 32;
char* write_fixed_fast(char* out, double value, int decimals);

// The same, returned.
std::string fixed_text(double value, int decimals);

} // namespace ncjoule
