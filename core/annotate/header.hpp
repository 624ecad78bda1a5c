// The summary header: a few comment lines with the program's totals, their split by component,
// and the machine and constants the prediction used.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "marker.hpp"
#include "ncjoule/annotate.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/machine.hpp"

namespace ncjoule::annotation {

// The header's summary lines (marked comments, without line endings), each within the style's
// line length: totals, the time and energy split, the operations, the machine and the constants.
// A group of fields that does not fit on one line continues on the next, under the same label.
std::vector<std::string> summary_lines(const Estimate& estimate, const MachineProfile& machine,
                                       const WriteStyle& style);

// What the block comments of a file hold, for the KEYS lines that explain them.
struct KeyUse {
  BlockFields fields;
  bool inch = false;      // MRR in in^3/min
  bool load = false;      // some block has LOAD_PCT
  bool operation = false; // some block starts an operation (OP, OPT, OPE)
};

// The KEYS lines: each field the block comments hold, in the program's units, as whole
// sentences within the style's line length; and what the seal line is for.
std::vector<std::string> key_lines(const KeyUse& keys, const WriteStyle& style);

// One warning of the header: `head`, then the line it concerns (if any) as "L<n> ", then the
// message's first clause.
struct WarningText {
  std::string head;
  int line = 0;        // 1-based source line; 0: none
  std::string message; // as the summary prints it
  int count = 1;       // how many times the program gave it
};

// What the header warns of: the tools not simulated, then each distinct warning and error of the
// program with its count, the first few of them.
std::vector<WarningText> header_warnings(const Estimate& estimate);

// The header's warning lines, one per warning, after the summary, each naming its line as
// `line_in_output` maps it (1-based source line to 1-based line of the annotated file). Each is
// a whole sentence within the style's line length: the warning's first clause, or as much of it
// as ends at a clause or a word; the whole text is in the summary and the JSON.
std::vector<std::string> warning_lines(const std::vector<WarningText>& warnings,
                                       const WriteStyle& style,
                                       const std::function<int(int)>& line_in_output);

} // namespace ncjoule::annotation
