// Writing the optimized program: the original bytes, changed blocks rewritten in place, restore
// blocks after them, and a header that lists the changes and their rules.
#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

#include "block_rewrite.hpp"
#include "line_layout.hpp"
#include "ncjoule/optimize.hpp"

namespace ncjoule {
namespace {

using optimize_detail::format_feed;
using optimize_detail::mark_comment;

// The line the header goes before: after a leading '%', O-number (and Sinumerik ;$PATH) lines
// and the title comment right after them, as annotate places its own header; the end of the
// file when nothing follows them.
std::size_t header_position(const SourceFile& source) {
  const std::size_t n = source.lines.size();
  std::size_t i = 0;
  bool leading = false, named = false;
  while (i < n) {
    const std::string_view line = source.line_text(i);
    if (annotation::is_percent_line(line) || annotation::is_program_number_line(line)) {
      leading = true;
      named = annotation::is_program_number_line(line) && annotation::has_trailing_comment(line);
    } else if (!(leading && annotation::is_sinumerik_path_line(line))) {
      break;
    }
    ++i;
  }
  if (leading && !named && i < n && annotation::is_comment_only(source.line_text(i)) &&
      !annotation::is_sinumerik_path_line(source.line_text(i)))
    ++i;
  return i;
}

// The file's line ending: that of its first line that has one, else "\n".
std::string file_eol(const SourceFile& source) {
  for (const LineSpan& l : source.lines)
    if (l.eol_length) return source.text.substr(l.begin + l.length, l.eol_length);
  return "\n";
}

// Words into comment lines of at most `width` bytes, each starting with the mark.
void wrap(std::vector<std::string>& out, const std::string& text, const Dialect& dialect,
          std::size_t width) {
  std::istringstream words(text);
  std::string word, line = kOptimizeMark;
  const std::size_t frame = mark_comment("", dialect).size();
  while (words >> word) {
    if (line.size() + 1 + word.size() + frame > width && line != kOptimizeMark) {
      out.push_back(mark_comment(line, dialect));
      line = std::string(kOptimizeMark) + " ";
      line += word;
    } else {
      line += " " + word;
    }
  }
  if (line != kOptimizeMark) out.push_back(mark_comment(line, dialect));
}

std::vector<std::string> header_lines(const Dialect& dialect, const OptimizePlan& plan,
                                      const std::vector<int>& changed, std::size_t restores) {
  const std::size_t width =
      dialect.max_line_length > 0 ? std::min<std::size_t>(dialect.max_line_length, 72) : 72;
  const char* unit = plan.inch ? "IN" : "MM";
  const double margin = plan.inch ? plan.margin_mm / 25.4 : plan.margin_mm;
  char number[32];
  std::snprintf(number, sizeof number, "%.*f", plan.inch ? 3 : 2, margin);
  std::vector<std::string> out;
  std::size_t air = 0, rapid = 0, load = 0;
  for (const BlockEdit& e : plan.edits) {
    if (e.rule == EditRule::AirFeed) ++air;
    if (e.rule == EditRule::RapidLink) ++rapid;
    if (e.rule == EditRule::LoadFeed) ++load;
  }
  wrap(out,
       "OPTIMIZED COPY BY NCJOULE OPTIMIZE, " + std::to_string(changed.size()) +
           " BLOCKS CHANGED, " + std::to_string(restores) + " RESTORE BLOCKS ADDED. " +
           (load ? "OF WHAT CUTS ONLY THE FEEDS MARKED LOAD CHANGED."
                 : "NOTHING THAT CUTS WAS CHANGED."),
       dialect, width);
  if (air)
    wrap(out,
         "AIR - " + std::to_string(air) +
             " FEED MOVES CLEAR OF THE STOCK BY THE TOOL RADIUS PLUS " + number + " " + unit +
             " RUN AT UP TO F" + format_feed(plan.air_feed_mm_min, plan.inch) +
             " WITHIN THE AXIS LIMITS.",
         dialect, width);
  if (rapid)
    wrap(out,
         "RAPID - " + std::to_string(rapid) +
             " CLEAR RETRACTS AND LINKS RUN AS G0, THE RAPID PATH CHECKED CLEAR BY THE SAME "
             "MARGIN.",
         dialect, width);
  if (load) {
    char share[32], factor[32], floor[32], depth[32];
    std::snprintf(share, sizeof share, "%.0f%%", 100 * plan.load_share);
    std::snprintf(factor, sizeof factor, "%.2f", plan.max_feed_factor);
    std::snprintf(floor, sizeof floor, "%.2f", plan.min_feed_factor);
    std::snprintf(depth, sizeof depth, "%.*f", plan.inch ? 3 : 2,
                  plan.inch ? plan.finish_depth_mm / 25.4 : plan.finish_depth_mm);
    wrap(out,
         "LOAD - " + std::to_string(load) + " CUTTING FEEDS SCALED, " +
             std::to_string(plan.load_lowered) + " LOWERED, " + std::to_string(plan.load_raised) +
             " RAISED, SO THE PREDICTED CUTTING POWER STAYS WITHIN " + share +
             " OF THE SPINDLE RATING, AT MOST " + factor + " AND AT LEAST " + floor +
             " TIMES THE PROGRAMMED FEED AND WITHIN THE AXIS LIMITS. FINISHING PASSES, UNDER " +
             depth + " " + unit + " DEEP OR WIDE, UNCHANGED.",
         dialect, width);
  }
  if (restores)
    wrap(out,
         "RESTORE - THE ORIGINAL F PUT BACK RIGHT AFTER A CHANGED BLOCK, G1 ON THE BLOCK THAT "
         "MOVED ON IT.",
         dialect, width);
  std::string lines = "CHANGED LINES OF THE ORIGINAL -";
  constexpr std::size_t kListed = 200;
  for (std::size_t k = 0; k < changed.size() && k < kListed; ++k)
    lines += " L" + std::to_string(changed[k] + 1);
  if (changed.size() > kListed)
    lines += " AND " + std::to_string(changed.size() - kListed) + " MORE";
  wrap(out, lines, dialect, width);
  wrap(out, "REVIEW WITH NCJOULE COMPARE ORIGINAL OPTIMIZED.", dialect, width);
  return out;
}

} // namespace

OptimizedText write_optimized(const SourceFile& source, const Dialect& dialect,
                              const OptimizePlan& plan) {
  OptimizedText result;
  std::map<int, std::string> rewritten, restores;
  std::vector<int> changed;
  for (const BlockEdit& e : plan.edits) {
    if (e.line < 0 || std::size_t(e.line) >= source.lines.size()) continue;
    const auto text = optimize_detail::rewrite_block(source.line_text(std::size_t(e.line)), dialect,
                                                     e, plan.inch);
    if (!text) continue; // the plan checked it: not reached
    rewritten[e.line] = *text;
    if (e.rule == EditRule::RestoreG1)
      ++result.restore_blocks;
    else
      changed.push_back(e.line);
    const std::string restore = optimize_detail::restore_block(e, dialect, plan.inch);
    if (!restore.empty()) restores[e.line] = restore;
  }
  result.changed_blocks = changed.size();
  result.restore_blocks += restores.size();
  if (rewritten.empty()) {
    result.text = source.text;
    for (std::size_t i = 0; i < source.lines.size(); ++i)
      result.original_line.push_back(int(i));
    return result;
  }
  const std::string eol = file_eol(source);
  const std::size_t header_at = header_position(source);
  std::string& out = result.text;
  out.reserve(source.text.size() + 64 * (rewritten.size() + restores.size() + 8));
  std::vector<int>& origin = result.original_line;
  origin.reserve(source.lines.size() + restores.size() + 16);
  auto put_header = [&] {
    for (const std::string& line : header_lines(dialect, plan, changed, result.restore_blocks)) {
      out += line + eol;
      origin.push_back(-1);
    }
  };
  for (std::size_t i = 0; i < source.lines.size(); ++i) {
    const LineSpan& l = source.lines[i];
    if (i == header_at) put_header();
    origin.push_back(int(i));
    const auto r = rewritten.find(int(i));
    if (r == rewritten.end()) {
      out.append(source.text, l.begin, l.length + l.eol_length);
      continue;
    }
    out += r->second;
    const std::string own_eol =
        l.eol_length ? source.text.substr(l.begin + l.length, l.eol_length) : std::string();
    out += own_eol;
    if (const auto s = restores.find(int(i)); s != restores.end()) {
      out += (own_eol.empty() ? eol : std::string()) + s->second + own_eol;
      origin.push_back(-1);
    }
  }
  if (header_at >= source.lines.size()) {
    if (!source.lines.empty() && source.lines.back().eol_length == 0) out += eol;
    put_header();
  }
  return result;
}

} // namespace ncjoule
