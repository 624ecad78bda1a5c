// Splitting NC text into lines, and formatting diagnostics.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "ncjoule/gcode.hpp"

namespace ncjoule {

std::size_t count_lines(std::string_view t) {
  // Line feeds counted at memchr's speed; a lone CR (rare) by a byte-by-byte pass.
  std::size_t lines = 1 + std::size_t(std::count(t.begin(), t.end(), '\n'));
  if (t.find('\r') != std::string_view::npos)
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t[i] == '\r' && (i + 1 == t.size() || t[i + 1] != '\n')) ++lines;
  return lines;
}

SourceFile make_source(std::string path, std::string text) {
  SourceFile file;
  file.path = std::move(path);
  file.text = std::move(text);
  const std::string& t = file.text;
  std::size_t begin = 0;
  const std::size_t n = t.size();
  if (t.find('\r') == std::string::npos) {
    // Line feeds alone (nearly every program): found by memchr, the lines counted first. Byte by
    // byte, with the list growing, this was a twentieth of estimating a 1M-line program, before
    // anything else could start.
    file.lines.reserve(count_lines(t));
    while (begin < n) {
      const void* found = std::memchr(t.data() + begin, '\n', n - begin);
      const std::size_t i = found ? std::size_t(static_cast<const char*>(found) - t.data()) : n;
      file.lines.push_back(LineSpan{begin, i - begin, std::uint8_t(i < n ? 1 : 0)});
      begin = i + 1;
    }
    return file;
  }
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

namespace {

// A code point that could make a terminal or an editor show something else than the message:
// C1 controls (U+0080 to U+009F), the bidirectional overrides and isolates that reorder text
// (U+202A to U+202E, U+2066 to U+2069), the direction marks (U+200E, U+200F, U+061C), and the
// line and paragraph separators.
bool is_deceptive(std::uint32_t c) {
  return (c >= 0x80 && c <= 0x9f) || (c >= 0x202a && c <= 0x202e) || (c >= 0x2066 && c <= 0x2069) ||
         c == 0x200e || c == 0x200f || c == 0x061c || c == 0x2028 || c == 0x2029;
}

// Length of the UTF-8 sequence at text[i] and its code point; 0 when the bytes are not UTF-8.
std::size_t utf8_at(std::string_view text, std::size_t i, std::uint32_t& code) {
  const auto c = static_cast<unsigned char>(text[i]);
  const std::size_t n = c >= 0xc2 && c < 0xe0   ? 2
                        : c >= 0xe0 && c < 0xf0 ? 3
                        : c >= 0xf0 && c < 0xf5 ? 4
                                                : 0;
  if (n == 0 || i + n > text.size()) return 0;
  code = c & (0x7f >> n);
  for (std::size_t k = 1; k < n; ++k) {
    const auto b = static_cast<unsigned char>(text[i + k]);
    if ((b & 0xc0) != 0x80) return 0;
    code = (code << 6) | (b & 0x3f);
  }
  return n;
}

void append_escaped_byte(std::string& out, unsigned char c) {
  static const char digits[] = "0123456789abcdef";
  out += "\\x";
  out += digits[c >> 4];
  out += digits[c & 15];
}

// Appends `text` as it may be printed: control bytes, bytes that are not UTF-8 and deceptive
// code points escaped (\x1b, \u{202e}), so that a program cannot drive the terminal or the
// editor its diagnostics are read in; with `cut_long_runs`, a run without blanks longer than
// kLongestRun (a 10 MB word) is cut, with the number of bytes left out.
void append_printable(std::string& out, std::string_view text, bool cut_long_runs) {
  constexpr std::size_t kLongestRun = 200, kKept = 160;
  std::size_t run = 0;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    run = c == ' ' ? 0 : run + 1;
    if (cut_long_runs && run == kKept + 1) {
      std::size_t end = i;
      while (end < text.size() && text[end] != ' ')
        ++end;
      if (end - i > kLongestRun - kKept) {
        out += "...(" + std::to_string(end - i) + " more bytes)";
        i = end;
        continue;
      }
    }
    if (c < 0x20 || c == 0x7f) {
      append_escaped_byte(out, c);
      ++i;
    } else if (c < 0x80) {
      out += char(c);
      ++i;
    } else {
      std::uint32_t code = 0;
      const std::size_t n = utf8_at(text, i, code);
      if (n == 0) {
        append_escaped_byte(out, c);
        ++i;
      } else if (is_deceptive(code)) {
        char buf[16];
        std::snprintf(buf, sizeof buf, "\\u{%x}", unsigned(code));
        out += buf;
        i += n;
      } else {
        out.append(text.substr(i, n));
        i += n;
      }
    }
  }
}

} // namespace

std::string printable(std::string_view text) {
  std::string out;
  append_printable(out, text, false);
  return out;
}

std::string format_diagnostic(const Diagnostic& d) {
  std::string out;
  append_printable(out, d.file, false);
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
  // Messages quote the program: shown so that it cannot drive the terminal, and a word of
  // megabytes is not printed whole (append_printable).
  append_printable(out, d.message, true);
  return out;
}

} // namespace ncjoule
