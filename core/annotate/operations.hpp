// Operations: what runs from one tool change to the next, named after the comment a CAM post
// writes for it, with its time and energy.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/estimate.hpp"

namespace ncjoule::annotation {

struct Operation {
  int line = 0;     // 0-based line of the tool change (M6) that starts it
  int tool = 0;     // the tool it loads (the first time the line runs)
  std::string name; // as the post wrote it (not yet made safe); "T<n>" when no comment names it
  double time_s = 0;
  double energy_j = 0;
};

// The operations of a run, by the line of their tool change. Time and energy are summed over
// every command from a tool change to the next one in the order they run, so that subprograms
// count where they are called. `lines` holds the text of every source line (without annotations).
//
// The name is the nearest comment-only line above the tool change, looking up over lines that
// do not move the machine (M5, M9, T2, blank lines); else the first comment on the tool-change
// line itself; else "T" and the tool number.
std::map<int, Operation> find_operations(const std::vector<std::string_view>& lines,
                                         const Estimate& estimate);

} // namespace ncjoule::annotation
