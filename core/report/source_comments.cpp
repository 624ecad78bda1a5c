// Splitting a source line into its comments and the rest, as the dialect reads comments.
#include "source_comments.hpp"

namespace ncjoule::report_detail {
namespace {

std::string trimmed(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(first, last - first + 1));
}

} // namespace

LineComments line_comments(std::string_view line, const Dialect& dialect) {
  LineComments out;
  std::size_t i = 0;
  while (i < line.size()) {
    const char ch = line[i];
    if (dialect.paren_comments && ch == '(') {
      // Without nesting the first ')' closes; with it, parentheses must balance.
      int depth = 1;
      std::size_t j = i + 1;
      for (; j < line.size(); ++j) {
        if (line[j] == '(' && dialect.nested_paren_comments) ++depth;
        if (line[j] == ')' && --depth == 0) break;
      }
      out.texts.push_back(trimmed(line.substr(i + 1, j - i - 1)));
      i = j + 1;
      continue;
    }
    if (dialect.semicolon_comments && ch == ';') {
      out.texts.push_back(trimmed(line.substr(i + 1)));
      break;
    }
    if (ch != ' ' && ch != '\t' && ch != '\r' && ch != '\n' && ch != '%') out.has_code = true;
    ++i;
  }
  return out;
}

} // namespace ncjoule::report_detail
