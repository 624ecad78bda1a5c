// Internal: the comments of a source line in a dialect's syntax, for naming operations.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::report_detail {

struct LineComments {
  std::vector<std::string> texts; // each comment's text without its delimiters, trimmed
  bool has_code = false;          // anything besides comments, blanks and a '%' tape mark
};

LineComments line_comments(std::string_view line, const Dialect& dialect);

} // namespace ncjoule::report_detail
