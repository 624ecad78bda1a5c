#include <algorithm>

#include "marker.hpp"
#include "ncjoule/annotate.hpp"
#include "strip_line.hpp"

namespace ncjoule {
namespace annotation {

bool is_header_line(std::string_view line) {
  return !line.empty() && match_marked_comment(line, 0, MarkKind::Header) == line.size();
}

bool strip_inline(std::string_view line, std::string& out) {
  bool found = false;
  std::size_t copied = 0;
  // An inline annotation is " (NCJ ...)" or " ;NCJ ...": a space, then a marked comment.
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    if (line[i] != ' ' || (line[i + 1] != '(' && line[i + 1] != ';')) continue;
    const std::size_t length = match_marked_comment(line, i + 1, MarkKind::Inline);
    if (length == 0) continue;
    out.append(line.substr(copied, i - copied));
    copied = i + 1 + length;
    i = copied - 1;
    found = true;
  }
  out.append(line.substr(copied));
  return found;
}

std::vector<LineSpan> split_lines(std::string_view text) {
  std::vector<LineSpan> lines;
  lines.reserve(std::count(text.begin(), text.end(), '\n') + 1);
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t i = begin;
    while (i < text.size() && text[i] != '\n' && text[i] != '\r')
      ++i;
    LineSpan span{begin, i - begin, 0};
    if (i < text.size())
      span.eol_length = (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ? 2 : 1;
    lines.push_back(span);
    begin = i + span.eol_length;
  }
  return lines;
}

} // namespace annotation

std::string strip(std::string_view text) {
  using namespace annotation;
  std::string out;
  out.reserve(text.size());
  for (const LineSpan& span : split_lines(text)) {
    const std::string_view line = text.substr(span.begin, span.length);
    if (is_header_line(line)) continue; // with its line ending
    strip_inline(line, out);
    out.append(text.substr(span.begin + span.length, span.eol_length));
  }
  return out;
}

bool has_annotations(std::string_view text) {
  using namespace annotation;
  std::string scratch;
  for (const LineSpan& span : split_lines(text)) {
    const std::string_view line = text.substr(span.begin, span.length);
    scratch.clear();
    if (is_header_line(line) || strip_inline(line, scratch)) return true;
  }
  return false;
}

} // namespace ncjoule
