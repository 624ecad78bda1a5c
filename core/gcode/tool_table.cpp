// Reading LinuxCNC tool tables: "T1 P1 Z1.5 D0.25 ;comment" lines.
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>

#include "expression.hpp"
#include "ncjoule/gcode.hpp"
#include "ncjoule/tool.hpp"

namespace ncjoule {

ToolTable parse_tool_table(const SourceFile& file, bool inch,
                           std::vector<Diagnostic>& diagnostics) {
  ToolTable table;
  const double scale = inch ? 25.4 : 1.0;
  for (std::size_t i = 0; i < file.lines.size(); ++i) {
    std::string_view line = file.line_text(i);
    ToolEntry entry;
    if (auto semi = line.find(';'); semi != std::string_view::npos) {
      entry.comment = std::string(line.substr(semi + 1));
      line = line.substr(0, semi);
    }
    bool have_t = false;
    std::size_t p = 0;
    while (p < line.size()) {
      const char c = char(std::toupper(static_cast<unsigned char>(line[p])));
      if (c == ' ' || c == '\t') {
        ++p;
        continue;
      }
      std::size_t q = p + 1;
      while (q < line.size() && line[q] != ' ' && line[q] != '\t')
        ++q;
      double value = 0;
      if (!detail::parse_plain_number(line.substr(p + 1, q - p - 1), value)) {
        diagnostics.push_back(
            {Severity::Error, file.path, int(i) + 1, int(p) + 1,
             std::string("expected a number after '") + c + "': the line is skipped"});
        have_t = false;
        break;
      }
      // Each value checked as a control would take it: a tool number in range (a larger one
      // would wrap into another tool's), a diameter and an offset a tool can have.
      auto refuse = [&](const std::string& why) {
        diagnostics.push_back({Severity::Error, file.path, int(i) + 1, int(p) + 1, why});
        have_t = false;
      };
      if (c == 'T') {
        if (value < 0 || value != std::floor(value) || value > kMaxToolNumber) {
          refuse("T must be a whole tool number from 0 to " + std::to_string(kMaxToolNumber) +
                 ": the line is skipped");
          break;
        }
        entry.number = int(value), have_t = true;
      } else if (c == 'Z') {
        if (std::abs(value * scale) > 1e5) {
          refuse("Z: a tool length offset beyond 100 m is no tool's: the line is skipped");
          break;
        }
        entry.z_offset = value * scale;
      } else if (c == 'D') {
        if (value < 0 || value * scale > 2000) {
          refuse("D must be a diameter from 0 to 2000 mm: the line is skipped");
          break;
        }
        entry.diameter = value * scale;
      }
      p = q;
    }
    if (have_t) table[entry.number] = entry;
  }
  return table;
}

} // namespace ncjoule
