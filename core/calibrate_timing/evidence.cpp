// The runs of the programs, aligned, measured and judged: what may be compared with a
// prediction and fitted, and why the rest may not.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "ncjoule/calibrate_timing.hpp"

namespace ncjoule {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string percent(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f%%", 100 * x);
  return text;
}

// Logged path speed over the programmed feed on the run's steady feed lines: single lines the
// log shows on their own, predicted to take a second or more, away from their ends.
std::vector<double> feed_ratios(const LogRun& run, const LoggedRun& r, const LoggedProgram& p,
                                const LogEvidence& evidence) {
  if (run.feed.empty()) return {};
  std::vector<double> peak(p.source.lines.size() + 2, 0.0);
  std::vector<double> time(p.source.lines.size() + 2, 0.0);
  std::vector<char> is_feed(p.source.lines.size() + 2, 0);
  for (const LineSummary& l : p.estimate.lines) {
    const std::size_t line = std::size_t(l.line) + 1;
    if (line >= peak.size()) continue;
    peak[line] = l.peak_speed_mm_s;
    time[line] += l.time_s;
    is_feed[line] = l.kind == LineKind::Feed;
  }
  std::vector<double> ratios;
  for (const LineGroup& g : r.groups) {
    if (g.disturbed || g.next != g.first + 1 || g.first >= int(peak.size())) continue;
    const std::size_t line = std::size_t(g.first);
    if (!is_feed[line] || time[line] < 1.0 || peak[line] <= 0 || g.duration_s < 1.0) continue;
    // Logged on change only: the speed in force at the line's middle, if the line's own (logged
    // after it began, once it had sped up).
    const double middle = g.start_s + 0.5 * g.duration_s;
    auto it = std::upper_bound(run.feed.begin(), run.feed.end(), middle,
                               [](double t, const TimedValue& v) { return t < v.t_s; });
    if (it == run.feed.begin()) continue;
    --it;
    if (it->t_s <= g.start_s + 0.1 || !(it->value > 0)) continue;
    ratios.push_back(it->value / peak[line] / evidence.feed_at(r, g.start_s));
  }
  return ratios;
}

double feed_ratio(const LogRun& run, const LoggedRun& r, const LoggedProgram& p,
                  const LogEvidence& evidence) {
  const std::vector<double> ratios = feed_ratios(run, r, p, evidence);
  return ratios.size() >= 5 ? median(ratios) : 0;
}

// How far a program's feeds are from the logged speeds, line by line: the mean of |log ratio|,
// each capped at a factor of 1.5 (a line the log caught while slowing down counts once). Of two
// programs that differ in one operation's feed, the one that ran has its lines at 0 there.
double feed_misfit(const std::vector<double>& ratios) {
  if (ratios.size() < 5) return INFINITY;
  double sum = 0;
  for (double x : ratios)
    sum += std::min(std::abs(std::log(x)), std::log(1.5));
  return sum / double(ratios.size());
}

// Measured over predicted time of the run's stretches of rapid lines alone.
double rapid_ratio(const LoggedRun& r, const LoggedProgram& p, const LineTimes& times,
                   const LogEvidence& evidence) {
  std::vector<char> rapid(p.source.lines.size() + 2, 0), timed(p.source.lines.size() + 2, 0);
  for (const LineSummary& l : p.estimate.lines) {
    const std::size_t line = std::size_t(l.line) + 1;
    if (line >= rapid.size()) continue;
    rapid[line] = l.kind == LineKind::Rapid;
    timed[line] = l.time_s > 0;
  }
  double measured = 0, predicted = 0;
  for (const LineGroup& g : r.groups) {
    if (g.disturbed) continue;
    bool only_rapids = true, any = false;
    for (int l = g.first; l < g.next && l < int(rapid.size()) && only_rapids; ++l) {
      if (!timed[std::size_t(l)]) continue;
      only_rapids = rapid[std::size_t(l)];
      any = true;
    }
    if (!any || !only_rapids) continue;
    const double pred = times.between(g.first, g.next, evidence.rapid_at(r, g.start_s),
                                      evidence.feed_at(r, g.start_s));
    if (pred < 0.3) continue;
    measured += g.duration_s;
    predicted += pred;
  }
  return predicted >= 3 ? measured / predicted : 0;
}

} // namespace

double LogEvidence::rapid_at(const LoggedRun& r, double t_s) const {
  return override_at(runs[r.run].rapid_override, t_s, 1);
}

double LogEvidence::feed_at(const LoggedRun& r, double t_s) const {
  return override_at(runs[r.run].feed_override, t_s, 1);
}

void gather_runs(LogEvidence& evidence, const EvidenceOptions& options) {
  std::vector<ProgramOutline> outlines;
  for (const LoggedProgram& p : evidence.programs)
    outlines.push_back(p.outline);
  evidence.alignments = align_runs(evidence.runs, outlines, options.align);
  evidence.program_runs.clear();
  for (const RunAlignment& a : evidence.alignments) {
    if (a.program < 0) continue;
    const LogRun& run = evidence.runs[a.run];
    LoggedRun r;
    r.run = a.run;
    r.program = std::size_t(a.program);
    r.groups = line_groups(run, a, options.align);
    r.measured_s = run.end_s - run.start_s;
    r.usable = a.usable;
    r.why = a.why;
    r.notes = a.notes;
    evidence.program_runs.push_back(std::move(r));
  }
}

bool needs_rapid_override(const LogEvidence& evidence, std::size_t program) {
  for (const LoggedRun& r : evidence.program_runs) {
    if (r.program != program) continue;
    const RunAlignment& a = evidence.alignments[r.run];
    if (a.rapid_override_known &&
        (std::abs(a.rapid_override_min - 1) > 0.005 || std::abs(a.rapid_override_max - 1) > 0.005))
      return true;
  }
  return false;
}

// A run whose lines fit several programs alike ran the one whose feeds its logged path speeds
// show (programs of one toolpath at different feeds and speeds, a test plan: the first given is
// not the one that ran, and two may differ in one operation's feed only). The program whose
// feeds are nearest the logged speeds line by line (feed_misfit) is taken, when its median
// speed/F is within the tolerance; the alignment's note says so. Only among programs of the same
// lines as the one taken, so that the run's line groups hold for each.
void pick_by_feeds(LogEvidence& evidence, LoggedRun& r, double tolerance) {
  RunAlignment& a = evidence.alignments[r.run];
  if (a.alike.size() < 2) return;
  const LogRun& run = evidence.runs[r.run];
  const LoggedProgram& taken = evidence.programs[r.program];
  const std::vector<double> taken_ratios = feed_ratios(run, r, taken, evidence);
  std::size_t best = r.program;
  double best_misfit = feed_misfit(taken_ratios);
  for (std::size_t k : a.alike) {
    const LoggedProgram& p = evidence.programs[k];
    if (k == r.program || p.outline.lines != taken.outline.lines) continue;
    const std::vector<double> ratios = feed_ratios(run, r, p, evidence);
    const double misfit = feed_misfit(ratios);
    if (misfit < best_misfit && std::abs(median(ratios) - 1) <= tolerance)
      best = k, best_misfit = misfit;
  }
  if (best == r.program) return;
  const std::string was = taken.outline.name;
  r.program = best;
  a.program = std::ptrdiff_t(best);
  // Composed, not printed into a buffer: a program's name may be long.
  const std::string text = " (its logged speeds match its feeds best: with " + was +
                           "'s its feed lines ran at " +
                           percent(taken_ratios.size() >= 5 ? median(taken_ratios) : 0) + " of F)";
  const std::string now = evidence.programs[best].outline.name;
  for (std::vector<std::string>* notes : {&r.notes, &a.notes})
    for (std::string& n : *notes)
      if (const std::size_t at = n.rfind(": taken as " + was);
          n.rfind("its lines fit", 0) == 0 && at != std::string::npos)
        n = n.substr(0, at) + ": taken as " + now + text;
}

void judge_runs(LogEvidence& evidence, const std::vector<LineTimes>& times,
                const EvidenceOptions& options) {
  std::vector<double> rapid_ratios;
  for (LoggedRun& r : evidence.program_runs) {
    pick_by_feeds(evidence, r, options.feed_ratio_tolerance);
    const LogRun& run = evidence.runs[r.run];
    const LoggedProgram& p = evidence.programs[r.program];
    r.feed_ratio = feed_ratio(run, r, p, evidence);
    if (r.feed_ratio > 0 && std::abs(r.feed_ratio - 1) > options.feed_ratio_tolerance) {
      const RunAlignment& a = evidence.alignments[r.run];
      r.why.push_back("its feed lines ran at " + percent(r.feed_ratio) +
                      " of F x the feed override " +
                      (a.feed_override_known ? "logged" : "taken as 100%") +
                      ": the override in force was not what the log says");
      r.usable = false;
    }
    if (r.program < times.size()) r.rapid_ratio = rapid_ratio(r, p, times[r.program], evidence);
    if (r.usable && r.rapid_ratio > 0) rapid_ratios.push_back(r.rapid_ratio);
  }
  // Rapids that took far longer (or shorter) than the other runs' for their prediction ran at a
  // rapid override the log does not hold.
  if (rapid_ratios.size() >= 3) {
    const double typical = median(rapid_ratios);
    for (LoggedRun& r : evidence.program_runs) {
      if (r.rapid_ratio <= 0 ||
          std::abs(r.rapid_ratio / typical - 1) <= options.rapid_ratio_tolerance)
        continue;
      char text[200];
      std::snprintf(text, sizeof text,
                    "its rapids took %.2f times their prediction where the other runs' took "
                    "%.2f: it ran at a rapid override the log does not hold",
                    r.rapid_ratio, typical);
      r.why.push_back(text);
      r.usable = false;
    }
  }
}

} // namespace ncjoule
