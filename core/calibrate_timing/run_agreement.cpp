// Whether the usable runs agree on each fitted key that only adds time (waits, tool changes,
// settling). A control setting that changed between runs (a coolant delay, an optional stop
// switched on, a spindle kept running through M30) gives two kinds of runs; one least-squares
// value then lies between them and matches neither, and a program checked later is off by the
// difference. The fit is not changed: the runs of each kind are named, so that the shop fits on
// the kind its machine runs as now, or looks at the setting.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "timing_model.hpp"

namespace ncjoule::timing_detail {
namespace {

// Runs apart by at least this much in a key's value (s), and by half the fitted value.
constexpr double kMinGapS = 1.0;
// A run counts when the key falls at least this often on its stretches; a kind of runs is at
// least this many (one run apart from the rest is an odd run, not a setting).
constexpr double kMinCount = 1.0;
constexpr std::size_t kMinRunsOfAKind = 2;

struct RunValue {
  double value = 0;
  std::size_t run = 0;
};

std::string run_list(const std::vector<RunValue>& runs, std::size_t begin, std::size_t end) {
  std::vector<std::size_t> numbers;
  for (std::size_t i = begin; i < end; ++i)
    numbers.push_back(runs[i].run + 1); // as the runs table numbers them
  std::sort(numbers.begin(), numbers.end());
  std::string s;
  for (std::size_t n : numbers)
    s += (s.empty() ? "" : ", ") + std::to_string(n);
  return s;
}

double median_value(const std::vector<RunValue>& runs, std::size_t begin, std::size_t end) {
  const std::size_t n = end - begin, mid = begin + n / 2;
  return n % 2 ? runs[mid].value : 0.5 * (runs[mid - 1].value + runs[mid].value);
}

} // namespace

std::vector<std::string> run_disagreements(const TimingModel& model,
                                           const std::vector<double>& residual_s,
                                           const std::vector<double>& linear_values,
                                           const std::vector<std::size_t>& fitted_linear) {
  std::vector<std::string> notes;
  const std::vector<Observation>& observations = model.observations();
  for (std::size_t k : fitted_linear) {
    // Each run's own least-squares value of the key, the other keys as fitted: the fitted value
    // plus its stretches' misfit (measured - predicted) per occurrence.
    std::map<std::size_t, std::pair<double, double>> sums; // run: (sum c*r, sum c^2)
    std::map<std::size_t, double> counts;
    for (std::size_t o = 0; o < observations.size(); ++o) {
      const double c = model.count(o, k);
      if (!(c > 0)) continue;
      auto& s = sums[observations[o].run];
      s.first += c * -residual_s[o];
      s.second += c * c;
      counts[observations[o].run] += c;
    }
    std::vector<RunValue> runs;
    for (const auto& [run, s] : sums)
      if (counts[run] >= kMinCount && s.second > 0)
        runs.push_back({linear_values[k] + s.first / s.second, run});
    if (runs.size() < 2 * kMinRunsOfAKind) continue;
    std::sort(runs.begin(), runs.end(),
              [](const RunValue& a, const RunValue& b) { return a.value < b.value; });
    // The widest gap between runs in order, and whether each side holds together on its own.
    std::size_t split = 0;
    double gap = 0;
    for (std::size_t i = 1; i < runs.size(); ++i)
      if (runs[i].value - runs[i - 1].value > gap)
        gap = runs[i].value - runs[i - 1].value, split = i;
    const double low_spread = runs[split - 1].value - runs.front().value;
    const double high_spread = runs.back().value - runs[split].value;
    if (gap < std::max(kMinGapS, 0.5 * linear_values[k]) ||
        gap < 2 * std::max(low_spread, high_spread))
      continue;
    const double low = median_value(runs, 0, split), high = median_value(runs, split, runs.size());
    char text[512];
    std::snprintf(text, sizeof text,
                  "%s: the runs disagree, about %.2f s in run%s %s and %.2f s in run%s %s; the "
                  "fitted %.2f s matches neither. A setting of the control that changed between "
                  "them (a delay, an optional stop switched on or off, the spindle kept running), "
                  "or time the log does not show: check the machine's setting, and calibrate on "
                  "the runs of the kind it runs as now",
                  timing_key_name(model.linear()[k]).c_str(), low, split > 1 ? "s" : "",
                  run_list(runs, 0, split).c_str(), high, runs.size() - split > 1 ? "s" : "",
                  run_list(runs, split, runs.size()).c_str(), linear_values[k]);
    notes.push_back(text);
  }
  return notes;
}

} // namespace ncjoule::timing_detail
