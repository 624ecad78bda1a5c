// Steady-state readings and power logs from numeric CSV tables: finds the columns by name and
// converts their units to ncjoule's internal ones.
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "ncjoule/calibrate.hpp"

namespace ncjoule {
namespace {

struct ColumnChoice {
  std::string_view name;
  double factor; // to internal units
};

// What a reading can physically be, in internal units (a slip such as 1e308 or 1e-300 in a cell
// is refused at the cell, before a fit overflows on it): spindle speeds to 200,000 rpm, feeds to
// 2,000 mm/s (120 m/min), removal rates to 1e6 mm^3/s, powers to 1 MW (as a profile's), times
// to 1e10 s (a Unix time stamp fits).
struct Range {
  double highest;
  std::string_view unit; // for the message, in internal units
};
constexpr Range kRpmRange{2e5, "rpm"};
constexpr Range kFeedRange{2000, "mm/s"};
constexpr Range kMrrRange{1e6, "mm^3/s"};
constexpr Range kPowerRange{1e6, "W"};
constexpr Range kTimeRange{1e10, "s"};

std::string format_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// The cell's value in internal units when it lies within [lowest, range.highest]; otherwise an
// error at the cell and nullopt.
std::optional<double> checked(const NumericCsv& csv, std::size_t row, std::size_t column,
                              double factor, double lowest, const Range& range,
                              std::vector<Diagnostic>& diagnostics) {
  const double v = csv.rows[row][column] * factor;
  if (v >= lowest && v <= range.highest) return v;
  const std::string what = !std::isfinite(v) ? "is not a finite number"
                           : v < lowest      ? "must not be negative"
                                             : "is beyond what a machine can be";
  diagnostics.push_back(
      {Severity::Error, csv.path, csv.row_lines[row], csv.cell_columns[row][column],
       "column '" + csv.columns[column] + "' " + what + " (" + format_number(v) + " " +
           std::string(range.unit) + "; from " + format_number(lowest) + " to " +
           format_number(range.highest) + " " + std::string(range.unit) + ")"});
  return std::nullopt;
}

struct FoundColumn {
  std::size_t index = 0;
  double factor = 1;
};

std::string names_of(const std::vector<ColumnChoice>& choices) {
  std::string out;
  for (const auto& c : choices)
    out += (out.empty() ? "" : " or ") + std::string(c.name);
  return out;
}

std::optional<FoundColumn> find_column(const NumericCsv& csv,
                                       const std::vector<ColumnChoice>& choices) {
  for (const auto& c : choices)
    if (auto i = csv.column(c.name)) return FoundColumn{*i, c.factor};
  return std::nullopt;
}

const std::vector<ColumnChoice> kRpm{{"rpm", 1}, {"spindle_rpm", 1}};
const std::vector<ColumnChoice> kFeed{{"feed_mm_min", 1.0 / 60},
                                      {"feed_mm_s", 1},
                                      {"feed_ipm", 25.4 / 60},
                                      {"feed_in_min", 25.4 / 60}};
const std::vector<ColumnChoice> kMrr{
    {"mrr_mm3_s", 1}, {"mrr_mm3_min", 1.0 / 60}, {"mrr_cm3_min", 1000.0 / 60}};
const std::vector<ColumnChoice> kPower{{"power_w", 1}, {"power_kw", 1000}};
const std::vector<ColumnChoice> kTime{{"time_s", 1}, {"t_s", 1}};

} // namespace

std::vector<SteadyStateReading> readings_from_csv(const NumericCsv& csv, unsigned required,
                                                  std::vector<Diagnostic>& diagnostics) {
  std::vector<SteadyStateReading> readings;
  bool missing = false;
  auto need = [&](const std::vector<ColumnChoice>& choices, bool needed) {
    auto found = find_column(csv, choices);
    if (!found && needed) {
      diagnostics.push_back({Severity::Error, csv.path, 1, 0,
                             "missing column " + names_of(choices) + " in the header"});
      missing = true;
    }
    return found;
  };
  const auto rpm = need(kRpm, required & kFieldRpm);
  const auto feed = need(kFeed, required & kFieldFeed);
  const auto mrr = need(kMrr, required & kFieldMrr);
  const auto power = need(kPower, true);
  if (missing) return readings;
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    const int line = csv.row_lines[r];
    bool ok = true;
    auto value = [&](const std::optional<FoundColumn>& c, const Range& range) {
      if (!c) return 0.0;
      const auto v = checked(csv, r, c->index, c->factor, 0, range, diagnostics);
      ok = ok && v.has_value();
      return v.value_or(0.0);
    };
    SteadyStateReading reading;
    reading.rpm = value(rpm, kRpmRange);
    reading.feed_mm_s = value(feed, kFeedRange);
    reading.mrr_mm3_s = value(mrr, kMrrRange);
    reading.power_w = value(power, kPowerRange);
    reading.line = line;
    if (ok) readings.push_back(reading);
  }
  if (readings.empty()) diagnostics.push_back({Severity::Error, csv.path, 0, 0, "no usable rows"});
  return readings;
}

std::optional<PowerLog> power_log_from_csv(const NumericCsv& csv,
                                           std::vector<Diagnostic>& diagnostics) {
  const auto time = find_column(csv, kTime);
  const auto power = find_column(csv, kPower);
  if (!time || !power) {
    diagnostics.push_back({Severity::Error, csv.path, 1, 0,
                           std::string("missing column ") +
                               (!time ? names_of(kTime) : names_of(kPower)) + " in the header"});
    return std::nullopt;
  }
  PowerLog log;
  log.path = csv.path;
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    // A meter's power is never negative: a negative cell is a slip, or the wrong column.
    const auto time_s =
        checked(csv, r, time->index, time->factor, -kTimeRange.highest, kTimeRange, diagnostics);
    const auto power_w = checked(csv, r, power->index, power->factor, 0, kPowerRange, diagnostics);
    if (!time_s || !power_w) continue;
    const double t = *time_s, p = *power_w;
    if (!log.t_s.empty() && !(t > log.t_s.back())) {
      diagnostics.push_back({Severity::Error, csv.path, csv.row_lines[r],
                             csv.cell_columns[r][time->index],
                             "time " + std::to_string(t) + " s does not increase (previous row: " +
                                 std::to_string(log.t_s.back()) + " s); row skipped"});
      continue;
    }
    log.t_s.push_back(t);
    log.power_w.push_back(p);
  }
  if (log.t_s.size() < 2) {
    diagnostics.push_back({Severity::Error, csv.path, 0, 0, "a power log needs at least 2 rows"});
    return std::nullopt;
  }
  return log;
}

std::optional<PowerLog> read_power_log(const std::string& path,
                                       std::vector<Diagnostic>& diagnostics) {
  auto csv = read_numeric_csv(path, diagnostics);
  if (!csv) return std::nullopt;
  return power_log_from_csv(*csv, diagnostics);
}

} // namespace ncjoule
