#include "operations.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "line_layout.hpp"

namespace ncjoule::annotation {
namespace {

// How far above a tool change its name is looked for, so that a file without comments costs
// no more than a few lines per tool change.
constexpr int kNameSearchLines = 40;

std::string operation_name(const std::vector<std::string_view>& lines, int tool_change_line,
                           const std::set<int>& stop_lines, int tool) {
  const int lowest = std::max(0, tool_change_line - kNameSearchLines);
  for (int i = tool_change_line - 1; i >= lowest; --i) {
    if (stop_lines.count(i)) break;
    const std::string_view text = lines[static_cast<std::size_t>(i)];
    if (is_comment_only(text)) {
      const std::string_view name = first_comment(text);
      if (!name.empty()) return std::string(name);
    }
  }
  const std::string_view own = first_comment(lines[static_cast<std::size_t>(tool_change_line)]);
  if (!own.empty()) return std::string(own);
  return "T" + std::to_string(tool);
}

} // namespace

std::map<int, Operation> find_operations(const std::vector<std::string_view>& lines,
                                         const Estimate& estimate) {
  std::map<int, Operation> operations;
  const auto& timed = estimate.timeline.commands;
  const auto& energy = estimate.energy.commands;
  Operation* current = nullptr;
  for (std::size_t k = 0; k < timed.size(); ++k) {
    const TimedCommand& c = timed[k];
    if (c.kind == CanonKind::ChangeTool && c.line >= 0 &&
        static_cast<std::size_t>(c.line) < lines.size()) {
      const bool first_run = operations.count(c.line) == 0;
      current = &operations[c.line];
      current->line = c.line;
      if (first_run && c.command < estimate.toolpath.commands.size())
        current->tool = static_cast<int>(std::lround(estimate.toolpath.commands[c.command].value));
    }
    if (!current) continue;
    current->time_s += c.duration_s;
    if (k < energy.size()) current->energy_j += energy[k].energy_j;
  }
  // Names last: looking up stops at lines that move the machine and at other tool changes.
  std::set<int> stop_lines;
  for (const LineSummary& s : estimate.lines)
    if (s.has_move) stop_lines.insert(s.line);
  for (const auto& [line, op] : operations)
    stop_lines.insert(line);
  for (auto& [line, op] : operations)
    op.name = operation_name(lines, line, stop_lines, op.tool);
  return operations;
}

} // namespace ncjoule::annotation
