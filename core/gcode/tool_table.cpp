// Reading LinuxCNC tool tables: "T1 P1 Z1.5 D0.25 ;comment" lines.
#include <cctype>
#include <cstdlib>

#include "expression.hpp"
#include "ncjoule/gcode.hpp"

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
        diagnostics.push_back({Severity::Error, file.path, int(i) + 1, int(p) + 1,
                               std::string("expected a number after '") + c + "'"});
        break;
      }
      if (c == 'T')
        entry.number = detail::saturate<int>(value), have_t = true;
      else if (c == 'Z')
        entry.z_offset = value * scale;
      else if (c == 'D')
        entry.diameter = value * scale;
      p = q;
    }
    if (have_t) table[entry.number] = entry;
  }
  return table;
}

} // namespace ncjoule
