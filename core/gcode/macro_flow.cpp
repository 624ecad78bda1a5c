// Fanuc Custom Macro B control flow, as the Fanuc, Haas and compatible controls run it:
// - "IF [<condition>] GOTO n": when the condition holds, the program goes on at block Nn.
// - "IF [<condition>] THEN <assignment>": the assignment runs when the condition holds.
// - "GOTO n": go on at block Nn (searched in the program being run).
// - "WHILE [<condition>] DO m ... END m" (m = 1-3): the blocks between run while the condition
//   holds; "DO m ... END m" without WHILE loops for ever (the loop guard stops it).
// A GOTO to a block that does not exist or a DO without its END is an alarm on the control.
#include "interpreter_impl.hpp"

#include <cmath>

#include "expression.hpp"

namespace ncjoule::detail {

bool Interpreter::macro_statement(const Block& b) {
  const MacroStatement& m = b.macro;
  double condition = 1;
  if (!m.condition.empty()) {
    std::string err;
    std::size_t off = 0;
    if (!evaluate(m.condition, params_, condition, err, off)) {
      error(m.column, err);
      return false;
    }
  }
  const bool holds = condition != 0;
  switch (m.kind) {
  case MacroFlow::If:
    if (m.then) return holds;
    if (holds) macro_goto(m);
    return false;
  case MacroFlow::Goto:
    macro_goto(m);
    return false;
  case MacroFlow::While:
    if (!holds) {
      if (auto end = macro_loop_match(pc_, m)) next_pc_ = *end + 1;
    }
    return false;
  case MacroFlow::End:
    if (auto start = macro_loop_match(pc_, m)) next_pc_ = *start; // WHILE tests again
    return false;
  case MacroFlow::Do:
  case MacroFlow::None:
    return false;
  }
  return false;
}

void Interpreter::macro_goto(const MacroStatement& m) {
  double value = 0;
  std::string err;
  std::size_t off = 0;
  if (!evaluate(m.target, params_, value, err, off)) {
    error(m.column, err);
    return;
  }
  const long n = saturate<long>(std::round(value));
  if (auto line = n_number_line(n)) {
    next_pc_ = *line;
    return;
  }
  error(m.column, "GOTO " + std::to_string(n) + ": there is no block N" + std::to_string(n) +
                      " in this program (the control stops with an alarm)");
  stop();
}

// The END m closing the WHILE/DO m at `line`, or the WHILE/DO m an END m at `line` closes:
// Fanuc forbids overlapping loops with the same number, so it is the nearest one.
std::optional<std::size_t> Interpreter::macro_loop_match(std::size_t line,
                                                         const MacroStatement& m) {
  if (auto it = macro_loop_matches_.find(line); it != macro_loop_matches_.end()) return it->second;
  const bool forward = m.kind != MacroFlow::End;
  const std::string number(m.target);
  Block scratch;
  std::optional<std::size_t> found;
  for (std::size_t i = line; forward ? i + 1 < line_count_ : i > 0;) {
    i = forward ? i + 1 : i - 1;
    lex_line(line_text(i), dialect_, scratch);
    const MacroFlow k = scratch.macro.kind;
    const bool opens = k == MacroFlow::While || k == MacroFlow::Do;
    if ((forward ? k == MacroFlow::End : opens) && scratch.macro.target == number) {
      found = i;
      break;
    }
  }
  if (!found) {
    error(m.column, forward ? "DO" + number + " has no END" + number + " after it"
                            : "END" + number + " has no WHILE ... DO" + number + " before it");
    stop();
    return std::nullopt;
  }
  macro_loop_matches_.emplace(line, *found);
  return found;
}

} // namespace ncjoule::detail
