// Internal: how one changed block, a restore block and a mark are written (optimize.hpp). The
// plan asks it whether a changed block still fits the dialect's line length; the writer writes
// with it.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "ncjoule/gcode.hpp"
#include "ncjoule/optimize.hpp"

namespace ncjoule::optimize_detail {

// A feed (mm/min) in the program's units per minute, always with a decimal point (the Fanuc
// family reads "500" as 0.5 without one), up to 3 decimals (4 in inches), zeros trimmed: "5000.",
// "333.3", "23.622".
std::string format_feed(double mm_min, bool inch);

// OPEN content CLOSE in the dialect's comment syntax, upper case (the Fanuc family's, and
// readable in every controller's editor).
std::string mark_comment(std::string_view content, const Dialect& dialect);

// The block with the edit applied and its mark after its code; std::nullopt when the line is
// not a simple block or the result passes the dialect's line length.
std::optional<std::string> rewrite_block(std::string_view line, const Dialect& dialect,
                                         const BlockEdit& edit, bool inch);

// The block that puts back what the edit left different ("G1 F500. (NCJOPT RESTORE)");
// empty when it restores nothing.
std::string restore_block(const BlockEdit& edit, const Dialect& dialect, bool inch);

} // namespace ncjoule::optimize_detail
