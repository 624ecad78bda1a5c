// ncjoule calibration and measurement: fitting a machine's power constants (Ceres) from
// steady-state tables and from a time-stamped power log of a known program, measuring the
// energy of a logged run, and writing the fitted constants into a profile.
//
// Units as everywhere in ncjoule: W, J, s, mm/s, mm^3/s, rpm. CSV columns say their unit in
// their name (power_w or power_kw, feed_mm_min, feed_mm_s or feed_ipm, ...); see docs/models.md.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/energy.hpp"
#include "ncjoule/gcode.hpp"
#include "ncjoule/machine.hpp"

namespace ncjoule {

// ---------------------------------------------------------------------------------------------
// CSV input. The first non-comment line is the header; '#' starts a comment line; fields are
// separated by commas (a ';' separator is detected). Every cell must be a number: problems are
// diagnostics with file, line, column and the reason, and the rows that parsed are kept.
// ---------------------------------------------------------------------------------------------

struct NumericCsv {
  std::string path;
  std::vector<std::string> columns; // header names, trimmed and lower-cased
  std::vector<std::vector<double>> rows;
  std::vector<int> row_lines;                 // 1-based line of every row
  std::vector<std::vector<int>> cell_columns; // 1-based character column of every cell
  std::optional<std::size_t> column(std::string_view name) const;
};

std::optional<NumericCsv> parse_numeric_csv(std::string path, std::string_view text,
                                            std::vector<Diagnostic>& diagnostics);
std::optional<NumericCsv> read_numeric_csv(const std::string& path,
                                           std::vector<Diagnostic>& diagnostics);

// One steady-state reading of whole-machine power.
struct SteadyStateReading {
  double rpm = 0;
  double feed_mm_s = 0;
  double mrr_mm3_s = 0;
  double power_w = 0;
  int line = 0; // 1-based line in the CSV
};

// Which quantities a table must have besides power.
enum ReadingField : unsigned { kFieldRpm = 1, kFieldFeed = 2, kFieldMrr = 4 };

// Accepted columns: rpm | spindle_rpm; feed_mm_min | feed_mm_s | feed_ipm; mrr_mm3_s |
// mrr_mm3_min; power_w | power_kw. Optional fields that are absent read as 0.
std::vector<SteadyStateReading> readings_from_csv(const NumericCsv& csv, unsigned required,
                                                  std::vector<Diagnostic>& diagnostics);

// ---------------------------------------------------------------------------------------------
// Fits. Every fit reports each constant with its standard error (ceres::Covariance, scaled by
// the residual variance), the fit's RMSE = sqrt(SSE / degrees of freedom), and R^2.
// ---------------------------------------------------------------------------------------------

struct FittedConstant {
  PowerParameter parameter = PowerParameter::Tare;
  double value = 0;
  double std_error = 0; // NaN when the data cannot determine it
  bool held = false;    // not fitted: kept at its initial value
};

struct FitReport {
  std::string what; // e.g. "spindle (spindle.csv)"
  std::vector<FittedConstant> constants;
  std::size_t points = 0;
  std::size_t dof = 0; // points - fitted constants
  double sse = 0;      // W^2 (J^2/mm^6 for the SEC model)
  double rmse = 0;
  double r_squared = 0;
  bool converged = false;
  std::string message; // solver or covariance trouble, empty when all went well
  // Why the data cannot be fitted at all (too few rows, one value only where a slope needs two,
  // numbers a solver would overflow on); nothing is fitted then and apply_fit changes nothing.
  std::string refused;

  const FittedConstant* find(PowerParameter p) const;
};

// Writes the fitted (not held) values into the constants.
void apply_fit(PowerConstants& constants, const FitReport& fit);

// Spindle at several speeds, nothing else running: P - baseline = KA + KB * n. The baseline
// is the machine's starting state (Pavanaskar: tare with the spindle off).
FitReport fit_spindle(const std::vector<SteadyStateReading>& readings, double baseline_w);
// One axis moving at several feeds: P - (tare + spindle at the row's rpm) = KA + KB * F.
FitReport fit_axis_move(const std::vector<SteadyStateReading>& readings, Axis axis,
                        const PowerConstants& known);
// Cuts along one axis: P - (tare + spindle + that axis's move terms) = KA_cut + KB_cut * MRR.
FitReport fit_axis_cut(const std::vector<SteadyStateReading>& readings, Axis axis,
                       const PowerConstants& known);
// Zhou: whole-machine P = c1 + c2*n + c3*n^c4*MRR (kW), all coefficients >= 0.
FitReport fit_zhou_power(const std::vector<SteadyStateReading>& readings);
// Zhou's SEC model on SEC = P / MRR of the same readings (rows with MRR > 0), all >= 0.
FitReport fit_zhou_sec(const std::vector<SteadyStateReading>& readings);
// The spindle speeds and removal rates the Zhou fit saw (cutting rows only), so estimates
// outside them are warned about as extrapolation.
void set_zhou_fitted_ranges(ZhouConstants& zhou, const std::vector<SteadyStateReading>& readings);

// ---------------------------------------------------------------------------------------------
// Power logs
// ---------------------------------------------------------------------------------------------

struct PowerLog {
  std::string path;
  std::vector<double> t_s; // increasing
  std::vector<double> power_w;
};

// Columns time_s (or t_s) and power_w (or power_kw); times must increase.
std::optional<PowerLog> power_log_from_csv(const NumericCsv& csv,
                                           std::vector<Diagnostic>& diagnostics);
std::optional<PowerLog> read_power_log(const std::string& path,
                                       std::vector<Diagnostic>& diagnostics);

enum class RobustLoss { None, Huber, Cauchy };

struct LogFitOptions {
  double max_offset_s = 60; // search the offset in [-max, +max]
  RobustLoss loss = RobustLoss::Huber;
  double loss_scale_w = 0;          // 0: 1.5 x the robust spread (MAD) of a first least-squares fit
  bool fit_zhou_exponent = false;   // c4 rarely varies enough in a log; held unless asked
  std::vector<PowerParameter> hold; // constants to keep at their initial values
};

struct LogFitResult {
  // Program time = log time - offset_s: the program started offset_s after the log did.
  double offset_s = 0;
  PowerConstants constants; // the initial constants with the fitted values written in
  FitReport report;
  std::vector<std::string> notes; // constants held because the log cannot determine them, ...
};

// Fits the model's constants to the whole log. The offset comes first, from the correlation of
// the log with the power the initial constants predict, refined by least squares over the
// offset; then every constant the log can determine is fitted with the robust loss.
LogFitResult fit_power_log(const PowerLog& log, const std::vector<OperatingSegment>& trace,
                           const PowerConstants& initial, const LogFitOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Measured energy (Mora, Pavanaskar): trapezoidal integral of a log, optionally minus idle.
// ---------------------------------------------------------------------------------------------

struct MeasureOptions {
  std::optional<double> idle_w;            // subtract this constant idle power
  std::optional<double> idle_from_first_s; // or the mean power of the log's first seconds
};

struct MeasuredEnergy {
  std::size_t samples = 0;
  double duration_s = 0;
  double energy_j = 0; // gross
  double idle_w = 0;   // what was subtracted (0 when nothing)
  double net_energy_j = 0;
  double mean_power_w = 0;
  double peak_power_w = 0;
};

MeasuredEnergy measure_energy(const PowerLog& log, const MeasureOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Profiles: the [power] section in the layout core/machine reads (docs/machine-profiles.md).
// ---------------------------------------------------------------------------------------------

// The [power] tables as TOML text. `notes` gives the source of a constant, written as a comment
// beside it; `source` becomes the section's source key.
std::string power_section_toml(const PowerConstants& constants,
                               const std::map<PowerParameter, std::string>& notes = {},
                               const std::string& source = "");
// A whole profile: the base profile's other tables (TOML text read from `base_path`), `name`
// when not empty, and the [power] section of `constants`. nullopt, with an error at the line and
// column in `diagnostics`, when the base does not parse or the profile made from it would not
// load. Without a base (empty text), the [power] tables alone.
std::optional<std::string> profile_with_power(std::string_view base_toml,
                                              const std::string& base_path, const std::string& name,
                                              const PowerConstants& constants,
                                              const std::map<PowerParameter, std::string>& notes,
                                              const std::string& power_source,
                                              std::vector<Diagnostic>& diagnostics);

} // namespace ncjoule
