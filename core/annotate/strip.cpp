#include <algorithm>

#include "line_layout.hpp"
#include "marker.hpp"
#include "ncjoule/annotate.hpp"
#include "strip_line.hpp"

namespace ncjoule {
namespace annotation {
namespace {

// A line a key may come before: nothing a controller runs (a program's '%', its number, its
// comments, blank lines).
bool holds_no_code(std::string_view line) {
  return is_blank(line) || is_comment_only(line) || is_percent_line(line) ||
         is_program_number_line(line);
}

} // namespace

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

Annotations::Annotations(std::string_view text, const std::vector<LineSpan>& lines)
    : text_(text), lines_(lines), whole_(lines.size(), false) {
  // The key: from the first key line before any line with code. Every key line there goes (a
  // second one would be the next strip's key); one further down, pasted into the program, is
  // the user's text.
  for (std::size_t i = 0; i < lines_.size(); ++i) {
    if (const std::optional<std::string> key = key_of_line(line(i))) {
      if (seed_.empty()) seed_ = key_seed(*key);
      whole_[i] = any_whole_ = true;
      continue;
    }
    if (!holds_no_code(line(i))) break;
  }
  // From the end: a block's comment line is sealed with the line after it as strip() leaves it,
  // the next line that stays, without its own annotations.
  std::string next_seed;
  std::optional<std::size_t> next_kept;
  bool next_seed_known = true;
  for (std::size_t i = lines_.size(); i-- > 0;) {
    if (whole_[i]) continue;
    const std::string_view l = line(i);
    if (!l.empty() && (l[0] == '(' || l[0] == ';')) {
      if (!next_seed_known) {
        std::string stripped;
        strip_inline(*next_kept, stripped);
        next_seed = line_seed(stripped);
        next_seed_known = true;
      }
      whole_[i] = is_whole_annotation(i, next_kept ? next_seed : std::string());
    }
    if (whole_[i]) {
      any_whole_ = true;
    } else {
      next_kept = i;
      next_seed_known = false;
    }
  }
}

std::string_view Annotations::line(std::size_t i) const {
  return text_.substr(lines_[i].begin, lines_[i].length);
}

bool Annotations::is_whole_annotation(std::size_t i, const std::string& next_seed) const {
  const std::string_view l = line(i);
  if (!seed_.empty() && (match_marked_comment(l, 0, MarkKind::Header, seed_) == l.size() ||
                         match_marked_comment(l, 0, MarkKind::Line, seed_) == l.size()))
    return true;
  return !next_seed.empty() && match_marked_comment(l, 0, MarkKind::Line, next_seed) == l.size();
}

bool Annotations::strip_inline(std::size_t i, std::string& out) const {
  const std::string_view l = line(i);
  bool found = false;
  std::size_t copied = 0;
  // An inline annotation is " (NCJ ...)" or " ;NCJ ...": a space, then a marked comment sealed
  // with the file's key or with its line.
  for (std::size_t k = 0; k + 1 < l.size(); ++k) {
    if (l[k] != ' ' || (l[k + 1] != '(' && l[k + 1] != ';')) continue;
    std::size_t length = 0;
    if (!seed_.empty()) length = match_marked_comment(l, k + 1, MarkKind::Inline, seed_);
    if (length == 0) length = match_line_bound_comment(l, k);
    if (length == 0) continue;
    out.append(l.substr(copied, k - copied));
    copied = k + 1 + length;
    k = copied - 1;
    found = true;
  }
  out.append(l.substr(copied));
  return found;
}

} // namespace annotation

std::string strip(std::string_view text) {
  using namespace annotation;
  const std::vector<LineSpan> lines = split_lines(text);
  const Annotations annotations(text, lines);
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (annotations.whole_line(i)) continue; // with its line ending
    annotations.strip_inline(i, out);
    out.append(text.substr(lines[i].begin + lines[i].length, lines[i].eol_length));
  }
  return out;
}

bool has_annotations(std::string_view text) {
  using namespace annotation;
  const std::vector<LineSpan> lines = split_lines(text);
  const Annotations annotations(text, lines);
  if (annotations.any_whole_line()) return true;
  std::string scratch;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    scratch.clear();
    if (annotations.strip_inline(i, scratch)) return true;
  }
  return false;
}

} // namespace ncjoule
