// G and M codes as numbers: their modal groups and names, and the codes that only hint the
// planner. Codes are G numbers times 10 (G61.1 -> 611).
#pragma once

#include <algorithm>
#include <string>

#include "interpreter_impl.hpp"

namespace ncjoule::detail {

// Modal group of a G code (0 non-modal, 1 motion, 2 plane, ...); -1 for codes of no group.
int g_group(int code);
std::string g_name(int code); // "G61.1"
// Inline: every block asks a dozen times.
inline bool has_g(const BlockValues& v, int code) {
  return std::find(v.g.begin(), v.g.end(), code) != v.g.end();
}
inline bool has_m(const BlockValues& v, int code) {
  return std::find(v.m.begin(), v.m.end(), code) != v.m.end();
}
// Codes that change only how a controller blends or smooths the path (see codes.cpp).
bool is_planner_hint_g(int code, const Dialect& dialect);
std::string number_text(double value); // %g

} // namespace ncjoule::detail
