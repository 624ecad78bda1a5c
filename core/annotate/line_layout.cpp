#include "line_layout.hpp"

#include "comment_syntax.hpp"

namespace ncjoule::annotation {
namespace {

bool is_blank_char(char c) {
  return c == ' ' || c == '\t';
}

std::size_t skip_blanks(std::string_view line, std::size_t i) {
  while (i < line.size() && is_blank_char(line[i]))
    ++i;
  return i;
}

// Without the blanks (space, tab) at either end: a line's own bytes, CR included, are kept.
std::string_view trim_blanks(std::string_view text) {
  std::size_t b = 0, e = text.size();
  while (b < e && is_blank_char(text[b]))
    ++b;
  while (e > b && is_blank_char(text[e - 1]))
    --e;
  return text.substr(b, e - b);
}

} // namespace

std::optional<std::size_t> insertion_point(std::string_view line, const Dialect& dialect,
                                           const CommentStyle& style) {
  const detail::CodeSpan span = detail::code_span(line, dialect);
  if (span.code_begin == std::string_view::npos) return std::nullopt;
  // An argument list or a string the line ends inside: any place after its opening is inside it
  // (and the code before it is not all of the block's).
  if (span.unclosed) return std::nullopt;
  std::size_t end;
  std::size_t floor;
  if (style.open == ";") {
    // Everything after a ';' is comment: past all the code, before the user's ';' comment;
    // not in a "( )" comment that runs to the line's end ("(MSG, note": it would say it).
    if (span.unclosed_comment) return std::nullopt;
    end = span.semicolon == std::string_view::npos ? line.size() : span.semicolon;
    floor = span.code_end;
  } else {
    end = span.stop == std::string_view::npos ? line.size() : span.stop;
    floor = 0;
  }
  while (end > floor && is_blank_char(line[end - 1]))
    --end;
  // Block delete and blanks alone are no code.
  std::size_t code = skip_blanks(line, 0);
  if (code < end && line[code] == '/') code = skip_blanks(line, code + 1);
  if (code >= end || span.code_begin >= end) return std::nullopt;
  return end;
}

bool is_blank(std::string_view line) {
  return skip_blanks(line, 0) == line.size();
}

bool is_comment_only(std::string_view line) {
  std::size_t i = skip_blanks(line, 0);
  if (i == line.size()) return false;
  while (i < line.size()) {
    if (line[i] == ';') return true;
    if (line[i] != '(') return false;
    const std::size_t close = line.find(')', i);
    if (close == std::string_view::npos) return true;
    i = skip_blanks(line, close + 1);
  }
  return true;
}

std::string_view first_comment(std::string_view line) {
  const std::size_t open = line.find_first_of("(;");
  if (open == std::string_view::npos) return {};
  if (line[open] == ';') return trim_blanks(line.substr(open + 1));
  const std::size_t close = line.find(')', open);
  const std::size_t end = close == std::string_view::npos ? line.size() : close;
  return trim_blanks(line.substr(open + 1, end - open - 1));
}

bool is_percent_line(std::string_view line) {
  const std::size_t i = skip_blanks(line, 0);
  return i < line.size() && line[i] == '%';
}

bool is_program_number_line(std::string_view line) {
  // Only a number and comments: "O1234 (NAME)". LinuxCNC's "o100 sub" or "o100 if [...]" are
  // control words, not the program's name.
  std::size_t i = skip_blanks(line, 0);
  if (i >= line.size() || (line[i] != 'O' && line[i] != 'o' && line[i] != ':')) return false;
  const std::size_t digits = ++i;
  while (i < line.size() && line[i] >= '0' && line[i] <= '9')
    ++i;
  if (i == digits) return false;
  const std::string_view rest = line.substr(i);
  return is_blank(rest) || is_comment_only(rest);
}

} // namespace ncjoule::annotation

namespace ncjoule::annotation {

bool is_sinumerik_path_line(std::string_view line) {
  constexpr std::string_view kPath = ";$PATH=";
  const std::size_t i = skip_blanks(line, 0);
  if (line.size() - i < kPath.size()) return false;
  for (std::size_t k = 0; k < kPath.size(); ++k) {
    const char c = line[i + k];
    if ((c >= 'a' && c <= 'z' ? char(c - 'a' + 'A') : c) != kPath[k]) return false;
  }
  return true;
}

bool has_trailing_comment(std::string_view line) {
  return line.find_first_of("(;") != std::string_view::npos;
}

} // namespace ncjoule::annotation
