// The per-block results as CSV (comma separated, a header row, text quoted as RFC 4180 says when it
// holds a comma, a quote or a line break), written row by row. Columns are listed in
// docs/report.md.
#include <charconv>
#include <sstream>

#include "ncjoule/report.hpp"

namespace ncjoule {
namespace {

// Shortest text that reads back to the same number.
template <class T> void number(std::ostream& out, T value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  out.write(text, result.ptr - text);
}

void quoted(std::ostream& out, std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) {
    out << text;
    return;
  }
  out.put('"');
  for (char ch : text) {
    if (ch == '"') out.put('"');
    out.put(ch);
  }
  out.put('"');
}

} // namespace

void write_estimate_csv(std::ostream& out, const Estimate& e) {
  out << "line,kind,operation,start_s,time_s,length_mm,entry_speed_mm_s,exit_speed_mm_s,"
         "peak_speed_mm_s,commands,removed_mm3,mrr_mm3_s,mrr_peak_mm3_s,power_w,power_peak_w,"
         "energy_j";
  for (std::size_t i = 0; i < kPowerComponentCount; ++i)
    out << ',' << component_name(PowerComponent(i)) << "_j";
  out << '\n';
  for (const LineSummary& b : e.lines) {
    out << b.line + 1 << ',' << line_kind_name(b.kind) << ',';
    if (b.operation > 0 && b.operation <= e.operations.size())
      quoted(out, e.operations[b.operation - 1].name);
    out << ',';
    number(out, b.start_s);
    out << ',';
    number(out, b.time_s);
    for (float v : {b.length_mm, b.entry_speed_mm_s, b.exit_speed_mm_s, b.peak_speed_mm_s}) {
      out << ',';
      number(out, v);
    }
    out << ',' << b.commands << ',';
    number(out, b.removed_mm3);
    out << ',';
    number(out, b.time_s > 0 ? b.removed_mm3 / b.time_s : 0.0);
    out << ',';
    number(out, b.mrr_peak_mm3_s);
    out << ',';
    number(out, b.time_s > 0 ? b.energy_j / b.time_s : 0.0);
    out << ',';
    number(out, b.power_peak_w);
    out << ',';
    number(out, b.energy_j);
    for (float v : b.components_j) {
      out << ',';
      number(out, v);
    }
    out << '\n';
  }
}

std::string estimate_csv(const Estimate& e) {
  std::ostringstream out;
  write_estimate_csv(out, e);
  return out.str();
}

} // namespace ncjoule
