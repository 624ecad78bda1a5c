// The Ceres least-squares engine behind every calibration fit, and the small linear solvers
// that give it starting values.
#include "fit_engine.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <ceres/ceres.h>
#include <ceres/covariance.h>
#include <cmath>
#include <memory>

namespace ncjoule::fit {
namespace {

// Residual of one observation; parameters arrive divided by their scale.
struct ResidualFunctor {
  const Problem* problem;
  const Observation* o;

  template <class T> bool operator()(T const* const* q, T* residual) const {
    const auto& ps = problem->parameters;
    T sum(0.0);
    for (std::size_t j = 0; j < ps.size(); ++j)
      if (o->x[j] != 0.0) sum += T(ps[j].scale * o->x[j]) * q[j][0];
    if (problem->power_law && o->power_weight != 0.0) {
      const auto& pl = *problem->power_law;
      const T c = T(ps[pl.coefficient].scale) * q[pl.coefficient][0];
      const T e = T(ps[pl.exponent].scale) * q[pl.exponent][0];
      using std::exp;
      sum += c * T(o->power_weight) * exp(e * T(std::log(o->power_base)));
    }
    residual[0] = sum - T(o->y);
    return true;
  }
};

// Derivative of the robust loss at squared residual s: the weight an observation keeps.
double loss_weight(RobustLoss loss, double scale, double s) {
  switch (loss) {
  case RobustLoss::None:
    return 1.0;
  case RobustLoss::Huber:
    return s <= scale * scale ? 1.0 : scale / std::sqrt(s);
  case RobustLoss::Cauchy:
    return 1.0 / (1.0 + s / (scale * scale));
  }
  return 1.0;
}

ceres::LossFunction* make_loss(RobustLoss loss, double scale) {
  switch (loss) {
  case RobustLoss::None:
    return nullptr;
  case RobustLoss::Huber:
    return new ceres::HuberLoss(scale);
  case RobustLoss::Cauchy:
    return new ceres::CauchyLoss(scale);
  }
  return nullptr;
}

// Parameters no observation depends on cannot be fitted: they are held.
std::vector<bool> unused_parameters(const Problem& p) {
  std::vector<bool> unused(p.parameters.size(), true);
  for (const Observation& o : p.observations) {
    for (std::size_t j = 0; j < p.parameters.size(); ++j)
      if (o.x[j] != 0.0) unused[j] = false;
    if (p.power_law && o.power_weight != 0.0) {
      unused[p.power_law->coefficient] = false;
      unused[p.power_law->exponent] = false;
    }
  }
  return unused;
}

double power_law_value(const Problem& p, const std::vector<double>& v, const Observation& o) {
  if (!p.power_law || o.power_weight == 0.0) return 0.0;
  return v[p.power_law->coefficient] * o.power_weight *
         std::pow(o.power_base, v[p.power_law->exponent]);
}

bool is_power_law_parameter(const Problem& p, std::size_t j) {
  return p.power_law && (j == p.power_law->coefficient || j == p.power_law->exponent);
}

// Solves min |A x - b| over the listed columns; returns the SSE, or NaN when the subset is
// rank deficient.
double solve_columns(const Problem& p, const std::vector<std::size_t>& columns,
                     std::vector<double>& values) {
  const std::size_t n = p.observations.size();
  Eigen::MatrixXd a(n, columns.size());
  Eigen::VectorXd b(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Observation& o = p.observations[i];
    double rhs = o.y - power_law_value(p, values, o);
    for (std::size_t j = 0; j < p.parameters.size(); ++j) {
      const bool solved = std::find(columns.begin(), columns.end(), j) != columns.end();
      if (!solved && !is_power_law_parameter(p, j)) rhs -= values[j] * o.x[j];
    }
    for (std::size_t c = 0; c < columns.size(); ++c)
      a(i, c) = o.x[columns[c]];
    b(i) = rhs;
  }
  if (!columns.empty()) {
    Eigen::VectorXd norms = a.colwise().norm();
    for (Eigen::Index c = 0; c < a.cols(); ++c)
      if (norms(c) > 0) a.col(c) /= norms(c);
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
    qr.setThreshold(1e-10);
    if (qr.rank() < a.cols()) return std::nan("");
    const Eigen::VectorXd x = qr.solve(b);
    for (std::size_t c = 0; c < columns.size(); ++c)
      values[columns[c]] = norms(static_cast<Eigen::Index>(c)) > 0 ? x(c) / norms(c) : 0.0;
  }
  double sse = 0;
  for (const Observation& o : p.observations) {
    const double r = predict(p, values, o) - o.y;
    sse += r * r;
  }
  return sse;
}

} // namespace

// Whether every number of the problem is one the solver can square and sum without overflow:
// finite, within 1e100 in size, and a power law's base above 0. Readings are checked against
// physical ranges where they are read; this keeps a caller's slip from reaching Ceres and Eigen
// (a 1e308 once ended in a crash inside Eigen's SVD under Ceres' covariance).
bool solvable(const Problem& p) {
  auto fits = [](double v) { return std::isfinite(v) && std::abs(v) <= 1e100; };
  for (const Parameter& par : p.parameters)
    if (!fits(par.initial) || !fits(par.scale) || par.scale == 0) return false;
  for (const Observation& o : p.observations) {
    if (!fits(o.y) || !fits(o.power_weight)) return false;
    for (double x : o.x)
      if (!fits(x)) return false;
    if (p.power_law && o.power_weight != 0.0 && !(o.power_base > 0 && fits(o.power_base)))
      return false;
  }
  return true;
}

double predict(const Problem& p, const std::vector<double>& v, const Observation& o) {
  double sum = power_law_value(p, v, o);
  for (std::size_t j = 0; j < p.parameters.size(); ++j)
    if (!is_power_law_parameter(p, j)) sum += v[j] * o.x[j];
  return sum;
}

double linear_least_squares(const Problem& p, std::vector<double>& values,
                            std::vector<bool>* determined) {
  if (!solvable(p)) {
    if (determined) determined->assign(p.parameters.size(), false);
    return std::nan("");
  }
  const std::size_t n = p.observations.size();
  std::vector<std::size_t> candidates;
  for (std::size_t j = 0; j < p.parameters.size(); ++j)
    if (!p.parameters[j].held && !is_power_law_parameter(p, j)) candidates.push_back(j);
  // Keep the columns a pivoted QR finds independent; the rest stay at their given values.
  Eigen::MatrixXd a(n, candidates.size());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < candidates.size(); ++c)
      a(i, c) = p.observations[i].x[candidates[c]];
  std::vector<std::size_t> independent;
  if (!candidates.empty()) {
    Eigen::VectorXd norms = a.colwise().norm();
    for (Eigen::Index c = 0; c < a.cols(); ++c)
      if (norms(c) > 0) a.col(c) /= norms(c);
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
    qr.setThreshold(1e-8);
    for (Eigen::Index r = 0; r < qr.rank(); ++r) {
      const auto c = static_cast<std::size_t>(qr.colsPermutation().indices()(r));
      if (norms(static_cast<Eigen::Index>(c)) > 0) independent.push_back(candidates[c]);
    }
  }
  if (determined) {
    determined->assign(p.parameters.size(), false);
    for (std::size_t j : independent)
      (*determined)[j] = true;
  }
  return solve_columns(p, independent, values);
}

double nonnegative_least_squares(const Problem& p, std::vector<double>& values) {
  if (!solvable(p)) return std::nan("");
  std::vector<std::size_t> free;
  for (std::size_t j = 0; j < p.parameters.size(); ++j)
    if (!p.parameters[j].held && !is_power_law_parameter(p, j)) free.push_back(j);
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> best_values = values;
  for (unsigned mask = 0; mask < (1u << free.size()); ++mask) {
    std::vector<double> trial = values;
    std::vector<std::size_t> columns;
    for (std::size_t k = 0; k < free.size(); ++k) {
      if (mask & (1u << k))
        columns.push_back(free[k]);
      else
        trial[free[k]] = 0.0;
    }
    const double sse = solve_columns(p, columns, trial);
    if (!std::isfinite(sse) || sse >= best) continue;
    bool feasible = true;
    for (std::size_t j : columns)
      feasible = feasible && trial[j] >= 0;
    if (!feasible) continue;
    best = sse;
    best_values = trial;
  }
  values = best_values;
  return best;
}

FitReport solve(const Problem& problem, const std::string& what) {
  FitReport report;
  report.what = what;
  if (!solvable(problem)) {
    report.points = problem.observations.size();
    report.refused = "a value beyond what the fit can take (not finite, or above 1e100)";
    return report;
  }
  const std::size_t np = problem.parameters.size();
  const std::vector<bool> unused = unused_parameters(problem);
  std::vector<double> q(np);
  std::vector<bool> held(np);
  for (std::size_t j = 0; j < np; ++j) {
    const Parameter& par = problem.parameters[j];
    q[j] = par.initial / par.scale;
    held[j] = par.held || unused[j];
  }
  ceres::Problem ceres_problem;
  ceres::LossFunction* loss = make_loss(problem.loss, problem.loss_scale);
  std::vector<double*> blocks(np);
  for (std::size_t j = 0; j < np; ++j)
    blocks[j] = &q[j];
  for (const Observation& o : problem.observations) {
    auto* cost = new ceres::DynamicAutoDiffCostFunction<ResidualFunctor, 8>(
        new ResidualFunctor{&problem, &o});
    for (std::size_t j = 0; j < np; ++j)
      cost->AddParameterBlock(1);
    cost->SetNumResiduals(1);
    ceres_problem.AddResidualBlock(cost, loss, blocks);
  }
  if (problem.observations.empty() && loss) delete loss;
  std::size_t free_count = 0;
  for (std::size_t j = 0; j < np; ++j) {
    const Parameter& par = problem.parameters[j];
    if (problem.observations.empty()) break;
    if (held[j]) {
      ceres_problem.SetParameterBlockConstant(&q[j]);
      continue;
    }
    ++free_count;
    if (std::isfinite(par.lower))
      ceres_problem.SetParameterLowerBound(&q[j], 0, par.lower / par.scale);
    if (std::isfinite(par.upper))
      ceres_problem.SetParameterUpperBound(&q[j], 0, par.upper / par.scale);
  }
  report.points = problem.observations.size();
  if (report.points == 0) {
    report.message = "no data";
    return report;
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = problem.max_iterations;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-12;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  if (free_count > 0) ceres::Solve(options, &ceres_problem, &summary);
  report.converged = free_count == 0 || summary.termination_type == ceres::CONVERGENCE;
  if (!report.converged) report.message = "solver: " + summary.message;

  // Statistics on the unweighted residuals.
  std::vector<double> values(np);
  for (std::size_t j = 0; j < np; ++j)
    values[j] = q[j] * problem.parameters[j].scale;
  for (double v : values)
    if (!std::isfinite(v)) {
      report.refused = "the solver ended on a value that is not finite: the data do not "
                       "describe the model";
      return report;
    }
  double mean_y = 0;
  for (const Observation& o : problem.observations)
    mean_y += o.y;
  mean_y /= static_cast<double>(report.points);
  double sst = 0, weighted_sse = 0, weight_sum = 0;
  for (const Observation& o : problem.observations) {
    const double r = predict(problem, values, o) - o.y;
    const double w = loss_weight(problem.loss, problem.loss_scale, r * r);
    report.sse += r * r;
    weighted_sse += w * r * r;
    weight_sum += w;
    sst += (o.y - mean_y) * (o.y - mean_y);
  }
  report.dof = report.points > free_count ? report.points - free_count : 0;
  report.rmse = std::sqrt(report.sse / static_cast<double>(std::max<std::size_t>(report.dof, 1)));
  report.r_squared = sst > 0 ? 1.0 - report.sse / sst : 1.0;
  const double robust_dof = weight_sum - static_cast<double>(free_count);
  const double sigma2 = robust_dof > 0 ? weighted_sse / robust_dof : 0.0;

  // Standard errors from the covariance of the free parameters.
  std::vector<double> variance(np, std::nan(""));
  if (free_count > 0) {
    ceres::Covariance::Options cov_options;
    cov_options.algorithm_type = ceres::DENSE_SVD;
    ceres::Covariance covariance(cov_options);
    std::vector<std::pair<const double*, const double*>> pairs;
    for (std::size_t j = 0; j < np; ++j)
      if (!held[j]) pairs.emplace_back(&q[j], &q[j]);
    if (covariance.Compute(pairs, &ceres_problem)) {
      for (std::size_t j = 0; j < np; ++j) {
        if (held[j]) continue;
        double v = 0;
        covariance.GetCovarianceBlock(&q[j], &q[j], &v);
        variance[j] = v;
      }
    } else {
      report.message += (report.message.empty() ? "" : "; ") +
                        std::string("the data do not determine every constant (singular "
                                    "covariance): standard errors unknown");
    }
  }
  for (std::size_t j = 0; j < np; ++j) {
    const Parameter& par = problem.parameters[j];
    FittedConstant c;
    c.parameter = par.id;
    c.value = values[j];
    c.held = held[j];
    c.std_error = held[j] ? 0.0 : std::sqrt(variance[j] * sigma2) * std::abs(par.scale);
    report.constants.push_back(c);
  }
  return report;
}

} // namespace ncjoule::fit
