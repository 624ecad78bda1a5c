#include "block_rewrite.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <vector>

#include "simple_block.hpp"

namespace ncjoule::optimize_detail {

std::string format_feed(double mm_min, bool inch) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", inch ? 4 : 3, inch ? mm_min / 25.4 : mm_min);
  std::string s = text;
  while (!s.empty() && s.back() == '0')
    s.pop_back();
  return s; // the point stays: "5000."
}

std::string mark_comment(std::string_view content, const Dialect& dialect) {
  std::string upper(content);
  for (char& c : upper)
    c = char(std::toupper(static_cast<unsigned char>(c)));
  if (dialect.paren_comments) return "(" + upper + ")";
  return ";" + upper;
}

std::optional<std::string> rewrite_block(std::string_view line, const Dialect& dialect,
                                         const BlockEdit& edit, bool inch) {
  const std::optional<SimpleBlock> block = read_simple_block(line, dialect);
  if (!block) return std::nullopt;
  // Replacements of [begin, end) by text, applied from the last to the first.
  struct Splice {
    std::size_t begin, end;
    std::string text;
  };
  std::vector<Splice> splices;
  std::string mark = std::string(kOptimizeMark) + " ";
  // "G1 " before the first word that is not a sequence number.
  auto insert_g1 = [&] {
    std::size_t at = block->words.front().begin;
    for (const Word& w : block->words)
      if (w.letter != 'N') {
        at = w.begin;
        break;
      }
    splices.push_back({at, at, "G1 "});
  };
  if (edit.rule == EditRule::RestoreG1) {
    if (block->has('G')) return std::nullopt;
    insert_g1();
    mark += "RESTORE G1";
  } else if (changes_feed(edit.rule)) {
    if (edit.insert_g1) {
      if (block->has('G')) return std::nullopt;
      insert_g1();
    }
    const std::string feed = format_feed(edit.feed_mm_min, inch);
    if (const Word* f = block->find('F'))
      splices.push_back({f->number, f->end, feed});
    else if (!edit.modal_feed) // else the block before set this feed
      splices.push_back({block->code_end, block->code_end, " F" + feed});
    mark += std::string(edit.rule == EditRule::LoadFeed ? "LOAD" : "AIR") + " F" + feed + " WAS F" +
            format_feed(edit.was_feed_mm_min, inch);
  } else {
    if (const Word* g = block->find('G')) {
      splices.push_back({g->number, g->end, std::string(g->end - g->number, '0')});
    } else {
      std::size_t at = block->words.front().begin;
      for (const Word& w : block->words)
        if (w.letter != 'N') {
          at = w.begin;
          break;
        }
      splices.push_back({at, at, "G0 "});
    }
    mark += "RAPID WAS G1";
  }
  splices.push_back({block->code_end, block->code_end, " " + mark_comment(mark, dialect)});
  std::string out(line);
  // Equal positions: the later splice in the list goes after the earlier one.
  for (auto it = splices.rbegin(); it != splices.rend(); ++it)
    out.replace(it->begin, it->end - it->begin, it->text);
  if (dialect.max_line_length > 0 && out.size() > dialect.max_line_length) return std::nullopt;
  return out;
}

std::string restore_block(const BlockEdit& edit, const Dialect& dialect, bool inch) {
  if (!edit.restore_feed && !edit.restore_g1) return {};
  std::string code;
  if (edit.restore_g1) code = "G1";
  if (edit.restore_feed) {
    if (!code.empty()) code += ' ';
    code += "F" + format_feed(edit.restore_feed_mm_min, inch);
  }
  return code + " " + mark_comment(std::string(kOptimizeMark) + " RESTORE", dialect);
}

} // namespace ncjoule::optimize_detail
