#include "setups.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "ncjoule/machine.hpp"
#include "ncjoule/text.hpp"

namespace ncjoule::estimate_detail {

SetupScan::SetupScan(const SourceFile& source, const Dialect& dialect)
    : source_(source), dialect_(dialect) {
  starts_.push_back({0, 0, "the program's start"});
}

std::string SetupScan::setup_comment_before(int line) {
  std::string found;
  const int last = std::min(line, int(source_.lines.size()) - 1);
  for (int l = looked_to_ + 1; l <= last && found.empty(); ++l)
    for (const LineComment& comment :
         line_comments(source_.line_text(std::size_t(l)), dialect_).comments)
      if (names_setup(comment.text)) {
        found = std::string(trim(comment.text));
        break;
      }
  looked_to_ = std::max(looked_to_, last);
  return found;
}

bool SetupScan::names_setup(std::string_view text) {
  const std::string t = to_lower(text);
  for (const char* words :
       {"setup", "set up", "set-up", "flip", "turn over", "turn the part", "turn part", "part over",
        "second side", "other side", "side 2", "reclamp", "re-clamp", "refixture", "re-fixture"})
    if (t.find(words) != std::string::npos) return true;
  return false;
}

void SetupScan::add(const CanonCommand& c, std::size_t index) {
  if (c.kind == CanonKind::Traverse && cut_since_start_) {
    const double turned[3] = {c.end.a - c.start.a, c.end.b - c.start.b, c.end.c - c.start.c};
    static const char* const names = "ABC";
    for (int i = 0; i < 3; ++i) {
      if (!(std::abs(turned[i]) > 1e-9)) continue;
      const double to = i == 0 ? c.end.a : i == 1 ? c.end.b : c.end.c;
      char text[96];
      std::snprintf(text, sizeof text, "the part turned: %c%g (a rotary index)", names[i], to);
      starts_.push_back({index, c.line, text});
      cut_since_start_ = stopped_ = false;
      return;
    }
  }
  if (c.kind == CanonKind::Feed || c.kind == CanonKind::Arc) cut_since_start_ = true;
  if (c.kind == CanonKind::ProgramStop || c.kind == CanonKind::OptionalStop) {
    if (!stopped_) {
      stopped_ = true;
      stop_index_ = index;
      stop_line_ = c.line;
      stop_code_ = c.kind == CanonKind::ProgramStop ? "M0" : "M1";
      looked_to_ = c.line - 1; // the stop's own line may say why it stops
    }
    return;
  }
  if (c.kind == CanonKind::WorkOffset) {
    const int old = work_offset_;
    work_offset_ = int(c.value);
    if (stopped_ && work_offset_ != old) {
      cut_since_start_ = false;
      starts_.push_back({stop_index_ + 1, c.line,
                         stop_code_ + " at line " + std::to_string(stop_line_ + 1) + ", then " +
                             work_offset_name(work_offset_)});
      stopped_ = false;
    }
    return;
  }
  if (!stopped_) return;
  if (const std::string comment = setup_comment_before(c.line); !comment.empty()) {
    starts_.push_back(
        {stop_index_ + 1, c.line,
         stop_code_ + " at line " + std::to_string(stop_line_ + 1) + ", then (" + comment + ")"});
    stopped_ = cut_since_start_ = false;
  } else if (c.kind == CanonKind::Probe) {
    starts_.push_back(
        {stop_index_ + 1, c.line,
         stop_code_ + " at line " + std::to_string(stop_line_ + 1) + ", then a probing move"});
    stopped_ = cut_since_start_ = false;
  } else if (c.kind == CanonKind::Feed || c.kind == CanonKind::Arc) {
    stopped_ = false; // the same part goes on being cut
  }
}

SetupIndex::SetupIndex(std::vector<std::size_t> first_commands)
    : first_(std::move(first_commands)) {
  if (first_.empty()) first_.push_back(0);
}

std::size_t SetupIndex::of(std::size_t command) const {
  const auto it = std::upper_bound(first_.begin(), first_.end(), command);
  return it == first_.begin() ? 0 : std::size_t(it - first_.begin()) - 1;
}

std::size_t SetupIndex::first(std::size_t k) const {
  return k < first_.size() ? first_[k] : std::numeric_limits<std::size_t>::max();
}

} // namespace ncjoule::estimate_detail
