// Steady-state readings and power logs from numeric CSV tables: finds the columns by name and
// converts their units to ncjoule's internal ones.
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
    const auto& row = csv.rows[r];
    const int line = csv.row_lines[r];
    bool ok = true;
    auto value = [&](const std::optional<FoundColumn>& c) {
      if (!c) return 0.0;
      const double v = row[c->index] * c->factor;
      if (v < 0) {
        diagnostics.push_back({Severity::Error, csv.path, line, csv.cell_columns[r][c->index],
                               "column '" + csv.columns[c->index] + "' must not be negative"});
        ok = false;
      }
      return v;
    };
    SteadyStateReading reading;
    reading.rpm = value(rpm);
    reading.feed_mm_s = value(feed);
    reading.mrr_mm3_s = value(mrr);
    reading.power_w = value(power);
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
    const double t = csv.rows[r][time->index] * time->factor;
    const double p = csv.rows[r][power->index] * power->factor;
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
