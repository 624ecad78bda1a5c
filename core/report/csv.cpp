// The per-block results as CSV (comma separated, a header row, text quoted as RFC 4180 says when it
// holds a comma, a quote or a line break), written row by row. Columns are listed in
// docs/report.md.
#include <charconv>
#include <sstream>

#include "ncjoule/diagnostic.hpp"
#include "ncjoule/report.hpp"
#include "stock_source_name.hpp"

namespace ncjoule {
namespace {

// Shortest text that reads back to the same number.
template <class T> void number(std::string& out, T value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  out.append(text, result.ptr);
}

void quoted(std::string& out, std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) {
    out.append(text);
    return;
  }
  out.push_back('"');
  for (char ch : text) {
    if (ch == '"') out.push_back('"');
    out.push_back(ch);
  }
  out.push_back('"');
}

// Where the stock a line cuts came from (the setup it is in): "given", "program", "guessed" or
// "none"; a guessed one makes its volume, MRR, cutting power and energy guesses too.
const char* stock_of_line(const Estimate& e, int line) {
  if (!e.removal) return "none";
  const SetupSummary* setup = nullptr;
  for (const SetupSummary& s : e.setups)
    if (s.first_line <= line || !setup) setup = &s;
  return report_detail::stock_source_name(setup ? setup->stock_source : StockSource::None);
}

void row(std::string& out, const LineSummary& b, const Estimate& e) {
  number(out, b.line + 1);
  out.push_back(',');
  out.append(line_kind_name(b.kind));
  out.push_back(',');
  if (b.operation > 0 && b.operation <= e.operations.size())
    quoted(out, printable(e.operations[b.operation - 1].name)); // a comment: no raw ESC
  for (double v : {b.start_s, b.time_s}) {
    out.push_back(',');
    number(out, v);
  }
  for (float v : {b.length_mm, b.entry_speed_mm_s, b.exit_speed_mm_s, b.peak_speed_mm_s}) {
    out.push_back(',');
    number(out, v);
  }
  out.push_back(',');
  number(out, b.commands);
  out.push_back(',');
  number(out, b.removed_mm3);
  out.push_back(',');
  number(out, b.time_s > 0 ? b.removed_mm3 / b.time_s : 0.0);
  out.push_back(',');
  number(out, b.mrr_peak_mm3_s);
  out.push_back(',');
  number(out, b.time_s > 0 ? b.energy_j / b.time_s : 0.0);
  out.push_back(',');
  number(out, b.power_peak_w);
  out.push_back(',');
  number(out, b.energy_j);
  for (float v : b.components_j) {
    out.push_back(',');
    number(out, v);
  }
  out.push_back(',');
  out.append(stock_of_line(e, b.line));
  out.push_back('\n');
}

} // namespace

void write_estimate_csv(std::ostream& out, const Estimate& e) {
  std::string buffer = "line,kind,operation,start_s,time_s,length_mm,entry_speed_mm_s,"
                       "exit_speed_mm_s,peak_speed_mm_s,commands,removed_mm3,mrr_mm3_s,"
                       "mrr_peak_mm3_s,power_w,power_peak_w,energy_j";
  for (std::size_t i = 0; i < kPowerComponentCount; ++i)
    buffer += ',' + std::string(component_name(PowerComponent(i))) + "_j";
  buffer += ",stock\n";
  // Written in large pieces: a stream write per field is slow.
  for (const LineSummary& b : e.lines) {
    row(buffer, b, e);
    if (buffer.size() >= (1 << 16)) {
      out.write(buffer.data(), std::streamsize(buffer.size()));
      buffer.clear();
    }
  }
  out.write(buffer.data(), std::streamsize(buffer.size()));
}

std::string estimate_csv(const Estimate& e) {
  std::ostringstream out;
  write_estimate_csv(out, e);
  return out.str();
}

} // namespace ncjoule
