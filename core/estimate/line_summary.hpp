// Internal: per-line summaries of an estimate.
#pragma once

#include <vector>

#include "ncjoule/estimate.hpp"

namespace ncjoule {

std::vector<LineSummary> summarise_lines(const SourceFile& source, const Dialect& dialect,
                                         const Timeline& timeline, const RemovalResult* removal,
                                         const EnergyResult& energy);

} // namespace ncjoule
