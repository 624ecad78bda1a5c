// Internal: what a program's comments say of how its G41/G42 were posted (CutterCompMode).
//
// Mastercam writes the compensation type of each tool in its tool lines:
//   "( T1 | FLAT END MILL - 6 | H1 | D1 | CONTROL COMP | TOOL DIA. - 6. )", "... | WEAR COMP | ..."
// ("REVERSE WEAR COMP" for reverse wear); some Fusion posts write a comment per operation
// ("CUTTER COMP WEAR TYPE", "CUTTER COMP CONTROL TYPE"). Fusion's own posts write nothing: the
// machine profile's or the job file's cutter_compensation says it for them.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::detail {

struct CompModeHint {
  CutterCompMode mode = CutterCompMode::Control;
  int line = 0;     // 1-based line of the comment
  std::string text; // the words that told ("WEAR COMP")
};

struct CompModeHints {
  std::map<int, CompModeHint> by_tool; // tool lines, by their T and D numbers
  // Comments of no tool, in the order of their lines: each holds from its line on.
  std::vector<std::pair<std::size_t, CompModeHint>> from_line;
  // What holds for a G41/G42 on `line` (0-based) naming `d` with `tool` in the spindle.
  std::optional<CompModeHint> at(std::size_t line, int d, int tool) const;
};

// Reads every comment of the program once.
CompModeHints scan_comp_mode_hints(const SourceFile& source, const Dialect& dialect);

// What one comment says, if anything (exposed for tests).
std::optional<CompModeHint> comp_mode_of_comment(std::string_view comment);

} // namespace ncjoule::detail
