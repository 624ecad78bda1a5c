// The timing fit: the profile's timing keys fitted with Ceres to the stretches of the usable
// runs. Before the fit, the keys the logs cannot tell are found from the model's sensitivities
// at the base profile: a key no logged stretch depends on is not in the logs; one whose effect
// on the stretches is (nearly) that of keys already fitted cannot be told apart from them; the
// axes' rates and accelerations are fitted as one factor when their effects cannot be told apart.
// Those are left as in the base profile, and the fit says why.
#include <Eigen/Dense>
#include <algorithm>
#include <ceres/ceres.h>
#include <ceres/normal_prior.h>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>

#include "timing_model.hpp"

namespace ncjoule {
namespace {

using timing_detail::cosine;
using timing_detail::KeyColumn;
using timing_detail::KeySelection;
using timing_detail::Observation;
using timing_detail::PlanParameter;
using timing_detail::select_keys;
using timing_detail::TimingModel;

// Whether the fitted arc acceleration (parameter j) holds any logged arc below what the axes
// allow: planned with it raised to its bound (the axes' own), no stretch moves by a millisecond.
bool arcs_held(const TimingModel& model, const std::vector<PlanParameter>& parameters,
               const std::vector<double>& theta, std::size_t j) {
  std::vector<double> free = theta;
  free[j] = parameters[j].upper;
  const std::vector<double> held = model.motion(parameters, theta);
  const std::vector<double> unheld = model.motion(parameters, free);
  for (std::size_t o = 0; o < held.size(); ++o)
    if (std::abs(held[o] - unheld[o]) > 1e-3) return true;
  return false;
}

std::vector<TimingKey> default_keys(const MachineProfile& base) {
  std::vector<TimingKey> keys;
  for (std::size_t i = 0; i < kTimingKeyCount; ++i) {
    const auto key = static_cast<TimingKey>(i);
    if ((key == TimingKey::TransitionRatio || key == TimingKey::ArcAccel) &&
        base.kinematics.junction_rule == JunctionRule::LinuxCnc29)
      continue; // that rule blends and limits arcs as LinuxCNC does, without a ratio
    if (key == TimingKey::SpindleRamp && !base.kinematics.spindle_run_up.empty())
      continue; // a measured run-up curve times the spindle: nothing to fit
    keys.push_back(key);
  }
  return keys;
}

// The motion and its derivatives at the theta Ceres asks for, planned once per theta.
class MotionCache {
public:
  MotionCache(const TimingModel& model, const std::vector<PlanParameter>& parameters)
      : model_(model), parameters_(parameters) {}

  const std::vector<double>& values(const double* theta) {
    const std::vector<double> t(theta, theta + parameters_.size());
    if (t != at_ || motion_.empty()) {
      at_ = t;
      motion_ = model_.motion(parameters_, at_);
      ++plans_;
    }
    return motion_;
  }

  const std::vector<std::vector<double>>& derivatives(const double* theta) {
    values(theta);
    if (derivatives_at_ == at_ && !derivatives_.empty()) return derivatives_;
    derivatives_at_ = at_;
    derivatives_.assign(parameters_.size(), {});
    for (std::size_t j = 0; j < parameters_.size(); ++j) {
      std::vector<double> moved = at_;
      double h = parameters_[j].step;
      if (moved[j] + h > parameters_[j].upper) h = -h;
      moved[j] += h;
      const std::vector<double> m = model_.motion(parameters_, moved);
      ++plans_;
      derivatives_[j].resize(m.size());
      for (std::size_t o = 0; o < m.size(); ++o)
        derivatives_[j][o] = (m[o] - motion_[o]) / h;
    }
    return derivatives_;
  }

  std::size_t plans() const { return plans_; }

private:
  const TimingModel& model_;
  const std::vector<PlanParameter>& parameters_;
  std::vector<double> at_, derivatives_at_;
  std::vector<double> motion_;
  std::vector<std::vector<double>> derivatives_;
  std::size_t plans_ = 0;
};

class StretchCost : public ceres::CostFunction {
public:
  StretchCost(MotionCache& cache, const TimingModel& model, std::size_t o, std::size_t n_theta,
              std::size_t n_linear)
      : cache_(cache), model_(model), o_(o), n_theta_(n_theta), n_linear_(n_linear) {
    set_num_residuals(1);
    if (n_theta_) mutable_parameter_block_sizes()->push_back(int(n_theta_));
    if (n_linear_) mutable_parameter_block_sizes()->push_back(int(n_linear_));
  }

  bool Evaluate(double const* const* p, double* residuals, double** jacobians) const override {
    static const double none = 1; // a theta with no parameter
    const double* theta = n_theta_ ? p[0] : &none;
    const double* linear = n_linear_ ? p[n_theta_ ? 1 : 0] : nullptr;
    const Observation& ob = model_.observations()[o_];
    double predicted = n_theta_ ? cache_.values(theta)[o_] : fixed_motion_;
    for (std::size_t k = 0; k < n_linear_; ++k)
      predicted += linear[k] * model_.count(o_, k);
    residuals[0] = (predicted - ob.measured_s) / ob.sigma_s;
    if (!jacobians) return true;
    if (n_theta_ && jacobians[0]) {
      const auto& d = cache_.derivatives(theta);
      for (std::size_t j = 0; j < n_theta_; ++j)
        jacobians[0][j] = d[j][o_] / ob.sigma_s;
    }
    double* jl = n_linear_ ? jacobians[n_theta_ ? 1 : 0] : nullptr;
    if (jl)
      for (std::size_t k = 0; k < n_linear_; ++k)
        jl[k] = model_.count(o_, k) / ob.sigma_s;
    return true;
  }

  double fixed_motion_ = 0; // the motion when no plan parameter is fitted

private:
  MotionCache& cache_;
  const TimingModel& model_;
  std::size_t o_, n_theta_, n_linear_;
};

std::string axis_list(const std::vector<TimingKey>& keys) {
  std::string s;
  for (TimingKey k : keys)
    s += (s.empty() ? "" : ", ") + std::string(1, "XYZXYZ"[std::size_t(k) % 3]);
  return s;
}

} // namespace

TimingFit fit_timing(const LogEvidence& evidence, const MachineProfile& base,
                     const TimingFitOptions& options) {
  TimingFit fit;
  fit.machine = base;
  const std::vector<TimingKey> keys = options.keys.empty() ? default_keys(base) : options.keys;
  for (TimingKey k : keys) {
    FittedTimingKey f;
    f.key = k;
    f.base = f.value = timing_key_value(base, k);
    fit.keys.push_back(f);
  }
  auto entry = [&](TimingKey k) -> FittedTimingKey& {
    return *std::find_if(fit.keys.begin(), fit.keys.end(),
                         [&](const FittedTimingKey& f) { return f.key == k; });
  };

  std::vector<std::string> obs_notes;
  std::size_t runs_used = 0;
  const std::vector<Observation> observations =
      timing_detail::fit_observations(evidence, options, runs_used, obs_notes);
  fit.notes.insert(fit.notes.end(), obs_notes.begin(), obs_notes.end());
  fit.stretches = observations.size();
  fit.runs = runs_used;
  if (observations.empty()) {
    fit.message = "no usable run of the programs given: nothing to fit";
    for (FittedTimingKey& f : fit.keys)
      f.why = "no usable run";
    return fit;
  }

  std::vector<TimingKey> linear, plan_keys;
  for (TimingKey k : keys)
    (timing_key_info(k).linear ? linear : plan_keys).push_back(k);
  const TimingModel model(evidence, base, observations, linear);
  const std::size_t n_obs = observations.size();

  // Sensitivities at the base: one factor per key of the plan (ratio: its own value).
  std::vector<PlanParameter> each;
  for (TimingKey k : plan_keys) {
    PlanParameter p;
    p.keys = {k};
    p.label = timing_key_name(k);
    if (k == TimingKey::TransitionRatio) {
      p.factor = false;
      p.initial = timing_key_value(base, k);
      p.lower = 0.01;
      p.upper = 1;
      p.step = 0.01;
    } else if (timing_key_value(base, k) <= 0) {
      continue; // a factor on nothing
    }
    if (k == TimingKey::RapidX || k == TimingKey::RapidY || k == TimingKey::RapidZ) {
      // A rapid rate below the axis's highest feed is no machine's (the profile would not load).
      const AxisLimits& axis =
          base.kinematics.axes[std::size_t(k) - std::size_t(TimingKey::RapidX)];
      p.lower = std::max(p.lower, axis.max_feed_mm_s / axis.rapid_mm_s);
    }
    if (k == TimingKey::ArcAccel) {
      // Arcs are held to the in-plane axes' acceleration whatever this says: above it the key
      // changes nothing. A control may hold small arcs far below it (a twentieth and more). At
      // the base no arc feels it: its sensitivity is taken at 0.3 of it, and the fit starts there.
      p.lower = 0.05;
      p.start = 0.3;
      const Kinematics& kin = base.kinematics;
      p.upper = std::max(1.0, std::min(kin.axes[0].accel_mm_s2, kin.axes[1].accel_mm_s2) /
                                  timing_key_value(base, k));
    }
    each.push_back(p);
  }
  std::vector<double> initial_each;
  for (const PlanParameter& p : each)
    initial_each.push_back(p.initial);
  const std::vector<double> base_motion = model.motion(each, initial_each);
  std::vector<Eigen::VectorXd> each_column;
  for (std::size_t j = 0; j < each.size(); ++j) {
    std::vector<double> moved = initial_each;
    std::vector<double> from_motion;
    if (each[j].start >= 0) {
      moved[j] = each[j].start;
      from_motion = model.motion(each, moved);
    }
    const std::vector<double>& from = each[j].start >= 0 ? from_motion : base_motion;
    double h = each[j].step;
    if (moved[j] + h > each[j].upper) h = -h;
    moved[j] += h;
    const std::vector<double> m = model.motion(each, moved);
    Eigen::VectorXd c(n_obs);
    for (std::size_t o = 0; o < n_obs; ++o)
      c[o] = (m[o] - from[o]) / h / observations[o].sigma_s;
    each_column.push_back(c);
  }
  // Before: the base profile's prediction.
  {
    double sse = 0;
    for (std::size_t o = 0; o < n_obs; ++o) {
      double p = base_motion[o];
      for (std::size_t k = 0; k < linear.size(); ++k)
        p += timing_key_value(base, linear[k]) * model.count(o, k);
      sse += (p - observations[o].measured_s) * (p - observations[o].measured_s);
    }
    fit.rms_before_s = std::sqrt(sse / double(n_obs));
  }

  // Plan parameters: per axis where the logs tell the axes apart, else one factor for them.
  std::vector<PlanParameter> parameters;
  std::vector<Eigen::VectorXd> parameter_columns;
  auto group = [&](std::initializer_list<TimingKey> axis_keys, const char* what) {
    std::vector<std::size_t> idx;
    for (std::size_t j = 0; j < each.size(); ++j)
      if (std::find(axis_keys.begin(), axis_keys.end(), each[j].keys[0]) != axis_keys.end())
        idx.push_back(j);
    if (idx.empty()) return;
    bool apart = !options.tie_axes || idx.size() == 1;
    if (!apart) {
      apart = true;
      double largest = 0;
      for (std::size_t j : idx)
        largest = std::max(largest, each_column[j].norm());
      for (std::size_t a = 0; a < idx.size() && apart; ++a) {
        if (each_column[idx[a]].norm() < 0.05 * largest) apart = false;
        for (std::size_t b = a + 1; b < idx.size() && apart; ++b)
          if (std::abs(cosine(each_column[idx[a]], each_column[idx[b]])) > 0.5) apart = false;
      }
    }
    if (apart) {
      for (std::size_t j : idx) {
        parameters.push_back(each[j]);
        parameter_columns.push_back(each_column[j]);
      }
      return;
    }
    PlanParameter tied;
    Eigen::VectorXd column = Eigen::VectorXd::Zero(Eigen::Index(n_obs));
    for (std::size_t j : idx) {
      tied.keys.push_back(each[j].keys[0]);
      tied.lower = std::max(tied.lower, each[j].lower);
      column += each_column[j]; // d/d(common factor) = sum of the axes' d/d(factor)
    }
    tied.label = std::string(what) + " (" + axis_list(tied.keys) + " as one factor)";
    fit.notes.push_back(std::string("the logs cannot tell the axes' ") + what +
                        "s apart: one factor on the base profile's (" + axis_list(tied.keys) + ")");
    parameters.push_back(tied);
    parameter_columns.push_back(column);
  };
  group({TimingKey::AccelX, TimingKey::AccelY, TimingKey::AccelZ}, "acceleration");
  group({TimingKey::RapidX, TimingKey::RapidY, TimingKey::RapidZ}, "rapid rate");
  for (std::size_t j = 0; j < each.size(); ++j)
    if (each[j].keys[0] == TimingKey::TransitionRatio || each[j].keys[0] == TimingKey::ArcAccel) {
      parameters.push_back(each[j]);
      parameter_columns.push_back(each_column[j]);
    }

  // Which keys the logs determine (key_identifiability.cpp), from the sensitivities and the
  // base profile's misfit.
  Eigen::VectorXd misfit(static_cast<Eigen::Index>(n_obs));
  for (std::size_t o = 0; o < n_obs; ++o) {
    double p = base_motion[o];
    for (std::size_t k = 0; k < linear.size(); ++k)
      p += timing_key_value(base, linear[k]) * model.count(o, k);
    misfit[Eigen::Index(o)] = (p - observations[o].measured_s) / observations[o].sigma_s;
  }
  std::vector<KeyColumn> columns;
  for (std::size_t j = 0; j < parameters.size(); ++j)
    columns.push_back({parameters[j].label, parameter_columns[j], true, j,
                       parameters[j].factor ? 1.0 : std::max(parameters[j].initial, 0.05)});
  for (std::size_t k = 0; k < linear.size(); ++k) {
    Eigen::VectorXd c(n_obs);
    std::size_t evidence_lines = 0;
    for (std::size_t o = 0; o < n_obs; ++o) {
      c[Eigen::Index(o)] = model.count(o, k) / observations[o].sigma_s;
      evidence_lines += model.count(o, k) != 0;
    }
    entry(linear[k]).evidence = evidence_lines;
    columns.push_back({timing_key_name(linear[k]), c, false, k, 1.0});
  }
  const KeySelection selected = select_keys(columns, misfit, options.stretch_sigma_s);
  const std::vector<char>& keep = selected.keep;
  std::map<std::size_t, std::string> held_why = selected.why;
  // What is held stays as in the base profile.
  std::vector<PlanParameter> fitted_plan;
  std::vector<std::size_t> fitted_linear;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (columns[c].theta) {
      if (keep[c])
        fitted_plan.push_back(parameters[columns[c].index]);
      else
        for (TimingKey k : parameters[columns[c].index].keys)
          entry(k).why = held_why[c];
    } else {
      if (keep[c])
        fitted_linear.push_back(columns[c].index);
      else
        entry(linear[columns[c].index]).why = held_why[c];
    }
  }
  for (const PlanParameter& p : each)
    if (std::none_of(parameters.begin(), parameters.end(), [&](const PlanParameter& q) {
          return std::find(q.keys.begin(), q.keys.end(), p.keys[0]) != q.keys.end();
        }))
      entry(p.keys[0]).why = "its base value is 0";
  for (TimingKey k : plan_keys)
    if (entry(k).why.empty() && std::none_of(each.begin(), each.end(), [&](const PlanParameter& p) {
          return p.keys[0] == k;
        }))
      entry(k).why = "its base value is 0: a factor on it has nothing to scale";

  // The fit.
  std::vector<double> theta;
  for (const PlanParameter& p : fitted_plan)
    theta.push_back(p.start >= 0 ? p.start : p.initial);
  std::vector<double> lin(linear.size());
  for (std::size_t k = 0; k < linear.size(); ++k)
    lin[k] = timing_key_value(base, linear[k]);
  MotionCache cache(model, fitted_plan);
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  std::vector<double*> blocks;
  if (!theta.empty()) blocks.push_back(theta.data());
  if (!lin.empty()) blocks.push_back(lin.data());
  const std::vector<double> fixed_motion =
      theta.empty() ? model.motion({}, {}) : std::vector<double>{};
  for (std::size_t o = 0; o < n_obs; ++o) {
    auto* cost = new StretchCost(cache, model, o, theta.size(), lin.size());
    if (theta.empty()) cost->fixed_motion_ = fixed_motion[o];
    problem.AddResidualBlock(cost, new ceres::HuberLoss(options.huber_sigma), blocks);
  }
  if (!theta.empty()) {
    // A weak prior at the base profile's values (a factor of 1 +- 0.5, the ratio +- 0.5): where
    // the logs barely tell a rate or an acceleration, it stays near the data sheet's instead of
    // running to a bound to soak up what other keys leave.
    Eigen::MatrixXd a =
        Eigen::MatrixXd::Identity(Eigen::Index(theta.size()), Eigen::Index(theta.size())) /
        options.prior_sigma;
    Eigen::VectorXd b(Eigen::Index(theta.size()));
    for (std::size_t j = 0; j < theta.size(); ++j)
      b[Eigen::Index(j)] = fitted_plan[j].initial;
    problem.AddResidualBlock(new ceres::NormalPrior(a, b), nullptr, theta.data());
  }
  for (std::size_t j = 0; j < theta.size(); ++j) {
    problem.SetParameterLowerBound(theta.data(), int(j), fitted_plan[j].lower);
    problem.SetParameterUpperBound(theta.data(), int(j), fitted_plan[j].upper);
  }
  if (!lin.empty()) {
    std::vector<int> constant;
    for (std::size_t k = 0; k < lin.size(); ++k) {
      if (std::find(fitted_linear.begin(), fitted_linear.end(), k) == fitted_linear.end())
        constant.push_back(int(k));
      else {
        problem.SetParameterLowerBound(lin.data(), int(k), 0);
        problem.SetParameterUpperBound(lin.data(), int(k), 600);
      }
    }
    if (constant.size() == lin.size())
      problem.SetParameterBlockConstant(lin.data());
    else if (!constant.empty())
      problem.SetManifold(lin.data(), new ceres::SubsetManifold(int(lin.size()), constant));
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = 1e-7;
  solver.parameter_tolerance = 1e-6;
  solver.logging_type = ceres::SILENT;
  solver.num_threads = 1; // the cache is shared: one residual at a time
  ceres::Solver::Summary summary;
  if (!theta.empty() || !fitted_linear.empty()) ceres::Solve(solver, &problem, &summary);
  fit.converged =
      summary.termination_type == ceres::CONVERGENCE || (theta.empty() && fitted_linear.empty());
  if (summary.termination_type == ceres::FAILURE) fit.message = summary.message;

  // Uncertainties: the covariance of the fitted parameters, scaled by the residuals' variance.
  std::size_t n_fitted = theta.size() + fitted_linear.size();
  std::vector<double> residual_s; // predicted - measured, per observation, as fitted
  std::vector<double> se_theta(theta.size(), NAN), se_lin(lin.size(), NAN);
  {
    double sse = 0;
    const std::vector<double> m = theta.empty() ? fixed_motion : model.motion(fitted_plan, theta);
    double sse_s = 0;
    residual_s.resize(n_obs);
    for (std::size_t o = 0; o < n_obs; ++o) {
      double p = m[o];
      for (std::size_t k = 0; k < lin.size(); ++k)
        p += lin[k] * model.count(o, k);
      const double d = residual_s[o] = p - observations[o].measured_s;
      const double r = d / observations[o].sigma_s;
      sse += r * r;
      sse_s += d * d;
    }
    fit.rms_after_s = std::sqrt(sse_s / double(n_obs));
    const double dof = n_obs > n_fitted ? double(n_obs - n_fitted) : 1.0;
    const double scale = std::sqrt(sse / dof);
    if (n_fitted > 0) {
      ceres::Covariance::Options co;
      co.algorithm_type = ceres::DENSE_SVD;
      co.null_space_rank = -1;
      ceres::Covariance covariance(co);
      std::vector<std::pair<const double*, const double*>> pairs;
      for (double* b : blocks)
        if (!problem.IsParameterBlockConstant(b)) pairs.emplace_back(b, b);
      if (covariance.Compute(pairs, &problem)) {
        if (!theta.empty()) {
          std::vector<double> c(theta.size() * theta.size());
          covariance.GetCovarianceBlockInTangentSpace(theta.data(), theta.data(), c.data());
          for (std::size_t j = 0; j < theta.size(); ++j)
            se_theta[j] = std::sqrt(std::max(0.0, c[j * theta.size() + j])) * scale;
        }
        if (!fitted_linear.empty()) {
          const std::size_t n = fitted_linear.size();
          std::vector<double> c(n * n);
          covariance.GetCovarianceBlockInTangentSpace(lin.data(), lin.data(), c.data());
          // The tangent space holds the fitted coordinates in order.
          std::vector<std::size_t> order = fitted_linear;
          std::sort(order.begin(), order.end());
          for (std::size_t i = 0; i < n; ++i)
            se_lin[order[i]] = std::sqrt(std::max(0.0, c[i * n + i])) * scale;
        }
      } else {
        fit.message += (fit.message.empty() ? "" : "; ") +
                       std::string("the uncertainties could not be computed");
      }
    }
  }

  for (std::string& note : timing_detail::run_disagreements(model, residual_s, lin, fitted_linear))
    fit.notes.push_back(std::move(note));

  // Results.
  char data[160];
  std::snprintf(data, sizeof data, "%zu stretches of %zu runs", n_obs, fit.runs);
  for (std::size_t j = 0; j < fitted_plan.size(); ++j)
    for (TimingKey k : fitted_plan[j].keys) {
      FittedTimingKey& f = entry(k);
      if (k == TimingKey::ArcAccel && !arcs_held(model, fitted_plan, theta, j)) {
        f.why = "no arc in these logs ran slower than the axes' acceleration allows";
        continue;
      }
      f.fitted = true;
      f.value = fitted_plan[j].factor ? f.base * theta[j] : theta[j];
      f.std_error = fitted_plan[j].factor ? f.base * se_theta[j] : se_theta[j];
      const bool at_bound = std::abs(theta[j] - fitted_plan[j].lower) < 1e-6 ||
                            std::abs(theta[j] - fitted_plan[j].upper) < 1e-6;
      f.why = std::string(at_bound ? "at the bound of its range (the logs push it further: it "
                                     "stands in for time the model does not have), "
                                   : "") +
              "fitted from " + data +
              (fitted_plan[j].keys.size() > 1 ? " (" + fitted_plan[j].label + ")" : "");
      set_timing_key(fit.machine, k, f.value);
    }
  for (std::size_t k : fitted_linear) {
    FittedTimingKey& f = entry(linear[k]);
    if (linear[k] == TimingKey::SpindleRamp) {
      // Fitted with the path waiting for the spindle: a wait of (nearly) nothing is a control
      // that does not wait, and the base's ramp (its energy) stays.
      if (lin[k] < 0.02) {
        f.why = "the control does not wait for the spindle (fitted wait " +
                std::to_string(lin[k]).substr(0, 5) + " s per 1000 rpm): as in the base";
        continue;
      }
      fit.spindle_waits = true;
      fit.machine.kinematics.spindle_waits = true;
    }
    f.fitted = true;
    f.value = lin[k];
    f.std_error = se_lin[k];
    char text[200];
    std::snprintf(text, sizeof text, "fitted from %zu logged stretches where it falls (of %s)",
                  f.evidence, data);
    f.why = text;
    set_timing_key(fit.machine, linear[k], f.value);
  }
  return fit;
}

} // namespace ncjoule
