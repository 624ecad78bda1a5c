// Numeric CSV tables for calibration and power logs, with errors that point at the cell.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "ncjoule/calibrate.hpp"
#include "ncjoule/text.hpp"
#include "ncjoule/text_file.hpp"

namespace ncjoule {
namespace {

// A column's name as it is looked up: lower case, without the quotes spreadsheet exports put
// around headers.
std::string header_name(std::string_view s) {
  std::string out = to_lower(s);
  // Spreadsheet exports quote their headers.
  if (out.size() >= 2 && out.front() == '"' && out.back() == '"')
    out = out.substr(1, out.size() - 2);
  return out;
}

struct Field {
  std::string_view text;
  int column = 1; // 1-based character column of the field's first character
};

std::vector<Field> split(std::string_view line, char separator) {
  std::vector<Field> fields;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = line.find(separator, begin);
    const std::string_view raw =
        line.substr(begin, end == std::string_view::npos ? end : end - begin);
    std::size_t lead = 0;
    while (lead < raw.size() && std::isspace(static_cast<unsigned char>(raw[lead])))
      ++lead;
    fields.push_back({trim(raw), static_cast<int>(begin + lead + 1)});
    if (end == std::string_view::npos) break;
    begin = end + 1;
  }
  return fields;
}

} // namespace

std::optional<std::size_t> NumericCsv::column(std::string_view name) const {
  for (std::size_t i = 0; i < columns.size(); ++i)
    if (columns[i] == name) return i;
  return std::nullopt;
}

std::optional<NumericCsv> parse_numeric_csv(std::string path, std::string_view text,
                                            std::vector<Diagnostic>& diagnostics) {
  NumericCsv csv;
  csv.path = std::move(path);
  auto error = [&](int line, int column, std::string message) {
    diagnostics.push_back({Severity::Error, csv.path, line, column, std::move(message)});
  };
  char separator = ',';
  bool have_header = false;
  int line_number = 0;
  std::size_t pos = 0;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") pos = 3; // byte-order mark of spreadsheet exports
  while (pos <= text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    ++line_number;
    pos = end + 1;
    if (trim(line).empty() || trim(line).front() == '#') {
      if (end == text.size()) break;
      continue;
    }
    if (!have_header) {
      if (line.find(',') == std::string_view::npos && line.find(';') != std::string_view::npos)
        separator = ';';
      for (const Field& f : split(line, separator)) {
        if (f.text.empty()) {
          error(line_number, f.column, "empty column name in the header");
          return std::nullopt;
        }
        csv.columns.push_back(header_name(f.text));
      }
      have_header = true;
    } else {
      const auto fields = split(line, separator);
      if (fields.size() != csv.columns.size()) {
        error(line_number, 0,
              "expected " + std::to_string(csv.columns.size()) + " fields (" +
                  std::to_string(csv.columns.size()) + " columns in the header), found " +
                  std::to_string(fields.size()));
      } else {
        std::vector<double> row(fields.size());
        std::vector<int> columns(fields.size());
        bool ok = true;
        for (std::size_t i = 0; i < fields.size(); ++i) {
          columns[i] = fields[i].column;
          if (const auto value = parse_number(fields[i].text)) {
            row[i] = *value;
          } else {
            error(line_number, fields[i].column,
                  "column '" + csv.columns[i] + "': '" + std::string(fields[i].text) +
                      "' is not a number");
            ok = false;
          }
        }
        if (ok) {
          csv.rows.push_back(std::move(row));
          csv.row_lines.push_back(line_number);
          csv.cell_columns.push_back(std::move(columns));
        }
      }
    }
    if (end == text.size()) break;
  }
  if (!have_header) {
    error(1, 0, "no header line: the file is empty");
    return std::nullopt;
  }
  return csv;
}

std::optional<NumericCsv> read_numeric_csv(const std::string& path,
                                           std::vector<Diagnostic>& diagnostics) {
  // A power log of a day at 10 Hz is tens of megabytes.
  const std::optional<std::string> text =
      read_text_file(path, "a CSV file", diagnostics, std::size_t(256) << 20);
  if (!text) return std::nullopt;
  return parse_numeric_csv(path, *text, diagnostics);
}

} // namespace ncjoule
