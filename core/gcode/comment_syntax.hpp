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
std::size_t paren_length(std::string_view line, std::size_t pos);

// The ')' that closes the comment opened at line[open] (the first one, or the balancing one
// where the dialect nests comments); npos when the line ends first.
std::size_t comment_close(std::string_view line, std::size_t open, const Dialect& dialect);

} // namespace ncjoule::detail
