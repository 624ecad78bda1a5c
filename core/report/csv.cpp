// The per-block results as CSV (comma separated, a header row, text quoted as RFC 4180 says when it
// holds a comma, a quote or a line break). Columns are listed in docs/report.md.
#include <charconv>
#include <map>

#include "ncjoule/report.hpp"

namespace ncjoule {
namespace {

// Shortest text that reads back to the same double.
std::string number(double value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

std::string quoted(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char ch : text) {
    if (ch == '"') out += '"';
    out += ch;
  }
  return out + '"';
}

// The operation each source line belongs to: the one in which the line first runs.
std::map<int, std::string> operation_of_lines(const SourceFile& source, const Estimate& e) {
  const std::vector<OperationSummary> ops = operations(source, e);
  std::map<int, std::string> names;
  std::size_t op = 0;
  bool started = !ops.empty() && ops.front().line < 0;
  for (const TimedCommand& c : e.timeline.commands) {
    if (c.kind == CanonKind::ChangeTool) {
      for (std::size_t i = 0; i < ops.size(); ++i)
        if (ops[i].line == c.line) {
          op = i;
          started = true;
        }
    }
    if (started && !ops.empty()) names.try_emplace(c.line, ops[op].name);
  }
  return names;
}

} // namespace

std::string estimate_csv(const Estimate& e, const SourceFile& source) {
  std::string out = "line,kind,operation,start_s,time_s,length_mm,entry_speed_mm_s,"
                    "exit_speed_mm_s,peak_speed_mm_s,commands,removed_mm3,mrr_mm3_s,"
                    "mrr_peak_mm3_s,power_w,power_peak_w,energy_j";
  for (std::size_t i = 0; i < kPowerComponentCount; ++i)
    out += ',' + std::string(component_name(PowerComponent(i))) + "_j";
  out += "\n";
  const std::map<int, std::string> op_names = operation_of_lines(source, e);
  for (const LineSummary& b : e.lines) {
    const auto name = op_names.find(b.line);
    out += std::to_string(b.line + 1) + ',' + quoted(b.kind) + ',' +
           quoted(name != op_names.end() ? name->second : std::string()) + ',' + number(b.start_s) +
           ',' + number(b.time_s) + ',' + number(b.length_mm) + ',' + number(b.entry_speed_mm_s) +
           ',' + number(b.exit_speed_mm_s) + ',' + number(b.peak_speed_mm_s) + ',' +
           std::to_string(b.commands) + ',' + number(b.removed_mm3) + ',' +
           number(b.time_s > 0 ? b.removed_mm3 / b.time_s : 0.0) + ',' + number(b.mrr_peak_mm3_s) +
           ',' + number(b.time_s > 0 ? b.energy_j / b.time_s : 0.0) + ',' + number(b.power_peak_w) +
           ',' + number(b.energy_j);
    for (double v : b.components_j)
      out += ',' + number(v);
    out += "\n";
  }
  return out;
}

} // namespace ncjoule
