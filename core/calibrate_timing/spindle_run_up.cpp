// The spindle's run-up from rest, from the logged spindle speed: each run-up's time to reach
// every 1000 rpm, timed from where a straight line through its middle samples leaves 0 rpm (the
// first samples of a ramp may be missed: speeds are logged only on change, a sample period
// apart).
#include <algorithm>
#include <cmath>
#include <map>

#include "ncjoule/calibrate_timing.hpp"

namespace ncjoule {
namespace {

struct RunUp {
  std::vector<TimedValue> samples;
  double top = 0;
};

std::vector<RunUp> run_ups(const std::vector<TimedValue>& speeds) {
  std::vector<RunUp> out;
  std::optional<RunUp> current;
  double prev = speeds.empty() ? 0 : speeds.front().value;
  for (std::size_t i = 1; i < speeds.size(); ++i) {
    const TimedValue& s = speeds[i];
    if (!current) {
      if (prev <= 1 && s.value > prev + 1) current = RunUp{{s}, s.value};
    } else if (s.value < prev - 1 || s.t_s - current->samples.back().t_s > 2.0) {
      // Past the top (falling), or standing at it for a while: the run-up ended.
      if (current->samples.size() >= 4) out.push_back(std::move(*current));
      current.reset();
      if (s.value > prev + 1 && prev <= 1) current = RunUp{{s}, s.value};
    } else {
      current->samples.push_back(s);
      current->top = std::max(current->top, s.value);
    }
    prev = s.value;
  }
  if (current && current->samples.size() >= 4) out.push_back(std::move(*current));
  return out;
}

// When the run-up left 0 rpm: a least-squares line through its samples between 10% and 90% of
// its top speed, at 0 rpm.
std::optional<double> start_of(const RunUp& r) {
  double n = 0, st = 0, sv = 0, stt = 0, stv = 0;
  const double t0 = r.samples.front().t_s;
  for (const TimedValue& s : r.samples)
    if (s.value > 0.1 * r.top && s.value < 0.9 * r.top) {
      const double t = s.t_s - t0;
      n += 1;
      st += t;
      sv += s.value;
      stt += t * t;
      stv += t * s.value;
    }
  if (n < 3) return std::nullopt;
  const double slope = (n * stv - st * sv) / (n * stt - st * st);
  if (!(slope > 0)) return std::nullopt;
  const double intercept = (sv - slope * st) / n;
  return t0 - intercept / slope;
}

} // namespace

SpindleRunUp measure_spindle_run_up(const LogEvidence& evidence) {
  SpindleRunUp result;
  std::map<int, std::vector<double>> at_level; // rpm -> seconds from rest
  std::vector<double> rates;
  for (const LoggedRun& lr : evidence.program_runs) {
    if (!lr.usable) continue;
    for (const RunUp& r : run_ups(evidence.runs[lr.run].spindle)) {
      const auto start = start_of(r);
      if (!start) continue;
      ++result.run_ups;
      // The top is reached where the speed first comes within 1% of it.
      for (const TimedValue& s : r.samples)
        if (s.value >= 0.99 * r.top) {
          if (s.t_s > *start) rates.push_back(r.top / (s.t_s - *start));
          break;
        }
      for (int level = 1000; level <= r.top - 500; level += 1000) {
        for (std::size_t i = 1; i < r.samples.size(); ++i) {
          const TimedValue& a = r.samples[i - 1];
          const TimedValue& b = r.samples[i];
          if (a.value < level && b.value >= level) {
            const double t = a.t_s + (level - a.value) / (b.value - a.value) * (b.t_s - a.t_s);
            at_level[level].push_back(std::max(0.0, t - *start));
            break;
          }
        }
      }
    }
  }
  if (result.run_ups < 3) {
    result.run_ups = 0;
    return result;
  }
  for (auto& [level, times] : at_level) {
    if (times.size() < 3) continue;
    std::sort(times.begin(), times.end());
    const double median = times[times.size() / 2];
    // Rising in both: a noisy level may not come before the one below it.
    if (!result.points.empty() && median <= result.points.back().second) continue;
    result.points.emplace_back(level, median);
  }
  if (!rates.empty()) {
    std::sort(rates.begin(), rates.end());
    result.rpm_per_s = rates[rates.size() / 2];
  }
  return result;
}

} // namespace ncjoule
