// Internal: the timing model the fit works on. Every observed stretch of a run (lines first to
// next at the overrides in force) is predicted as the planned motion time of its lines, which
// depends on the keys that shape the plan (rates, accelerations, the block-end ratio: theta),
// plus the keys that only add time (settle, tool change, waits: the linear keys) times how often
// each falls on those lines. The counts are planned once; the motion is planned again for every
// theta the solver tries, every program at once.
#pragma once

#include <string>
#include <vector>

#include "ncjoule/calibrate_timing.hpp"

namespace ncjoule::timing_detail {

struct Observation {
  std::size_t program = 0;
  std::size_t run = 0; // index into evidence.program_runs
  int first = 0, next = 0;
  double measured_s = 0;
  double rapid = 1, feed = 1; // overrides in force (fractions)
  double sigma_s = 0.1;
};

// A parameter of the plan: a factor on the base value of one key, or of several tied together
// (axes the logs cannot tell apart), or (the block-end ratio) the key's own value.
struct PlanParameter {
  std::vector<TimingKey> keys;
  bool factor = true;
  double initial = 1, lower = 0.2, upper = 5, step = 0.01;
  std::string label;
};

class TimingModel {
public:
  TimingModel(const LogEvidence& evidence, const MachineProfile& base,
              std::vector<Observation> observations, std::vector<TimingKey> linear);

  const std::vector<Observation>& observations() const { return observations_; }
  const std::vector<TimingKey>& linear() const { return linear_; }
  // How many times linear key k falls on observation o's lines (seconds per second of the key).
  double count(std::size_t o, std::size_t k) const { return counts_[k][o]; }
  // Planned motion time of every observation with the plan parameters at `values`.
  std::vector<double> motion(const std::vector<PlanParameter>& parameters,
                             const std::vector<double>& values) const;
  // The machine with the plan parameters at `values` and the linear keys at `linear_values`
  // (all of them zero when empty: the machine the motion is planned on).
  MachineProfile machine(const std::vector<PlanParameter>& parameters,
                         const std::vector<double>& values,
                         const std::vector<double>& linear_values = {}) const;
  std::size_t programs_planned() const { return programs_.size(); }

private:
  const LogEvidence& evidence_;
  MachineProfile base_;
  std::vector<Observation> observations_;
  std::vector<TimingKey> linear_;
  std::vector<std::size_t> programs_;       // programs with observations
  std::vector<char> rapid_;                 // per program: plan the rapid part
  std::vector<std::vector<double>> counts_; // [linear key][observation]
};

} // namespace ncjoule::timing_detail
