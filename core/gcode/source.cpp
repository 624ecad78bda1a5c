// Splitting NC text into lines, and formatting diagnostics.
#include "ncjoule/gcode.hpp"

namespace ncjoule {

SourceFile make_source(std::string path, std::string text) {
  SourceFile file;
  file.path = std::move(path);
  file.text = std::move(text);
  const std::string& t = file.text;
  std::size_t begin = 0;
  const std::size_t n = t.size();
  while (begin < n) {
    std::size_t i = begin;
    while (i < n && t[i] != '\n' && t[i] != '\r')
      ++i;
    LineSpan span{begin, i - begin, 0};
    if (i < n) {
      span.eol_length = (t[i] == '\r' && i + 1 < n && t[i + 1] == '\n') ? 2 : 1;
    }
    file.lines.push_back(span);
    begin = i + span.eol_length;
  }
  return file;
}

Diagnostic TextOrigin::at(std::size_t offset, std::string message, Severity severity) const {
  const int column_there = column > 0 && line > 0 ? column + int(offset) : 0;
  return {severity, file, line, column_there, std::move(message)};
}

std::string format_diagnostic(const Diagnostic& d) {
  std::string out = d.file;
  if (d.line > 0) {
    out += ':' + std::to_string(d.line);
    if (d.column > 0) out += ':' + std::to_string(d.column);
  }
  switch (d.severity) {
  case Severity::Note:
    out += ": note: ";
    break;
  case Severity::Warning:
    out += ": warning: ";
    break;
  case Severity::Error:
    out += ": error: ";
    break;
  }
  // Messages quote the program; its control bytes (NUL, ESC, ...) are shown escaped, so that a
  // program cannot drive the terminal the message is printed on.
  for (const char ch : d.message) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f) {
      static const char digits[] = "0123456789abcdef";
      out += "\\x";
      out += digits[c >> 4];
      out += digits[c & 15];
    } else {
      out += ch;
    }
  }
  return out;
}

} // namespace ncjoule
