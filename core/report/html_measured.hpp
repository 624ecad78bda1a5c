// Internal: the part of a program's section that sets what the machine's log measured over the
// prediction (ncjoule report --log).
#pragma once

#include <string>
#include <vector>

#include "ncjoule/report.hpp"

namespace ncjoule::report_detail {

// The line reached over time, measured over predicted, and the tables of the runs, the
// operations and the worst blocks, measured against predicted. `id` prefixes the chart's id.
std::string measured_section(const std::string& id, const MeasuredOverlay& measured,
                             const std::vector<OperationSummary>& operations,
                             const std::string& predicted_color);

} // namespace ncjoule::report_detail
