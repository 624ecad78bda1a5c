// Each line's predicted time, split so that it follows the overrides a run was logged at: the
// rapid part of a line (what a plan at half the rapid rates adds, doubled) scales with 1/rapid
// override, a feed move's time with 1/feed override.
#include <algorithm>
#include <climits>

#include "ncjoule/calibrate_timing.hpp"

namespace ncjoule {
namespace {

std::vector<double> line_seconds(const Estimate& e, std::size_t lines, std::vector<char>* feed) {
  std::vector<double> t(lines + 2, 0.0);
  if (feed) feed->assign(lines + 2, 0);
  for (const LineSummary& l : e.lines) {
    const std::size_t line = std::size_t(l.line) + 1;
    if (line >= t.size()) continue;
    t[line] += l.time_s;
    if (feed && (l.kind == LineKind::Feed || l.kind == LineKind::Arc || l.kind == LineKind::Probe))
      (*feed)[line] = 1;
  }
  return t;
}

} // namespace

double LineTimes::total() const {
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    sum += a[i] + b[i];
  return sum;
}

double LineTimes::between(int first, int next, double rapid, double feed_override) const {
  const int end = std::min<long long>(next, static_cast<long long>(a.size()));
  double sum_a = 0, sum_b = 0;
  for (int l = std::max(first, 0); l < end; ++l) {
    sum_a += feed[std::size_t(l)] ? a[std::size_t(l)] / feed_override : a[std::size_t(l)];
    sum_b += b[std::size_t(l)];
  }
  return sum_a + (sum_b > 0 ? sum_b / rapid : 0.0);
}

LineTimes plan_line_times(const LoggedProgram& program, const MachineProfile& machine,
                          bool rapid_override) {
  LineTimes times;
  const std::size_t lines = program.source.lines.size();
  const Estimate full = estimate_program(program.source, machine, program.options);
  times.a = line_seconds(full, lines, &times.feed);
  times.b.assign(times.a.size(), 0.0);
  times.rapid_known = rapid_override;
  if (rapid_override) {
    MachineProfile half = machine;
    for (AxisLimits& axis : half.kinematics.axes)
      axis.rapid_mm_s *= 0.5;
    half.kinematics.rotary_rapid_deg_s *= 0.5;
    const std::vector<double> slow =
        line_seconds(estimate_program(program.source, half, program.options), lines, nullptr);
    for (std::size_t i = 0; i < times.a.size(); ++i) {
      // t(r) = a + b / r through t(1) and t(1/2); a line rapids do not touch keeps b = 0.
      const double b = std::max(0.0, slow[i] - times.a[i]);
      times.b[i] = b;
      times.a[i] -= b;
    }
  }
  return times;
}

} // namespace ncjoule
