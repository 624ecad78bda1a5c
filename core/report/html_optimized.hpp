// Internal: the part of a program's section that lists the blocks `ncjoule optimize` changed, so
// that a programmer reviewing an optimized program sees each change where it is.
#pragma once

#include <string>

#include "ncjoule/gcode.hpp"

namespace ncjoule::report_detail {

// The blocks of `source` that carry optimize's mark (docs/optimize.md), by rule, with their line
// and text; empty when the program was not written by optimize. The header's comment lines are
// left out: they say what the rules are, not where they changed something.
std::string optimized_blocks_section(const SourceFile& source);

} // namespace ncjoule::report_detail
