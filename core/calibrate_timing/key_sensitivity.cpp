// The timing model: per-stretch counts of the keys that only add time, and the planned motion of
// every stretch for a set of plan parameters (the programs planned in parallel).
#include <algorithm>
#include <tbb/parallel_for.h>

#include "timing_model.hpp"

namespace ncjoule::timing_detail {
namespace {

// Per-line values summed over each observation's lines.
void sum_over(const std::vector<Observation>& obs, std::size_t program, const LineTimes& t,
              std::vector<double>& out) {
  for (std::size_t o = 0; o < obs.size(); ++o)
    if (obs[o].program == program)
      out[o] = t.between(obs[o].first, obs[o].next, obs[o].rapid, obs[o].feed);
}

} // namespace

TimingModel::TimingModel(const LogEvidence& evidence, const MachineProfile& base,
                         std::vector<Observation> observations, std::vector<TimingKey> linear)
    : evidence_(evidence), base_(base), observations_(std::move(observations)),
      linear_(std::move(linear)) {
  rapid_.assign(evidence.programs.size(), 0);
  for (const Observation& o : observations_) {
    if (std::find(programs_.begin(), programs_.end(), o.program) == programs_.end())
      programs_.push_back(o.program);
    if (std::abs(o.rapid - 1) > 1e-9) rapid_[o.program] = 1;
  }
  // Counts: each linear key at one second (the others at zero) against all at zero, at 100%
  // overrides (what they add does not follow an override).
  const std::size_t n = linear_.size();
  std::vector<std::vector<double>> per_key(n + 1, std::vector<double>(observations_.size(), 0.0));
  std::vector<std::pair<std::size_t, std::size_t>> tasks; // (key or n for none, program)
  for (std::size_t k = 0; k <= n; ++k)
    for (std::size_t p : programs_)
      tasks.emplace_back(k, p);
  std::vector<LineTimes> planned(tasks.size());
  tbb::parallel_for(std::size_t(0), tasks.size(), [&](std::size_t i) {
    const auto [k, p] = tasks[i];
    std::vector<double> one(n, 0.0);
    if (k < n) one[k] = 1;
    planned[i] = plan_line_times(evidence_.programs[p], machine({}, {}, one), false);
  });
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const auto [k, p] = tasks[i];
    for (std::size_t o = 0; o < observations_.size(); ++o)
      if (observations_[o].program == p)
        per_key[k][o] = planned[i].between(observations_[o].first, observations_[o].next);
  }
  counts_.assign(n, std::vector<double>(observations_.size(), 0.0));
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t o = 0; o < observations_.size(); ++o) {
      const double c = per_key[k][o] - per_key[n][o];
      counts_[k][o] = std::abs(c) < 1e-9 ? 0.0 : c;
    }
}

MachineProfile TimingModel::machine(const std::vector<PlanParameter>& parameters,
                                    const std::vector<double>& values,
                                    const std::vector<double>& linear_values) const {
  MachineProfile m = base_;
  for (std::size_t j = 0; j < parameters.size(); ++j)
    for (TimingKey key : parameters[j].keys)
      set_timing_key(m, key,
                     parameters[j].factor ? timing_key_value(base_, key) * values[j] : values[j]);
  for (std::size_t k = 0; k < linear_.size(); ++k) {
    set_timing_key(m, linear_[k], linear_values.empty() ? 0.0 : linear_values[k]);
    // The spindle's ramp is fitted as what the path waits for it: a control that does not
    // wait comes out at (nearly) zero.
    if (linear_[k] == TimingKey::SpindleRamp) m.kinematics.spindle_waits = true;
  }
  return m;
}

std::vector<double> TimingModel::motion(const std::vector<PlanParameter>& parameters,
                                        const std::vector<double>& values) const {
  const MachineProfile m = machine(parameters, values);
  std::vector<LineTimes> planned(programs_.size());
  tbb::parallel_for(std::size_t(0), programs_.size(), [&](std::size_t i) {
    const std::size_t p = programs_[i];
    planned[i] = plan_line_times(evidence_.programs[p], m, rapid_[p]);
  });
  std::vector<double> out(observations_.size(), 0.0);
  for (std::size_t i = 0; i < programs_.size(); ++i)
    sum_over(observations_, programs_[i], planned[i], out);
  return out;
}

} // namespace ncjoule::timing_detail
