// The summary header: a few comment lines with the program's totals, their split by component,
// and the machine and constants the prediction used.
#pragma once

#include <string>
#include <vector>

#include "marker.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/machine.hpp"

namespace ncjoule::annotation {

// The header's lines (marked comments, without line endings), each within the style's line
// length: a group of fields that does not fit on one line continues on the next, under the same
// label.
std::vector<std::string> header_lines(const Estimate& estimate, const MachineProfile& machine,
                                      const WriteStyle& style);

} // namespace ncjoule::annotation
