// Fits from steady-state tables: the spindle, axis-motion and cutting lines of Pavanaskar's
// model, and Zhou's power and SEC models (all coefficients >= 0).
#include <algorithm>
#include <cmath>

#include "fit_engine.hpp"

namespace ncjoule {
namespace {

using PP = PowerParameter;

constexpr double kWattsPerKilowatt = 1000.0;

// A typical magnitude for the solver's scaling: the start value, or a fallback when it is 0.
double scale_of(double value, double fallback) {
  return std::abs(value) > 0 ? std::abs(value) : fallback;
}

fit::Parameter parameter(PP id, double initial, double fallback_scale,
                         double lower = -fit::kInfinity) {
  fit::Parameter p;
  p.id = id;
  p.initial = initial;
  p.scale = scale_of(initial, fallback_scale);
  p.lower = lower;
  return p;
}

// How many different values `values` holds (exactly equal ones counted once).
std::size_t distinct(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return std::size_t(std::unique(values.begin(), values.end()) - values.begin());
}

// A refusal when `rows` readings, with `spread` different values of what the slope is taken
// along, cannot determine `constants` constants with a standard error: one row more than the
// constants, and two values at least for a slope.
std::string too_little(std::size_t rows, std::size_t constants, std::size_t spread,
                       const std::string& along) {
  if (rows < constants + 1)
    return std::to_string(rows) + " usable row" + (rows == 1 ? "" : "s") + ": " +
           std::to_string(constants) + " constants need " + std::to_string(constants + 1) +
           " at least (one more than the constants, for an error estimate)";
  if (spread < 2)
    return "every row has the same " + along + ": a slope needs readings at two " + along +
           "s at least";
  return {};
}

FitReport refused(const std::string& what, std::size_t points, std::string why) {
  FitReport report;
  report.what = what;
  report.points = points;
  report.refused = std::move(why);
  return report;
}

// KA + KB * x fitted to y: starting values from ordinary least squares, then Ceres.
FitReport fit_line(PP ka, PP kb, const std::vector<std::pair<double, double>>& xy,
                   const std::string& what, const std::string& along) {
  std::vector<double> xs;
  for (const auto& [x, y] : xy)
    xs.push_back(x);
  if (std::string why = too_little(xy.size(), 2, distinct(xs), along); !why.empty())
    return refused(what, xy.size(), why);
  fit::Problem problem;
  problem.parameters = {parameter(ka, 0, 1), parameter(kb, 0, 1)};
  for (const auto& [x, y] : xy)
    problem.observations.push_back({{1.0, x}, 0, 0, y});
  std::vector<double> values(2, 0.0);
  fit::linear_least_squares(problem, values);
  problem.parameters[0] = parameter(ka, values[0], 1);
  problem.parameters[1] = parameter(kb, values[1], 1e-3);
  return fit::solve(problem, what);
}

// The spindle's no-load power as the model draws it (one home for the formula).
double spindle_power(const PowerConstants& k, double rpm) {
  PowerConstants pavanaskar = k;
  pavanaskar.model = PowerModel::Pavanaskar;
  OperatingPoint op;
  op.spindle_on = rpm > 0 ? 1.0 : 0.0;
  op.spindle_rpm = rpm;
  return component_power_w(pavanaskar, op)[static_cast<std::size_t>(PowerComponent::Spindle)];
}

// For a model linear in all parameters but a power law's exponent: the exponent on a grid, the
// others by non-negative least squares at each grid value. Returns the starting values.
std::vector<double> scan_exponent(const fit::Problem& full, double lo, double hi, double step) {
  const auto& pl = *full.power_law;
  fit::Problem linear = full;
  linear.power_law.reset();
  linear.parameters[pl.exponent].held = true;
  std::vector<double> best;
  double best_sse = std::numeric_limits<double>::infinity();
  for (double e = lo; e <= hi + 1e-12; e += step) {
    for (std::size_t i = 0; i < full.observations.size(); ++i) {
      const auto& o = full.observations[i];
      linear.observations[i].x[pl.coefficient] =
          o.power_weight != 0.0 ? o.power_weight * std::pow(o.power_base, e) : 0.0;
    }
    std::vector<double> values(full.parameters.size(), 0.0);
    const double sse = fit::nonnegative_least_squares(linear, values);
    if (!(sse < best_sse)) continue;
    best_sse = sse;
    values[pl.exponent] = e;
    best = values;
  }
  if (best.empty()) best.assign(full.parameters.size(), 0.0);
  return best;
}

// Scans, then polishes the power-law model with Ceres keeping every coefficient >= 0.
FitReport fit_power_law_model(fit::Problem problem, const std::vector<double>& fallback_scales,
                              double exponent_max, const std::string& what) {
  const std::vector<double> start = scan_exponent(problem, 0.0, exponent_max, 0.005);
  for (std::size_t j = 0; j < problem.parameters.size(); ++j)
    problem.parameters[j] = parameter(problem.parameters[j].id, start[j], fallback_scales[j], 0.0);
  return fit::solve(problem, what);
}

} // namespace

const FittedConstant* FitReport::find(PowerParameter p) const {
  for (const FittedConstant& c : constants)
    if (c.parameter == p) return &c;
  return nullptr;
}

void apply_fit(PowerConstants& constants, const FitReport& fit) {
  if (!fit.refused.empty()) return;
  for (const FittedConstant& c : fit.constants)
    if (!c.held) set_parameter(constants, c.parameter, c.value);
}

FitReport fit_spindle(const std::vector<SteadyStateReading>& readings, double baseline_w) {
  std::vector<std::pair<double, double>> xy;
  for (const auto& r : readings)
    xy.emplace_back(r.rpm, r.power_w - baseline_w);
  FitReport fit = fit_line(PP::SpindleKA, PP::SpindleKB, xy, "spindle", "spindle speed");
  if (!fit.refused.empty()) return fit;
  // A table's straight line replaces the base profile's spindle curve whole: its n^2 term too.
  fit.constants.push_back({PP::SpindleKC, 0.0, 0.0, false});
  return fit;
}

FitReport fit_axis_move(const std::vector<SteadyStateReading>& readings, Axis axis,
                        const PowerConstants& known) {
  const int i = static_cast<int>(axis);
  std::vector<std::pair<double, double>> xy;
  for (const auto& r : readings)
    xy.emplace_back(r.feed_mm_s, r.power_w - known.pavanaskar.tare_w - spindle_power(known, r.rpm));
  constexpr PP ka[3] = {PP::MoveKAX, PP::MoveKAY, PP::MoveKAZ};
  constexpr PP kb[3] = {PP::MoveKBX, PP::MoveKBY, PP::MoveKBZ};
  return fit_line(ka[i], kb[i], xy, std::string("axis ") + "xyz"[i] + " motion", "feed");
}

FitReport fit_axis_cut(const std::vector<SteadyStateReading>& readings, Axis axis,
                       const PowerConstants& known) {
  const int i = static_cast<int>(axis);
  const auto& pv = known.pavanaskar;
  // A cut state holds its axis feeding: the model draws the cut line in place of the move line
  // while material is removed (docs/models.md), so the move is not taken off the reading.
  std::vector<std::pair<double, double>> xy;
  for (const auto& r : readings)
    xy.emplace_back(r.mrr_mm3_s, r.power_w - pv.tare_w - spindle_power(known, r.rpm));
  constexpr PP ka[3] = {PP::CutKAX, PP::CutKAY, PP::CutKAZ};
  constexpr PP kb[3] = {PP::CutKBX, PP::CutKBY, PP::CutKBZ};
  return fit_line(ka[i], kb[i], xy, std::string("axis ") + "xyz"[i] + " cutting", "removal rate");
}

FitReport fit_zhou_power(const std::vector<SteadyStateReading>& readings) {
  // Parameters c1, c2, c3, c4; y in kW, as the constants are published.
  fit::Problem problem;
  problem.parameters = {parameter(PP::ZhouC1, 0, 1), parameter(PP::ZhouC2, 0, 1e-4),
                        parameter(PP::ZhouC3, 0, 1e-6), parameter(PP::ZhouC4, 0, 1)};
  problem.power_law = fit::PowerLawTerm{2, 3};
  std::vector<double> cutting_rpm;
  for (const auto& r : readings) {
    const double weight = r.rpm > 0 ? r.mrr_mm3_s : 0.0;
    problem.observations.push_back(
        {{1.0, r.rpm, 0, 0}, weight, r.rpm, r.power_w / kWattsPerKilowatt});
    if (weight > 0) cutting_rpm.push_back(r.rpm);
  }
  // c4, the speed exponent of the cutting term, needs cuts at two speeds.
  if (std::string why = too_little(readings.size(), 4, distinct(cutting_rpm),
                                   "spindle speed among the cutting rows (MRR > 0)");
      !why.empty())
    return refused("Zhou power (kW)", readings.size(), why);
  return fit_power_law_model(problem, {1, 1e-4, 1e-6, 1}, 3.0, "Zhou power (kW)");
}

FitReport fit_zhou_sec(const std::vector<SteadyStateReading>& readings) {
  // SEC = d1 * n^d2 + d3 * n / MRR + d4 / MRR; parameters d1, d2, d3, d4.
  fit::Problem problem;
  problem.parameters = {parameter(PP::ZhouD1, 0, 1e-5), parameter(PP::ZhouD2, 0, 1),
                        parameter(PP::ZhouD3, 0, 0.1), parameter(PP::ZhouD4, 0, 100)};
  problem.power_law = fit::PowerLawTerm{0, 1};
  for (const auto& r : readings) {
    if (!(r.mrr_mm3_s > 0) || !(r.rpm > 0)) continue;
    problem.observations.push_back(
        {{0, 0, r.rpm / r.mrr_mm3_s, 1.0 / r.mrr_mm3_s}, 1.0, r.rpm, r.power_w / r.mrr_mm3_s});
  }
  std::vector<double> rpm;
  for (const auto& o : problem.observations)
    rpm.push_back(o.power_base);
  if (std::string why = too_little(problem.observations.size(), 4, distinct(rpm),
                                   "spindle speed among the cutting rows (MRR > 0)");
      !why.empty())
    return refused("Zhou SEC (J/mm^3)", problem.observations.size(), why);
  return fit_power_law_model(problem, {1e-5, 1, 0.1, 100}, 3.0, "Zhou SEC (J/mm^3)");
}

void set_zhou_fitted_ranges(ZhouConstants& zhou, const std::vector<SteadyStateReading>& readings) {
  bool any = false;
  for (const auto& r : readings) {
    if (!(r.mrr_mm3_s > 0) || !(r.rpm > 0)) continue;
    if (!any) {
      zhou.fitted_rpm_min = zhou.fitted_rpm_max = r.rpm;
      zhou.fitted_mrr_min_mm3_s = zhou.fitted_mrr_max_mm3_s = r.mrr_mm3_s;
      any = true;
    }
    zhou.fitted_rpm_min = std::min(zhou.fitted_rpm_min, r.rpm);
    zhou.fitted_rpm_max = std::max(zhou.fitted_rpm_max, r.rpm);
    zhou.fitted_mrr_min_mm3_s = std::min(zhou.fitted_mrr_min_mm3_s, r.mrr_mm3_s);
    zhou.fitted_mrr_max_mm3_s = std::max(zhou.fitted_mrr_max_mm3_s, r.mrr_mm3_s);
  }
}

} // namespace ncjoule
