#include <algorithm>
#include <optional>

#include "annotation_form.hpp"
#include "line_layout.hpp"
#include "marker.hpp"
#include "ncjoule/annotate.hpp"
#include "seal.hpp"
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

// Whether the text holds "CK=" in any case: only then can it hold an earlier version's comments.
bool may_hold_legacy(std::string_view text) {
  for (std::size_t at = text.find('='); at != std::string_view::npos; at = text.find('=', at + 1))
    if (at >= 2 && (text[at - 1] == 'K' || text[at - 1] == 'k') &&
        (text[at - 2] == 'C' || text[at - 2] == 'c'))
      return true;
  return false;
}

// Whether the text holds "NCJ" in any case: every comment and header line of this version
// starts with it, so a text without it holds none (most programs, the first time they are
// annotated: strip and annotate then skip the per-line search).
bool may_hold_current(std::string_view text) {
  for (std::size_t at = text.find_first_of("Nn"); at != std::string_view::npos;
       at = text.find_first_of("Nn", at + 1))
    if (at + 2 < text.size() && (text[at + 1] == 'C' || text[at + 1] == 'c') &&
        (text[at + 2] == 'J' || text[at + 2] == 'j'))
      return true;
  return false;
}

// Earlier versions' inline comments on `l`: " (NCJ ... CK=XXXXXX)" or " ;NCJ ... CK=XXXXXX",
// sealed with the file's key (`seed`) or with their own line. Each as [begin, end).
std::vector<std::pair<std::size_t, std::size_t>> legacy_inline(std::string_view l,
                                                               const std::string& seed) {
  std::vector<std::pair<std::size_t, std::size_t>> found;
  for (std::size_t k = 0; k + 1 < l.size(); ++k) {
    if (l[k] != ' ' || (l[k + 1] != '(' && l[k + 1] != ';')) continue;
    std::size_t length = 0;
    if (!seed.empty()) length = match_marked_comment(l, k + 1, MarkKind::Inline, seed);
    if (length == 0) length = match_line_bound_comment(l, k);
    if (length == 0) continue;
    found.emplace_back(k, k + 1 + length);
    k += length;
  }
  return found;
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
  if (may_hold_legacy(text)) find_legacy();
  if (may_hold_current(text)) find_current();
  std::sort(spans_.begin(), spans_.end(), [](const Span& a, const Span& b) {
    return a.line != b.line ? a.line < b.line : a.begin < b.begin;
  });
  for (bool w : whole_)
    any_whole_ = any_whole_ || w;
}

std::string_view Annotations::line(std::size_t i) const {
  return text_.substr(lines_[i].begin, lines_[i].length);
}

void Annotations::find_legacy() {
  // The key: from the first key line before any line with code. Every key line there goes (a
  // second one would be the next strip's key); one further down, pasted into the program, is
  // the user's text.
  std::string seed;
  for (std::size_t i = 0; i < lines_.size(); ++i) {
    if (const std::optional<std::string> key = key_of_line(line(i))) {
      if (seed.empty()) seed = key_seed(*key);
      whole_[i] = true;
      continue;
    }
    if (!holds_no_code(line(i))) break;
  }
  // From the end: a block's comment line is sealed with the line after it as strip() leaves it,
  // the next line that stays, without its own annotations.
  std::string next_seed;
  std::optional<std::size_t> next_kept;
  bool next_seed_known = true;
  auto without_inline = [&](std::size_t i) {
    const std::string_view l = line(i);
    std::string out;
    std::size_t copied = 0;
    for (auto [begin, end] : legacy_inline(l, seed)) {
      out.append(l.substr(copied, begin - copied));
      copied = end;
    }
    out.append(l.substr(copied));
    return out;
  };
  for (std::size_t i = lines_.size(); i-- > 0;) {
    if (whole_[i]) continue;
    const std::string_view l = line(i);
    if (!l.empty() && (l[0] == '(' || l[0] == ';')) {
      if (!next_seed_known) {
        next_seed = line_seed(without_inline(*next_kept));
        next_seed_known = true;
      }
      const std::string& next = next_kept ? next_seed : std::string();
      whole_[i] =
          (!seed.empty() && (match_marked_comment(l, 0, MarkKind::Header, seed) == l.size() ||
                             match_marked_comment(l, 0, MarkKind::Line, seed) == l.size())) ||
          (!next.empty() && match_marked_comment(l, 0, MarkKind::Line, next) == l.size());
    }
    if (!whole_[i]) {
      next_kept = i;
      next_seed_known = false;
    }
  }
  for (std::size_t i = 0; i < lines_.size(); ++i)
    if (!whole_[i])
      for (auto [begin, end] : legacy_inline(line(i), seed))
        spans_.push_back({i, begin, end});
}

bool Annotations::has_span(std::size_t i, std::size_t begin, std::size_t end) const {
  // Called while spans_ holds the earlier versions' spans only, in line order.
  auto it = std::lower_bound(spans_.begin(), spans_.end(), i,
                             [](const Span& s, std::size_t line) { return s.line < line; });
  for (; it != spans_.end() && it->line == i; ++it)
    if (it->begin < end && begin < it->end) return true;
  return false;
}

void Annotations::find_current() {
  const std::size_t n = lines_.size();
  const bool legacy_found = !spans_.empty();
  // The seal lines: whole lines that are one (their own checksum verified), wherever a user's
  // edits moved them.
  std::vector<std::size_t> seal_lines;
  for (std::size_t i = 0; i < n; ++i) {
    if (whole_[i]) continue;
    const std::string_view l = line(i);
    if (l.size() >= 12 && (l[0] == '(' || l[0] == ';') && seal_of_line(l)) seal_lines.push_back(i);
  }
  std::vector<bool> is_seal(n, false);
  for (std::size_t i : seal_lines)
    is_seal[i] = true;
  // The header lines after a seal line, as many as it counts, as long as they are header lines
  // (another seal line among them, a line copied in an editor, goes too but is not counted).
  struct Header {
    std::size_t seal_at = 0;
    Seal seal;
    std::vector<std::size_t> lines; // counted
    std::vector<std::size_t> extra; // seal lines among them
    SealSum sum;
  };
  auto header_at = [&](std::size_t at) {
    Header h;
    h.seal_at = at;
    h.seal = *seal_of_line(line(at));
    std::vector<KeptComment> keep;
    for (std::size_t j = at + 1; j < n && h.lines.size() < h.seal.lines; ++j) {
      const std::string_view l = line(j);
      if (whole_[j] || !is_header_line(l)) break;
      if (is_seal[j]) {
        h.extra.push_back(j);
        continue;
      }
      h.lines.push_back(j);
      h.sum.add_header(normal_text(l));
      read_keep_line(l, keep);
    }
    h.seal.keep = std::move(keep);
    return h;
  };
  // Every comment of the block form, in order.
  struct Candidate {
    std::size_t line;
    FoundComment comment;
  };
  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i < n; ++i) {
    if (whole_[i] || is_seal[i]) continue;
    for (FoundComment& c : block_comments(line(i))) {
      if (legacy_found && has_span(i, c.begin, c.end)) continue;
      candidates.push_back({i, std::move(c)});
    }
  }
  // Whether `s` covers exactly the candidates (and, with a seal line, the header lines found).
  auto exact = [&](const Seal& s, std::size_t lines_found, const SealSum& sum) {
    if (lines_found != s.lines || candidates.size() != s.blocks + s.keep.size()) return false;
    std::vector<bool> kept(candidates.size(), false);
    for (const KeptComment& k : s.keep) {
      if (k.ordinal == 0 || k.ordinal > candidates.size()) return false;
      if (keep_hash(candidates[k.ordinal - 1].comment.normal) != k.hash) return false;
      kept[k.ordinal - 1] = true;
    }
    SealSum total = sum;
    for (std::size_t c = 0; c < candidates.size(); ++c)
      if (!kept[c]) total.add_block(candidates[c].comment.normal);
    return total.value(s.lines, s.blocks) == s.sum;
  };
  // The file's seal: the first seal line that covers exactly what the file holds, else the
  // first one with header lines after it (a lone seal line, pasted from another file, is the
  // user's text); without one, a file without a header: the SEAL field of one of its comments.
  std::optional<Header> header;
  for (std::size_t at : seal_lines) {
    Header h = header_at(at);
    if (!exact(h.seal, h.lines.size(), h.sum)) {
      if (!header && !h.lines.empty()) header = std::move(h);
      continue;
    }
    header = std::move(h);
    break;
  }
  std::optional<Seal> seal;
  SealSum header_sum;
  std::size_t header_lines = 0;
  if (header) {
    seal = header->seal;
    header_sum = header->sum;
    header_lines = header->lines.size();
    whole_[header->seal_at] = true;
    for (std::size_t j : header->lines)
      whole_[j] = true;
    for (std::size_t j : header->extra)
      whole_[j] = true;
  }
  // A SEAL field counts only when it covers the file exactly: one that does not (an edited file
  // without a header, or a comment pasted from one) leaves the choice to the comments' number.
  if (!seal) {
    for (const Candidate& c : candidates) {
      if (c.comment.seal.empty()) continue;
      if (std::optional<Seal> s = seal_of_field(c.comment.seal); s && exact(*s, 0, SealSum())) {
        seal = s;
        break;
      }
    }
  }

  std::vector<bool> goes(candidates.size(), false);
  if (seal) {
    const bool matches = exact(*seal, header_lines, header_sum);
    std::fill(goes.begin(), goes.end(), true);
    if (matches) {
      for (const KeptComment& k : seal->keep)
        goes[k.ordinal - 1] = false;
    } else {
      // Edited after it was annotated: the listed comments are found by their text, the one
      // nearest its old place each.
      by_form_ = true;
      for (const KeptComment& k : seal->keep) {
        std::optional<std::size_t> best;
        for (std::size_t c = 0; c < candidates.size(); ++c) {
          if (!goes[c] || keep_hash(candidates[c].comment.normal) != k.hash) continue;
          const auto distance = [&](std::size_t x) {
            return x + 1 > k.ordinal ? x + 1 - k.ordinal : k.ordinal - x - 1;
          };
          if (!best || distance(c) < distance(*best)) best = c;
        }
        if (best) goes[*best] = false;
      }
    }
  } else if (candidates.size() >= 3) {
    // No seal at all (a header deleted): an annotated file has them on most of its blocks.
    std::size_t code = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (!whole_[i] && !holds_no_code(line(i))) ++code;
    if (2 * candidates.size() > code) {
      by_form_ = true;
      std::fill(goes.begin(), goes.end(), true);
      // What is left of a header: its lines before the first comment of a block.
      for (std::size_t i = 0; i < candidates.front().line; ++i)
        if (is_header_line(line(i))) whole_[i] = true;
    }
  }
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (!goes[c]) continue;
    const Candidate& k = candidates[c];
    if (k.comment.whole_line)
      whole_[k.line] = true;
    else
      spans_.push_back({k.line, k.comment.begin, k.comment.end});
  }
}

bool Annotations::strip_inline(std::size_t i, std::string& out) const {
  const std::string_view l = line(i);
  auto it = std::lower_bound(spans_.begin(), spans_.end(), i,
                             [](const Span& s, std::size_t line) { return s.line < line; });
  bool found = false;
  std::size_t copied = 0;
  for (; it != spans_.end() && it->line == i; ++it) {
    if (it->begin < copied) continue;
    out.append(l.substr(copied, it->begin - copied));
    copied = it->end;
    found = true;
  }
  out.append(l.substr(copied));
  return found;
}

} // namespace annotation

StripResult strip_checked(std::string_view text) {
  using namespace annotation;
  if (!may_hold_legacy(text) && !may_hold_current(text)) return {std::string(text), false};
  const std::vector<LineSpan> lines = split_lines(text);
  const Annotations annotations(text, lines);
  StripResult result;
  result.by_form = annotations.by_form();
  if (!annotations.any()) {
    result.text = std::string(text);
    return result;
  }
  std::string& out = result.text;
  out.reserve(text.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (annotations.whole_line(i)) continue; // with its line ending
    annotations.strip_inline(i, out);
    out.append(text.substr(lines[i].begin + lines[i].length, lines[i].eol_length));
  }
  return result;
}

std::string strip(std::string_view text) {
  return strip_checked(text).text;
}

bool has_annotations(std::string_view text) {
  using namespace annotation;
  if (!may_hold_legacy(text) && !may_hold_current(text)) return false;
  const std::vector<LineSpan> lines = split_lines(text);
  return Annotations(text, lines).any();
}

} // namespace ncjoule
