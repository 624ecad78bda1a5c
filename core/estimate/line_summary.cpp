// Folding the per-command results into one summary per source line.
#include <algorithm>
#include <string_view>

#include "line_summary.hpp"

namespace ncjoule {

std::string kind_name(CanonKind kind) {
  switch (kind) {
  case CanonKind::Traverse:
    return "rapid";
  case CanonKind::Feed:
    return "feed";
  case CanonKind::Arc:
    return "arc";
  case CanonKind::Probe:
    return "probe";
  case CanonKind::Dwell:
    return "dwell";
  case CanonKind::SelectTool:
    return "select_tool";
  case CanonKind::ChangeTool:
    return "tool_change";
  case CanonKind::SpindleSpeed:
  case CanonKind::SpindleClockwise:
  case CanonKind::SpindleCounterClockwise:
  case CanonKind::SpindleStop:
    return "spindle";
  case CanonKind::MistOn:
  case CanonKind::FloodOn:
  case CanonKind::MistOff:
  case CanonKind::FloodOff:
    return "coolant";
  case CanonKind::ProgramStop:
    return "program_stop";
  case CanonKind::OptionalStop:
    return "optional_stop";
  case CanonKind::ProgramEnd:
    return "program_end";
  case CanonKind::Message:
    return "message";
  case CanonKind::Comment:
    return "comment";
  default:
    return "setting"; // feed rate, units, plane, offsets, path control, ...
  }
}

namespace {

// Whether a kind says more about a line than another: moves first, then what takes time.
int kind_rank(CanonKind kind) {
  switch (kind) {
  case CanonKind::Arc:
  case CanonKind::Feed:
  case CanonKind::Probe:
    return 5;
  case CanonKind::Traverse:
    return 4;
  case CanonKind::ChangeTool:
  case CanonKind::Dwell:
    return 3;
  case CanonKind::ProgramStop:
  case CanonKind::OptionalStop:
  case CanonKind::ProgramEnd:
  case CanonKind::SpindleSpeed:
  case CanonKind::SpindleClockwise:
  case CanonKind::SpindleCounterClockwise:
  case CanonKind::SpindleStop:
    return 2;
  case CanonKind::Comment:
  case CanonKind::Message:
    return 0;
  default:
    return 1;
  }
}

// True when the line holds something besides comments, whitespace and a '%' tape mark.
bool has_code(std::string_view text, const Dialect& dialect) {
  int depth = 0;
  for (char ch : text) {
    if (dialect.paren_comments && ch == '(') {
      depth = dialect.nested_paren_comments ? depth + 1 : 1;
      continue;
    }
    if (depth > 0) {
      if (ch == ')') --depth;
      continue;
    }
    if (dialect.semicolon_comments && ch == ';') break;
    if (ch == ' ' || ch == '\t' || ch == '%' || ch == '\r' || ch == '\n') continue;
    return true;
  }
  return false;
}

} // namespace

std::vector<LineSummary> summarise_lines(const SourceFile& source, const Dialect& dialect,
                                         const Timeline& timeline, const RemovalResult* removal,
                                         const EnergyResult& energy) {
  std::vector<LineSummary> lines(source.lines.size());
  std::vector<int> best_rank(source.lines.size(), -1);
  for (std::size_t k = 0; k < timeline.commands.size(); ++k) {
    const TimedCommand& c = timeline.commands[k];
    if (c.line < 0 || static_cast<std::size_t>(c.line) >= lines.size()) continue;
    LineSummary& b = lines[c.line];
    if (removal && k < removal->commands.size()) {
      b.removed_mm3 += removal->commands[k].removed_mm3;
      b.mrr_peak_mm3_s = std::max(b.mrr_peak_mm3_s, removal->commands[k].mrr_peak_mm3_s);
    }
    if (k < energy.commands.size()) {
      const CommandEnergy& e = energy.commands[k];
      b.energy_j += e.energy_j;
      b.power_peak_w = std::max(b.power_peak_w, e.peak_power_w);
      for (std::size_t i = 0; i < kPowerComponentCount; ++i)
        b.components_j[i] += e.components_j[i];
    }
    const bool move = c.kind == CanonKind::Traverse || c.kind == CanonKind::Feed ||
                      c.kind == CanonKind::Arc || c.kind == CanonKind::Probe;
    if (b.commands++ == 0) b.start_s = c.start_s;
    b.time_s += c.duration_s;
    b.length_mm += c.length_mm;
    b.peak_speed_mm_s = std::max(b.peak_speed_mm_s, c.peak_speed_mm_s);
    if (move) {
      if (!b.has_move) b.entry_speed_mm_s = c.entry_speed_mm_s;
      b.exit_speed_mm_s = c.exit_speed_mm_s;
      b.has_move = true;
    }
    if (!c.note.empty() && std::find(b.notes.begin(), b.notes.end(), c.note) == b.notes.end())
      b.notes.push_back(c.note);
    if (kind_rank(c.kind) > best_rank[c.line]) {
      best_rank[c.line] = kind_rank(c.kind);
      b.kind = kind_name(c.kind);
    }
  }
  std::vector<LineSummary> blocks;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    // Lines of comments only are left out; lines with code are kept even when they take no
    // time (G90, G21), so that every block of the program has its entry.
    const bool acts = lines[i].commands > 0 && best_rank[i] > 0;
    if (!acts && !has_code(source.line_text(i), dialect)) continue;
    lines[i].line = static_cast<int>(i);
    blocks.push_back(std::move(lines[i]));
  }
  return blocks;
}

} // namespace ncjoule
