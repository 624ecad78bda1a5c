// The summary header: a few comment lines with the program's totals, their split by component,
// and the machine and constants the prediction used.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "marker.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/machine.hpp"

namespace ncjoule::annotation {

// The header's summary lines (marked comments, without line endings), each within the style's
// line length: totals, the time and energy split, the operations, the machine and the constants.
// A group of fields that does not fit on one line continues on the next, under the same label.
std::vector<std::string> summary_lines(const Estimate& estimate, const MachineProfile& machine,
                                       const WriteStyle& style);

// One warning of the header: `head`, then the line it concerns (if any) as "L<n> ", then `tail`.
struct WarningText {
  std::string head;
  int line = 0; // 1-based source line; 0: none
  std::string tail;
};

// What the header warns of: the tools not simulated, then each distinct warning and error of the
// program with its count, the first few of them.
std::vector<WarningText> header_warnings(const Estimate& estimate);

// The header's warning lines, one per warning, after the summary, each naming its line as
// `line_in_output` maps it (1-based source line to 1-based line of the annotated file).
std::vector<std::string> warning_lines(const std::vector<WarningText>& warnings,
                                       const WriteStyle& style,
                                       const std::function<int(int)>& line_in_output);

} // namespace ncjoule::annotation
