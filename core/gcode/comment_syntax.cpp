// Where comments begin and end (comment_syntax.hpp), and the comments of a source line as every
// later stage reads them (line_comments in gcode.hpp).
#include "comment_syntax.hpp"

#include <array>
#include <cctype>
#include <cstdint>

#include "ncjoule/text.hpp"

namespace ncjoule::detail {
namespace {

bool is_name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}
bool is_letter(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) != 0;
}

} // namespace

bool opens_argument_list(std::string_view line, std::size_t paren) {
  std::size_t k = paren;
  while (k > 0 && (line[k - 1] == ' ' || line[k - 1] == '\t'))
    --k;
  std::size_t start = k;
  while (start > 0 && is_name_char(line[start - 1]))
    --start;
  return k - start >= 2 && is_letter(line[start]) && is_letter(line[start + 1]);
}

std::size_t paren_length(std::string_view line, std::size_t pos) {
  int depth = 0;
  for (std::size_t i = pos; i < line.size(); ++i) {
    if (line[i] == '"') {
      // A string argument: MSG("a (b)") closes at its last ')'.
      const std::size_t close = line.find('"', i + 1);
      if (close == std::string_view::npos) return 0;
      i = close;
    } else if (line[i] == '(') {
      ++depth;
    } else if (line[i] == ')' && --depth == 0) {
      return i - pos + 1;
    }
  }
  return 0;
}

std::size_t comment_close(std::string_view line, std::size_t open, const Dialect& dialect) {
  if (!dialect.nested_paren_comments) return line.find(')', open + 1);
  int depth = 0;
  for (std::size_t k = open; k < line.size(); ++k) {
    if (line[k] == '(')
      ++depth;
    else if (line[k] == ')' && --depth == 0)
      return k;
  }
  return std::string_view::npos;
}

} // namespace ncjoule::detail

namespace ncjoule {
namespace {

// The one reading of a line's comments and code: `comment(begin, end, open)` for each comment
// (its text is line[begin, end), `open` where its opening character is), `code(begin, end,
// closed)` for each run of code (closed: false for an argument list or a string the line ends
// inside), `stop(at)` where an end-of-block mark ends the scan.
template <class Comment, class Code, class Stop>
void scan_line(std::string_view line, const Dialect& dialect, Comment comment, Code code,
               Stop stop) {
  std::size_t i = 0;
  while (i < line.size()) {
    const char c = line[i];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '%') {
      ++i;
    } else if (c == '(' && dialect.paren_argument_lists && detail::opens_argument_list(line, i)) {
      const std::size_t len = detail::paren_length(line, i);
      const std::size_t begin = i;
      i = len ? i + len : line.size();
      code(begin, i, len != 0);
    } else if (c == '"' && dialect.paren_argument_lists) {
      // A Sinumerik string ("a;b(c)"): code, whatever it holds.
      const std::size_t close = line.find('"', i + 1);
      const std::size_t begin = i;
      i = close == std::string_view::npos ? line.size() : close + 1;
      code(begin, i, close != std::string_view::npos);
    } else if (c == '*' && dialect.star_block_end) {
      stop(i);
      return;
    } else if (c == '(' && dialect.paren_comments) {
      const std::size_t close = detail::comment_close(line, i, dialect);
      const std::size_t end = close == std::string_view::npos ? line.size() : close;
      comment(i + 1, end, i);
      i = end + 1;
    } else if (c == ')' && dialect.paren_comments) {
      // A stray ')' (Estlcam's "(HSS Twist Drill, 3mm (R))" where comments do not nest): the
      // lexer warns and passes over it, so it is no code.
      ++i;
    } else if (c == ';') {
      // A comment to the end of the line, or the Fanuc family's end of block.
      if (dialect.semicolon_comments)
        comment(i + 1, line.size(), i);
      else
        stop(i);
      return;
    } else {
      code(i, i + 1, true);
      ++i;
    }
  }
}

// What each character is to line_comments()'s shortcut: a blank, code, or one the scanner
// treats apart (a comment's, a string's or a block end's).
enum CharClass : std::uint8_t { kBlank = 0, kCode = 1, kApart = 2 };
constexpr std::array<std::uint8_t, 256> kCharClass = [] {
  std::array<std::uint8_t, 256> classes{};
  classes.fill(kCode);
  for (const unsigned char c : {' ', '\t', '\r', '\n', '%'})
    classes[c] = kBlank;
  for (const unsigned char c : {'(', ')', '"', '*', ';'})
    classes[c] = kApart;
  return classes;
}();

} // namespace

LineComments line_comments(std::string_view line, const Dialect& dialect) {
  // Most lines of a program are code alone: a line without any of the characters scan_line
  // treats apart holds no comment, and has code where it holds more than blanks and '%'. Told
  // in one pass without branches (the scanner's took 80 ms of the 1M-block program's serial
  // work, read for the tool comments).
  std::uint8_t seen = kBlank;
  for (const char c : line)
    seen |= kCharClass[static_cast<unsigned char>(c)];
  if (seen & kApart) return detail::scanned_line_comments(line, dialect);
  LineComments out;
  out.has_code = (seen & kCode) != 0;
  return out;
}

namespace detail {

LineComments scanned_line_comments(std::string_view line, const Dialect& dialect) {
  LineComments out;
  scan_line(
      line, dialect,
      [&](std::size_t begin, std::size_t end, std::size_t open) {
        out.comments.push_back({trim(line.substr(begin, end - begin)), int(open) + 1});
      },
      [&](std::size_t, std::size_t, bool) { out.has_code = true; }, [](std::size_t) {});
  return out;
}

CodeSpan code_span(std::string_view line, const Dialect& dialect) {
  CodeSpan span;
  scan_line(
      line, dialect,
      [&](std::size_t, std::size_t end, std::size_t open) {
        if (span.stop == std::string_view::npos) span.stop = open;
        if (line[open] == ';') span.semicolon = open;
        if (line[open] == '(' && end == line.size()) span.unclosed_comment = true;
      },
      [&](std::size_t begin, std::size_t end, bool closed) {
        if (span.code_begin == std::string_view::npos) span.code_begin = begin;
        span.code_end = end;
        span.unclosed = !closed;
      },
      [&](std::size_t at) {
        if (span.stop == std::string_view::npos) span.stop = at;
      });
  return span;
}

} // namespace detail

bool is_move(CanonKind kind) {
  return kind == CanonKind::Traverse || kind == CanonKind::Feed || kind == CanonKind::Arc ||
         kind == CanonKind::Probe;
}

bool is_feed_move(CanonKind kind) {
  return kind == CanonKind::Feed || kind == CanonKind::Arc || kind == CanonKind::Probe;
}

} // namespace ncjoule
