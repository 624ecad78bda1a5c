// Rule c with the prediction in the loop (optimize.hpp): the feeds are scaled from each block's
// predicted load, the written program's loads are predicted again, and a block still above the
// share is scaled again from the load it had. The cutting term need not be proportional to the
// feed (Kienzle's k_c(h) falls as the chip thickens), so one proportional step may fall short.
#include "ncjoule/estimate.hpp"
#include "ncjoule/optimize.hpp"
#include <algorithm>
#include <cmath>

namespace ncjoule {

std::map<int, double> mean_spindle_loads(const Estimate& estimate,
                                         const std::map<int, double>& rpm_by_line,
                                         const std::vector<int>* original_line) {
  constexpr std::size_t kCutting = static_cast<std::size_t>(PowerComponent::Cutting);
  std::map<int, double> out;
  for (const LineSummary& s : estimate.lines) {
    int line = s.line;
    if (original_line) {
      if (line < 0 || std::size_t(line) >= original_line->size()) continue;
      line = (*original_line)[std::size_t(line)];
      if (line < 0) continue;
    }
    const auto rpm = rpm_by_line.find(line);
    if (rpm == rpm_by_line.end() || !(s.time_s > 0) || !(s.components_j[kCutting] > 0)) continue;
    const double rated = rated_spindle_power_w(estimate.power, rpm->second);
    if (!(rated > 0)) continue;
    out[line] =
        double(s.components_j[kCutting]) * estimate.power.cutting_efficiency / s.time_s / rated;
  }
  return out;
}

std::map<int, double> spindle_rpm_by_line(const std::vector<CanonCommand>& commands) {
  std::map<int, double> out;
  for (const CanonCommand& c : commands)
    if (is_move(c.kind))
      out[c.line] =
          c.state.spindle != SpindleDir::Off && c.state.spindle_rpm > 0 ? c.state.spindle_rpm : 0;
  return out;
}

LoadedPlan plan_with_load_feeds(OptimizeInput input, const OptimizeOptions& options,
                                const LoadsOf& loads_of, int passes) {
  LoadedPlan out;
  std::map<int, LoadAt> loads = input.loads ? *input.loads : std::map<int, LoadAt>{};
  input.loads = &loads;
  const double share = options.load_share;
  for (int pass = 1;; ++pass) {
    out.plan = plan_optimization(input, options);
    out.text = write_optimized(*input.source, input.dialect, out.plan);
    out.passes = pass;
    out.over_share = 0;
    if (!options.load_feeds || !loads_of) break;
    bool scaled = false;
    for (const BlockEdit& e : out.plan.edits)
      scaled = scaled || e.rule == EditRule::LoadFeed;
    if (!scaled) break;
    const std::map<int, double> now = loads_of(out.text);
    for (const BlockEdit& e : out.plan.edits) {
      if (e.rule != EditRule::LoadFeed) continue;
      const auto it = now.find(e.line);
      // A tolerance of a thousandth: the load a feed rounded down to the written digits gives.
      if (it == now.end() || it->second <= share * 1.001) continue;
      ++out.over_share;
      // The exponent from the two loads, at the feed before and at this one.
      LoadAt& at = loads[e.line];
      const double f0 = at.feed_mm_min > 0 ? at.feed_mm_min : e.was_feed_mm_min;
      double exponent = at.exponent;
      // Within 0.5 (k_c as the chip thickness to -0.5, beyond Kienzle's mc of common materials)
      // and 1.5: a load that barely follows the feed is not chased with a feed far lower.
      if (f0 > 0 && at.load > 0 && std::abs(std::log(e.feed_mm_min / f0)) > 1e-3)
        exponent =
            std::clamp(std::log(it->second / at.load) / std::log(e.feed_mm_min / f0), 0.5, 1.5);
      at = LoadAt{it->second, e.feed_mm_min, exponent};
    }
    if (out.over_share == 0 || pass >= passes) break;
  }
  return out;
}

} // namespace ncjoule
