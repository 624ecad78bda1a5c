// Internal: the timing model the fit works on. Every observed stretch of a run (lines first to
// next at the overrides in force) is predicted as the planned motion time of its lines, which
// depends on the keys that shape the plan (rates, accelerations, the block-end ratio: theta),
// plus the keys that only add time (settle, tool change, waits: the linear keys) times how often
// each falls on those lines. The counts are planned once; the motion is planned again for every
// theta the solver tries, every program at once.
#pragma once

#include <Eigen/Dense>
#include <map>
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
  // A key that only matters below its base value (a limit no move reaches there) shows no
  // sensitivity at it: its sensitivity is taken at `start` instead, where moves feel it, and the
  // solver starts there (below 0: at `initial`).
  double start = -1;
  std::string label;
};

// The undisturbed stretches of every usable run, consecutive ones joined until they last
// options.min_stretch_s (a line's time the log gives to its neighbour is then inside one
// observation), none across a change of override; a run whose rapid override was not logged
// (where the log records one) gives its stretches without rapids only. `runs_used`: the runs
// that gave any; `notes`: what was left out.
std::vector<Observation> fit_observations(const LogEvidence& evidence,
                                          const TimingFitOptions& options, std::size_t& runs_used,
                                          std::vector<std::string>& notes);

// A key's sensitivity: d(stretch time)/d(key) / sigma, per observation.
struct KeyColumn {
  std::string label;
  Eigen::VectorXd values;
  bool theta = false;    // a planned key (a factor, or the ratio's own value)
  std::size_t index = 0; // into the plan parameters or the linear keys
  double scale = 1;      // what "half its value" is for a planned key
};
struct KeySelection {
  std::vector<char> keep;
  std::map<std::size_t, std::string> why; // of each key held
};
// key_identifiability.cpp. `misfit`: the base profile's residuals over sigma.
KeySelection select_keys(const std::vector<KeyColumn>& columns, const Eigen::VectorXd& misfit,
                         double sigma_s);

class TimingModel;
// run_agreement.cpp: for each fitted key that only adds time, whether the usable runs split into
// two kinds whose own values are far apart (a setting that changed between runs); a note for
// each such key, naming the runs of each kind. `residual_s`: predicted - measured per
// observation with the fitted values.
std::vector<std::string> run_disagreements(const TimingModel& model,
                                           const std::vector<double>& residual_s,
                                           const std::vector<double>& linear_values,
                                           const std::vector<std::size_t>& fitted_linear);

inline double cosine(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const double na = a.norm(), nb = b.norm();
  return na > 0 && nb > 0 ? a.dot(b) / (na * nb) : 0;
}

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
