// The split of a run into operations: from one tool change to the next, named after the comment
// the CAM post wrote for the operation.
#include <cctype>
#include <cmath>
#include <map>
#include <set>

#include "ncjoule/report.hpp"
#include "source_comments.hpp"

namespace ncjoule {
namespace {

// How far above a tool change its name is looked for, so that a file without comments costs no
// more than a few lines per tool change.
constexpr int kNameSearchLines = 40;

// A tool-list comment of the program header, as CAM posts write it: "T1 D=12. CR=0. - ...".
bool is_tool_definition(const std::string& comment) {
  std::size_t i = 0;
  if (i >= comment.size() || (comment[i] != 'T' && comment[i] != 't')) return false;
  for (++i; i < comment.size() && std::isdigit(static_cast<unsigned char>(comment[i]));)
    ++i;
  return i > 1 && comment.find("D=") != std::string::npos;
}

// The first comment of a comment-only line that may name an operation, or empty.
std::string name_on(const SourceFile& source, const Dialect& dialect, int line) {
  const auto comments =
      report_detail::line_comments(source.line_text(static_cast<std::size_t>(line)), dialect);
  if (comments.has_code || comments.texts.empty()) return {};
  return comments.texts.front();
}

// Where CAM posts put the operation's name: on a comment line just above the tool change (Fusion
// and most posts), on the tool-change line itself, or on a comment line just below it (some Haas
// and Fanuc posts). Looking up passes lines that do not move the machine (M5, M9, T2, blank) and
// stops at a move, another tool change or the header's tool list; looking down stops at the first
// move.
std::string operation_name(const SourceFile& source, const Dialect& dialect, int tool_change_line,
                           const std::set<int>& stop_lines, int tool) {
  const int lowest = std::max(0, tool_change_line - kNameSearchLines);
  for (int i = tool_change_line - 1; i >= lowest; --i) {
    if (stop_lines.count(i)) break;
    const std::string name = name_on(source, dialect, i);
    if (is_tool_definition(name)) break;
    if (!name.empty()) return name;
  }
  const auto own = report_detail::line_comments(
      source.line_text(static_cast<std::size_t>(tool_change_line)), dialect);
  for (const std::string& text : own.texts)
    if (!text.empty() && !is_tool_definition(text)) return text;
  const int highest =
      std::min(static_cast<int>(source.lines.size()) - 1, tool_change_line + kNameSearchLines);
  for (int i = tool_change_line + 1; i <= highest; ++i) {
    if (stop_lines.count(i)) break;
    const std::string name = name_on(source, dialect, i);
    if (!name.empty() && !is_tool_definition(name)) return name;
  }
  return "T" + std::to_string(tool);
}

void add_command(OperationSummary& op, const Estimate& e, std::size_t k) {
  const TimedCommand& c = e.timeline.commands[k];
  op.time_s += c.duration_s;
  if (k < e.energy.commands.size()) {
    op.energy_j += e.energy.commands[k].energy_j;
    for (std::size_t i = 0; i < kPowerComponentCount; ++i)
      op.components_j[i] += e.energy.commands[k].components_j[i];
  }
  if (e.removal && k < e.removal->commands.size())
    op.removed_mm3 += e.removal->commands[k].removed_mm3;
}

} // namespace

std::vector<OperationSummary> operations(const SourceFile& source, const Estimate& e) {
  // Index 0 gathers what runs before the first tool change; it is dropped below when empty.
  std::vector<OperationSummary> ops(1);
  ops[0].line = -1;
  std::map<int, std::size_t> by_line;
  std::size_t current = 0;
  const auto& timed = e.timeline.commands;
  for (std::size_t k = 0; k < timed.size(); ++k) {
    const TimedCommand& c = timed[k];
    const bool valid_line = c.line >= 0 && static_cast<std::size_t>(c.line) < source.lines.size();
    if (c.kind == CanonKind::ChangeTool && valid_line) {
      const auto [it, inserted] = by_line.try_emplace(c.line, ops.size());
      if (inserted) {
        OperationSummary op;
        op.line = c.line;
        op.start_s = c.start_s;
        if (c.command < e.toolpath.commands.size())
          op.tool = static_cast<int>(std::lround(e.toolpath.commands[c.command].value));
        ops.push_back(op);
      }
      current = it->second;
    } else if (current == 0 && ops[0].tool == 0 && c.command < e.toolpath.commands.size()) {
      ops[0].tool = e.toolpath.commands[c.command].state.tool; // a tool already in the spindle
    }
    add_command(ops[current], e, k);
  }

  // Names last: looking up stops at lines that move the machine and at other tool changes.
  std::set<int> stop_lines;
  for (const LineSummary& s : e.lines)
    if (s.has_move) stop_lines.insert(s.line);
  for (const auto& [line, index] : by_line)
    stop_lines.insert(line);
  for (std::size_t i = 1; i < ops.size(); ++i)
    ops[i].name = operation_name(source, e.dialect, ops[i].line, stop_lines, ops[i].tool);

  const bool lead_empty = ops[0].time_s == 0 && ops[0].energy_j == 0 && ops[0].removed_mm3 == 0;
  if (ops.size() == 1) {
    ops[0].name = "program";
  } else if (lead_empty) {
    ops.erase(ops.begin());
  } else {
    ops[0].name = "before first tool change";
  }
  for (OperationSummary& op : ops) {
    const double share = e.energy.energy_j > 0 ? op.energy_j / e.energy.energy_j : 0.0;
    op.co2_kg = e.energy.co2_kg * share;
    op.cost = e.energy.cost * share;
  }
  return ops;
}

} // namespace ncjoule
