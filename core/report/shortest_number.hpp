// Internal: a finite number in the shortest form that reads back to it, character for character
// what std::to_chars(first, last, value) writes (its plain form: fixed or scientific notation,
// whichever is shorter, fixed on a tie), about three times as fast. The digits come from fmt's
// Dragonbox (the shortest correctly rounded digits, as Ryu in libstdc++ gives them); the
// notation is chosen and written here.
#pragma once

namespace ncjoule::report_detail {

// Longest form written, with its sign: "-2.2250738585072014e-308".
inline constexpr int kShortestNumberMaxChars = 24;
// What p must have room for: the digits are copied in fixed pieces, and bytes past the end
// returned may be written over.
inline constexpr int kShortestNumberRoom = 40;

// Writes `value` (finite) at p, which has room for kShortestNumberRoom; returns the end.
char* write_shortest(char* p, double value);
// A float's own shortest form ("0.1", not the double's "0.10000000149011612").
char* write_shortest(char* p, float value);

} // namespace ncjoule::report_detail
