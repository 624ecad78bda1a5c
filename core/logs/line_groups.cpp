// Measured times of a run: the stretches between changes of the running line, and the time to
// each operation's start.
#include <algorithm>
#include <cmath>
#include <limits>

#include "ncjoule/logs.hpp"

namespace ncjoule {

std::vector<LineGroup> line_groups(const LogRun& run, const RunAlignment& alignment,
                                   const AlignOptions& options) {
  std::vector<LineGroup> groups;
  const auto& marks = alignment.marks;
  // Hold intervals: from a word other than ACTIVE to the next ACTIVE.
  std::vector<std::pair<double, double>> held;
  double since = NAN;
  for (const auto& [t, word] : run.states) {
    if (word != "ACTIVE" && std::isnan(since)) since = t;
    if (word == "ACTIVE" && !std::isnan(since)) {
      held.emplace_back(since, t);
      since = NAN;
    }
  }
  if (!std::isnan(since)) held.emplace_back(since, run.end_s);
  auto low_override = [&](double a, double b) {
    for (const std::vector<TimedValue>* values : {&run.feed_override, &run.rapid_override}) {
      if (values->empty()) continue;
      if (override_at(*values, a) < options.min_override) return true;
      for (const TimedValue& v : *values)
        if (v.t_s > a && v.t_s < b && v.value / 100 < options.min_override) return true;
    }
    return false;
  };
  for (std::size_t i = 0; i < marks.size(); ++i) {
    LineGroup g;
    g.first = int(marks[i].value);
    g.start_s = marks[i].t_s;
    const double end = i + 1 < marks.size() ? marks[i + 1].t_s : run.end_s;
    g.next = i + 1 < marks.size() ? int(marks[i + 1].value) : std::numeric_limits<int>::max();
    g.duration_s = end - g.start_s;
    for (const auto& [a, b] : held)
      g.disturbed = g.disturbed || (a < end && b > g.start_s);
    g.disturbed = g.disturbed || low_override(g.start_s, end);
    groups.push_back(g);
  }
  return groups;
}

std::vector<double> stretch_times(const RunAlignment& alignment, double end_s,
                                  const std::vector<int>& starts) {
  const auto& marks = alignment.marks;
  std::vector<double> at;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    if (marks.empty()) {
      at.push_back(NAN);
      continue;
    }
    if (k == 0 || starts[k] <= int(marks.front().value)) {
      at.push_back(marks.front().t_s);
      continue;
    }
    const auto it = std::find_if(marks.begin(), marks.end(),
                                 [&](const TimedValue& m) { return m.value >= starts[k]; });
    at.push_back(it == marks.end() ? NAN : it->t_s);
  }
  std::vector<double> durations;
  for (std::size_t k = 0; k < at.size(); ++k) {
    const double next = k + 1 < at.size() ? at[k + 1] : end_s;
    durations.push_back(next - at[k]);
  }
  return durations;
}

} // namespace ncjoule
