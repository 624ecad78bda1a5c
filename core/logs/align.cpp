// Aligning runs with programs: which program a run ran, read from the logged program name and
// the order of its lines, and whether the run is a whole, undisturbed run of it.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <tuple>

#include "ncjoule/logs.hpp"

namespace ncjoule {
namespace {

// A program's name as a control shows it, reduced to compare: NIST_MTC_CRADA_BOX_REV-A OP1
// (Bottom).NC and NIST_MTC_CRADA_BOX_REV-A_OP1.NC are the same program.
std::string name_key(std::string_view name) {
  if (const std::size_t slash = name.find_last_of("/\\"); slash != std::string_view::npos)
    name = name.substr(slash + 1);
  std::string out;
  int depth = 0;
  for (char c : name) {
    if (c == '(')
      ++depth;
    else if (c == ')')
      depth = std::max(0, depth - 1);
    else if (depth == 0 && std::isalnum(static_cast<unsigned char>(c)))
      out += char(std::toupper(static_cast<unsigned char>(c)));
  }
  for (std::string_view ext : {"NC", "NGC", "TAP", "CNC", "MPF", "PGM", "HWM", "EIA", "MIN", "H"})
    if (out.size() > ext.size() + 1 && out.compare(out.size() - ext.size(), ext.size(), ext) == 0 &&
        name.find('.') != std::string_view::npos) {
      out.resize(out.size() - ext.size());
      break;
    }
  return out;
}

// The names a program goes by: its file's, its O number's, its title comment's.
bool names_program(std::string_view logged, const ProgramOutline& p) {
  const std::string key = name_key(logged);
  if (key.empty()) return false;
  if (key == name_key(p.name)) return true;
  // "O0000(NIST_MTC_CRADA_PLATE)": the O number, and what the parentheses hold.
  const std::string& title = p.title;
  const std::size_t open = title.find('('), close = title.rfind(')');
  if (open != std::string::npos && close != std::string::npos && close > open &&
      key == name_key(title.substr(open + 1, close - open - 1)))
    return true;
  const std::string o = name_key(title.substr(0, open));
  return !o.empty() && o != "O0000" && key == o;
}

struct Reading {
  LineNumbering numbering = LineNumbering::FileLine;
  std::vector<TimedValue> marks; // (t, file line), consecutive duplicates dropped
  std::size_t unmapped = 0, backward = 0, tool_mismatches = 0;
  double first_backward_s = 0;
  bool ends_at_end = false;
  bool fits() const { return unmapped == 0 && tool_mismatches == 0 && !marks.empty(); }
};

Reading read_lines(const LogRun& run, const ProgramOutline& p, LineNumbering numbering) {
  Reading r;
  r.numbering = numbering;
  long current = 1;
  bool first = true;
  for (const TimedValue& v : run.lines) {
    const bool at_start = first && v.t_s < run.start_s;
    first = false;
    if (!std::isfinite(v.value)) continue;
    const long value = std::lround(v.value);
    long line = -1;
    if (numbering == LineNumbering::FileLine) {
      if (value == 0) continue; // the control's "no block" (reset)
      line = value;
    } else if (numbering == LineNumbering::FileLineFromZero) {
      line = value + 1;
    } else {
      for (long l = current; l < long(p.n_word.size()) && line < 0; ++l)
        if (p.n_word[std::size_t(l)] == value) line = l;
      for (long l = 1; l < current && line < 0; ++l) // wrapped back: a restart or a loop
        if (p.n_word[std::size_t(l)] == value) line = l;
    }
    if (line < 1 || line > p.lines) {
      // At cycle start a control may still show the line of the run before.
      if (!at_start) ++r.unmapped;
      continue;
    }
    // A line logged just before the start is the first the control shows; one logged long
    // before, or the program's end, is the last run's, shown until the first block runs.
    if (at_start && line > 1 &&
        (run.start_s - v.t_s > 2.0 || (p.end_line > 0 && line >= p.end_line)))
      continue;
    const double t = std::max(v.t_s, run.start_s);
    if (!r.marks.empty() && line < r.marks.back().value) {
      if (r.backward++ == 0) r.first_backward_s = t;
    }
    if (r.marks.empty() || r.marks.back().value != double(line))
      r.marks.push_back({t, double(line)});
    current = line;
  }
  // Tool changes: each new tool the log shows, at an M6 line loading that tool (the line
  // running then, or one of the two before it: the tool shows when the change ends).
  double last_tool = std::numeric_limits<double>::quiet_NaN();
  for (const TimedValue& tv : run.tool) {
    if (!(tv.value > 0) || tv.value == last_tool) continue;
    const bool at_start = tv.t_s < run.start_s;
    last_tool = tv.value;
    if (at_start) continue;
    auto it = std::upper_bound(r.marks.begin(), r.marks.end(), tv.t_s,
                               [](double t, const TimedValue& m) { return t < m.t_s; });
    bool ok = false;
    for (int back = 0; back < 3 && it != r.marks.begin() && !ok; ++back) {
      --it;
      const long line = std::lround(it->value);
      ok = line >= 1 && line < long(p.tool_at.size()) && p.tool_at[std::size_t(line)] != 0 &&
           (p.tool_at[std::size_t(line)] < 0 ||
            p.tool_at[std::size_t(line)] == std::lround(tv.value));
    }
    if (!ok) ++r.tool_mismatches;
  }
  r.ends_at_end = !r.marks.empty() && p.end_line > 0 && long(r.marks.back().value) == p.end_line;
  return r;
}

bool better(const Reading& a, const Reading& b) {
  auto key = [](const Reading& r) {
    return std::make_tuple(r.fits(), r.ends_at_end, -long(r.tool_mismatches), -long(r.unmapped),
                           -long(r.backward), r.marks.size());
  };
  return key(a) > key(b);
}

std::string clock(double t) {
  return format_log_time(t).substr(11, 8);
}

std::string percent_range(double lo, double hi) {
  char text[48];
  if (std::abs(hi - lo) < 0.005)
    std::snprintf(text, sizeof text, "%.0f%%", 100 * lo);
  else
    std::snprintf(text, sizeof text, "%.0f-%.0f%%", 100 * lo, 100 * hi);
  return text;
}

// Min and max of an override over the run (fractions); false when none was logged.
bool override_range(const std::vector<TimedValue>& values, double& lo, double& hi) {
  if (values.empty()) {
    lo = hi = 1;
    return false;
  }
  lo = INFINITY;
  hi = -INFINITY;
  for (const TimedValue& v : values) {
    lo = std::min(lo, v.value / 100);
    hi = std::max(hi, v.value / 100);
  }
  return true;
}

int first_line_of_work(const ProgramOutline& p) {
  // A run from the top shows its first tool change (or, without one, its first few blocks):
  // the lines before are settings a control runs faster than it logs them.
  for (int l = 1; l < int(p.tool_at.size()); ++l)
    if (p.tool_at[std::size_t(l)] != 0) return l + 1;
  int code = 0;
  for (int l = 1; l < int(p.code.size()); ++l)
    if (p.code[std::size_t(l)] && ++code == 3) return l;
  return p.lines;
}

void judge(const LogRun& run, const ProgramOutline& p, const Reading& r, RunAlignment& a,
           const AlignOptions& options) {
  const int first = a.marks.size() > 1 ? int(a.marks[1].value) : int(a.marks[0].value);
  const int last = int(a.marks.back().value);
  const bool top = first <= first_line_of_work(p);
  const bool end = p.end_line > 0 ? last >= p.end_line : last >= p.lines - 1;
  const bool ended_well = run.ended == "PROGRAM_COMPLETED" || (run.ended == "READY" && end);
  a.complete = top && end && ended_well && r.backward == 0;
  if (!top) a.why.push_back("did not start at the top (first line " + std::to_string(first) + ")");
  if (!end || !ended_well)
    a.why.push_back(
        "ended at line " + std::to_string(last) + " (" + run.ended + ")" +
        (p.end_line > 0 ? "; the program ends at line " + std::to_string(p.end_line) : ""));
  if (r.backward > 0)
    a.why.push_back("its lines run backwards at " + clock(r.first_backward_s) +
                    " (a restart, a jump or a subprogram)");
  std::vector<std::string> holds;
  for (const auto& [t, word] : run.states)
    if (word != "ACTIVE" && std::find(holds.begin(), holds.end(), word) == holds.end())
      holds.push_back(word);
  for (const std::string& h : holds) {
    const auto it = std::find_if(run.states.begin(), run.states.end(),
                                 [&](const auto& s) { return s.second == h; });
    a.why.push_back(h + " at " + clock(it->first));
  }
  for (const std::string& d : run.data_problems)
    a.why.push_back(d);
  double longest = 0;
  int longest_line = 0;
  for (std::size_t i = 1; i < a.marks.size(); ++i)
    if (a.marks[i].t_s - a.marks[i - 1].t_s > longest) {
      longest = a.marks[i].t_s - a.marks[i - 1].t_s;
      longest_line = int(a.marks[i - 1].value);
    }
  if (longest > options.max_line_s)
    a.why.push_back("stood " + std::to_string(int(longest)) + " s on line " +
                    std::to_string(longest_line) + " (held, or waiting for the operator)");
  a.feed_override_known =
      override_range(run.feed_override, a.feed_override_min, a.feed_override_max);
  a.rapid_override_known =
      override_range(run.rapid_override, a.rapid_override_min, a.rapid_override_max);
  for (int k = 0; k < 2; ++k) {
    const bool known = k == 0 ? a.feed_override_known : a.rapid_override_known;
    const double lo = k == 0 ? a.feed_override_min : a.rapid_override_min;
    const double hi = k == 0 ? a.feed_override_max : a.rapid_override_max;
    const std::string what = k == 0 ? "feed override" : "rapid override";
    if (!known) {
      a.notes.push_back(what + " not logged in this part of the log: taken as 100%");
    } else if (lo < options.min_override) {
      a.why.push_back(what + " at " + percent_range(lo, lo) +
                      " (the operator held the machine with the knob)");
    } else if (std::abs(lo - 1) > 0.005 || std::abs(hi - 1) > 0.005) {
      a.notes.push_back(what + " " + percent_range(lo, hi) +
                        " (logged; the prediction follows it)");
    }
  }
  a.usable = a.complete && a.why.empty();
}

} // namespace

double override_at(const std::vector<TimedValue>& values, double t_s, double fallback) {
  auto it = std::upper_bound(values.begin(), values.end(), t_s,
                             [](double t, const TimedValue& v) { return t < v.t_s; });
  if (it == values.begin()) return values.empty() ? fallback : values.front().value / 100;
  return std::prev(it)->value / 100;
}

std::vector<RunAlignment> align_runs(const std::vector<LogRun>& runs,
                                     const std::vector<ProgramOutline>& programs,
                                     const AlignOptions& options) {
  std::vector<RunAlignment> out;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const LogRun& run = runs[i];
    RunAlignment a;
    a.run = i;
    std::vector<LineNumbering> numberings;
    if (options.numbering == LineNumbering::Auto)
      numberings = {LineNumbering::FileLine, LineNumbering::FileLineFromZero, LineNumbering::NWord};
    else
      numberings = {options.numbering};
    std::vector<std::pair<std::size_t, Reading>> fitting;
    for (std::size_t k = 0; k < programs.size(); ++k) {
      std::optional<Reading> best;
      for (LineNumbering n : numberings) {
        Reading r = read_lines(run, programs[k], n);
        if (!best || better(r, *best)) best = std::move(r);
      }
      if (best && best->fits()) fitting.emplace_back(k, std::move(*best));
    }
    a.candidates = fitting.size();
    if (fitting.empty()) {
      a.why.push_back(
          run.lines.empty() ? "no line logged"
          : programs.empty()
              ? "no program given"
              : "fits none of the programs given (its lines or tools differ)" +
                    (run.program.empty() ? std::string() : "; the log names " + run.program));
      out.push_back(std::move(a));
      continue;
    }
    // The logged name decides among programs the lines fit alike; then the one that ends at
    // its end line; then the first given.
    std::size_t pick = 0;
    bool named = false;
    for (std::size_t k = 0; k < fitting.size(); ++k)
      if (!run.program.empty() && names_program(run.program, programs[fitting[k].first])) {
        pick = k;
        named = true;
        break;
      }
    if (!named)
      for (std::size_t k = 0; k < fitting.size(); ++k)
        if (fitting[k].second.ends_at_end && !fitting[pick].second.ends_at_end) pick = k;
    const ProgramOutline& p = programs[fitting[pick].first];
    Reading& r = fitting[pick].second;
    a.program = std::ptrdiff_t(fitting[pick].first);
    a.name_matches = named;
    a.numbering = r.numbering;
    a.marks.push_back({run.start_s, 1});
    for (const TimedValue& m : r.marks)
      if (m.value != a.marks.back().value) a.marks.push_back(m);
    if (!named && fitting.size() > 1) {
      for (const auto& f : fitting)
        a.alike.push_back(f.first);
      a.notes.push_back("its lines fit " + std::to_string(fitting.size()) +
                        " of the programs given alike" +
                        (run.program.empty() ? "" : " and the log names " + run.program) +
                        ": taken as " + p.name);
    } else if (!named && !run.program.empty())
      a.notes.push_back("the log names " + run.program + "; its lines are " + p.name + "'s");
    judge(run, p, r, a, options);
    out.push_back(std::move(a));
  }
  return out;
}

} // namespace ncjoule
