// Internal: one least-squares engine (Ceres) for every calibration fit. A model is linear in its
// parameters except for at most one power-law term coef * weight * base^exponent, which covers
// Zhou's c3*n^c4*MRR and the SEC model's d1*n^d2.
#pragma once

#include <limits>
#include <optional>
#include <vector>

#include "ncjoule/calibrate.hpp"

namespace ncjoule::fit {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Parameter {
  PowerParameter id = PowerParameter::Tare;
  double initial = 0;
  double scale = 1; // typical magnitude: the solver works on value / scale
  double lower = -kInfinity;
  double upper = kInfinity;
  bool held = false;
};

// Index (into the parameter list) of the coefficient and the exponent of the power-law term.
struct PowerLawTerm {
  std::size_t coefficient = 0;
  std::size_t exponent = 0;
};

struct Observation {
  std::vector<double> x; // one per parameter (the power-law's two entries unused)
  double power_weight = 0;
  double power_base = 0; // must be > 0 where power_weight != 0
  double y = 0;
};

struct Problem {
  std::vector<Parameter> parameters;
  std::optional<PowerLawTerm> power_law;
  std::vector<Observation> observations;
  RobustLoss loss = RobustLoss::None;
  double loss_scale = 1;
  int max_iterations = 200;
};

// Whether every number of the problem is finite and within 1e100 in size (a power law's base
// above 0): what the solvers below can take. solve refuses the rest, the least-squares helpers
// return NaN for it and leave the values alone.
bool solvable(const Problem& problem);

// Solves, then reports every parameter with its standard error.
FitReport solve(const Problem& problem, const std::string& what);

// Model value of one observation at the given parameter values.
double predict(const Problem& problem, const std::vector<double>& values, const Observation& o);

// Ordinary least squares on the linear parameters only (the power-law term evaluated at the
// given values is moved to the left-hand side), with columns that the data cannot determine
// left at their given values. Returns the sum of squared residuals; writes the solution into
// `values`. Used for starting values and for the offset search of log fits.
double linear_least_squares(const Problem& problem, std::vector<double>& values,
                            std::vector<bool>* determined = nullptr);

// Least squares with all linear parameters >= 0 (exhaustive active sets: few parameters only).
double nonnegative_least_squares(const Problem& problem, std::vector<double>& values);

} // namespace ncjoule::fit
