// Internal: where a dialect's comments begin and end on a line. One home for the rules the
// lexer reads code by and line_comments() (gcode.hpp) reads comments by.
#pragma once

#include <cstddef>
#include <string_view>

#include "ncjoule/gcode.hpp"

namespace ncjoule::detail {

// Sinumerik calls take their arguments in parentheses: "CYCLE81(10,0,2,-5)", "MSG("text")".
// A '(' right after a name that begins with two letters opens such a list, not a comment.
bool opens_argument_list(std::string_view line, std::size_t paren);

// Length of the ( ... ) list at line[pos], including both parentheses, or 0 when not closed.
// Parentheses inside a double-quoted string (Sinumerik's MSG("a (b)")) do not count.
std::size_t paren_length(std::string_view line, std::size_t pos);

// Where a line's code is as the dialect reads it: what an annotation written into the line must
// stay after (code_end) and before (stop: its first comment, or the end-of-block mark of the
// Fanuc family's ';' and Heidenhain's '*'). Read by the scanner line_comments() uses, so that
// nothing is put inside a call, an expression or a string.
struct CodeSpan {
  std::size_t code_begin = std::string_view::npos; // the first code byte; npos: no code
  std::size_t code_end = 0;                        // one past the last code byte
  std::size_t stop = std::string_view::npos;       // first comment or block end; npos: none
  std::size_t semicolon = std::string_view::npos;  // the ';' of a comment to the line's end
  // The line ends inside an argument list or a string (MSG("a;b): nothing written at its end
  // would be outside them.
  bool unclosed = false;
  // The line ends inside a "( )" comment that does not close ("(MSG, note"): what is written at
  // its end is part of it.
  bool unclosed_comment = false;
};
CodeSpan code_span(std::string_view line, const Dialect& dialect);

// line_comments() (gcode.hpp) by the scanner alone, without its shortcut for lines that hold
// no character a comment or string begins or ends with: what the shortcut is tested against.
LineComments scanned_line_comments(std::string_view line, const Dialect& dialect);

// The ')' that closes the comment opened at line[open] (the first one, or the balancing one
// where the dialect nests comments); npos when the line ends first.
std::size_t comment_close(std::string_view line, std::size_t open, const Dialect& dialect);

} // namespace ncjoule::detail
