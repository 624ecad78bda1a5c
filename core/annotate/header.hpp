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

// The header's warning lines, one per distinct warning, after the summary. A warning names the
// line it concerns as `line_in_output` maps it (1-based source line to 1-based line of the
// annotated file); how many lines there are does not depend on it.
std::vector<std::string> warning_lines(const Estimate& estimate, const WriteStyle& style,
                                       const std::function<int(int)>& line_in_output);

} // namespace ncjoule::annotation
