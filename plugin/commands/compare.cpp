// `ncjoule compare A.nc B.nc ... --machine PROFILE [--by energy|time|cost] [--json]`: estimates
// alternatives of the same part on one machine and ranks them, with the difference of each to
// the best and why, component by component and operation by operation (docs/report.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "multi_estimate.hpp"
#include "ncjoule/diagnostic.hpp"
#include "ncjoule/duration.hpp"
#include "ncjoule/report.hpp"

namespace ncjoule::cli {
namespace {

struct CompareOptions {
  std::vector<std::string> files;
  EstimateSettings settings;
  std::string by = "energy";
  bool json = false;
};

// The names the table shows: file names, or the paths as given when two file names are equal
// (a/part.nc and b/part.nc). Never shortened.
std::vector<std::string> labels_of(const std::vector<RankedProgram>& ranked) {
  std::vector<std::string> names;
  for (const RankedProgram& r : ranked) {
    const std::string name = std::filesystem::path(r.totals.file).filename().string();
    names.push_back(name.empty() ? r.totals.file : name);
  }
  for (std::size_t i = 0; i < names.size(); ++i)
    for (std::size_t k = 0; k < names.size(); ++k)
      if (i != k && std::filesystem::path(ranked[k].totals.file).filename() ==
                        std::filesystem::path(ranked[i].totals.file).filename())
        names[i] = ranked[i].totals.file;
  return names;
}

// One format for a whole column: seconds when every time is under a minute, else m:ss.s (h:mm:ss.s
// from an hour), so times line up and compare at a glance.
std::vector<std::string> time_column(const std::vector<double>& seconds) {
  double longest = 0;
  for (double s : seconds)
    longest = std::max(longest, s);
  std::vector<std::string> out;
  for (double s : seconds) {
    char text[64];
    if (longest < 60) {
      std::snprintf(text, sizeof text, "%.1f s", s);
    } else {
      const ClockParts c = split_duration(s, 0.1);
      if (longest >= 3600)
        std::snprintf(text, sizeof text, "%s:%02d:%04.1f", huge_hours(c.hours).c_str(), c.minutes,
                      c.seconds);
      else
        std::snprintf(text, sizeof text, "%d:%04.1f", c.minutes, c.seconds);
    }
    out.push_back(text);
  }
  return out;
}

std::string diff_text(double diff, double pct, const char* unit, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%+.*f %s (%+.1f%%)", decimals, diff, unit, pct);
  return text;
}

// A table of rows by program, each column as wide as its program's name or its widest cell.
void print_rows(const char* title, const char* first_column, const std::vector<std::string>& names,
                const std::vector<std::string>& rows,
                const std::vector<std::vector<std::string>>& cells) {
  std::vector<std::size_t> widths;
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::size_t w = names[i].size();
    for (const auto& row : cells)
      w = std::max(w, row[i].size());
    widths.push_back(w);
  }
  std::printf("\n%s\n  %-12s", title, first_column);
  for (std::size_t i = 0; i < names.size(); ++i)
    std::printf("  %*s", static_cast<int>(widths[i]), names[i].c_str());
  std::printf("\n");
  for (std::size_t row = 0; row < rows.size(); ++row) {
    std::printf("  %-12s", rows[row].c_str());
    for (std::size_t i = 0; i < names.size(); ++i)
      std::printf("  %*s", static_cast<int>(widths[i]), cells[row][i].c_str());
    std::printf("\n");
  }
}

void print_table(const std::vector<RankedProgram>& ranked, const MachineProfile& machine,
                 RankBy by) {
  // A program whose figures rest on a guessed stock is marked '*' (its range is in the warnings).
  // File names and operations' comments are printed escaped: no raw ESC or BEL reaches the
  // terminal.
  std::vector<std::string> names = labels_of(ranked);
  for (std::string& name : names)
    name = printable(name);
  for (std::size_t i = 0; i < ranked.size(); ++i)
    if (ranked[i].totals.guess.guessed) names[i] += '*';
  std::size_t width = 7;
  for (const std::string& name : names)
    width = std::max(width, name.size());
  std::vector<double> times, air;
  for (const RankedProgram& r : ranked) {
    times.push_back(r.totals.time_s);
    air.push_back(r.totals.air_cut_s);
  }
  const std::vector<std::string> time_cells = time_column(times), air_cells = time_column(air);
  const std::string currency = printable(ranked.front().totals.currency);
  const char* order = by == RankBy::Time   ? "shortest time"
                      : by == RankBy::Cost ? "lowest cost"
                                           : "least energy";
  std::printf("%zu alternatives on %s, %s first\n", ranked.size(), printable(machine.name).c_str(),
              order);
  for (const std::string& warning : comparison_warnings(ranked))
    std::printf("warning: %s\n", printable(warning).c_str());
  // Inch programs compare in in^3 (and J/in^3), as their programmers read volumes.
  const bool inch = std::all_of(ranked.begin(), ranked.end(),
                                [](const RankedProgram& r) { return r.totals.inch; });
  const double volume_unit = inch ? kMm3PerIn3 : 1.0; // mm^3 in one
  std::printf("\n #  %-*s %6s %10s %10s %10s %9s %8s %9s %9s %9s %10s  %-22s %s\n",
              static_cast<int>(width), "program", "setups", "time", "air cut", "energy kJ", "kWh",
              "peak kW", inch ? "in3" : "mm3", inch ? "SEC J/in3" : "SEC J/mm3", "CO2 g",
              ("cost " + currency).c_str(), "energy vs best", "time vs best");
  for (std::size_t i = 0; i < ranked.size(); ++i) {
    const RankedProgram& r = ranked[i];
    const ProgramTotals& t = r.totals;
    const bool best = r.rank == 1;
    std::printf("%2d  %-*s %6zu %10s %10s %10.2f %9.5f %8.2f %9.*f %9.*f %9.2f %10.4f  %-22s %s\n",
                r.rank, static_cast<int>(width), names[i].c_str(), t.setups, time_cells[i].c_str(),
                air_cells[i].c_str(), t.energy_j / 1000, t.energy_j / 3.6e6, t.peak_power_w / 1000,
                inch ? 3 : 0, t.removed_mm3 / volume_unit, inch ? 0 : 2, t.sec_j_mm3 * volume_unit,
                t.co2_kg * 1000, t.cost,
                best ? "best"
                     : diff_text(r.energy_diff_j / 1000, r.energy_diff_pct, "kJ", 2).c_str(),
                best ? "-" : diff_text(r.time_diff_s, r.time_diff_pct, "s", 1).c_str());
  }

  // Component by component, each program with its difference to the best; columns as wide as
  // their program's name.
  std::vector<std::vector<std::string>> cells;
  std::vector<std::string> rows;
  for (std::size_t c = 0; c < kPowerComponentCount; ++c) {
    bool any = false;
    for (const RankedProgram& r : ranked)
      any = any || r.totals.components_j[c] != 0;
    if (!any) continue;
    rows.push_back(std::string(component_name(PowerComponent(c))));
    cells.emplace_back();
    for (const RankedProgram& r : ranked) {
      char cell[64];
      if (r.rank == 1)
        std::snprintf(cell, sizeof cell, "%.2f", r.totals.components_j[c] / 1000);
      else
        std::snprintf(cell, sizeof cell, "%.2f (%+.2f)", r.totals.components_j[c] / 1000,
                      r.component_diff_j[c] / 1000);
      cells.back().push_back(cell);
    }
  }
  print_rows("energy by component, kJ (difference to the best):", "component", names, rows, cells);

  // Where the time goes, in the words a cycle time is read in.
  const bool removal = std::all_of(ranked.begin(), ranked.end(),
                                   [](const RankedProgram& r) { return r.totals.removal; });
  struct TimeRow {
    const char* name;
    double (*of)(const TimeSplit&);
  };
  std::vector<TimeRow> time_rows;
  if (removal) {
    time_rows.push_back({"cutting", [](const TimeSplit& t) { return t.cutting_s(); }});
    time_rows.push_back({"air cutting", [](const TimeSplit& t) { return t.air_cut_s; }});
  } else {
    time_rows.push_back({"feed moves", [](const TimeSplit& t) { return t.feed_s; }});
  }
  time_rows.push_back({"rapids", [](const TimeSplit& t) { return t.rapid_s; }});
  time_rows.push_back({"tool changes", [](const TimeSplit& t) { return t.tool_change_s; }});
  time_rows.push_back({"dwells", [](const TimeSplit& t) { return t.dwell_s; }});
  time_rows.push_back({"spindle", [](const TimeSplit& t) { return t.spindle_s; }});
  time_rows.push_back({"other", [](const TimeSplit& t) { return t.other_s; }});
  rows.clear();
  cells.clear();
  for (const TimeRow& row : time_rows) {
    bool any = false;
    for (const RankedProgram& r : ranked)
      any = any || row.of(r.totals.time) != 0;
    if (!any) continue;
    rows.push_back(row.name);
    cells.emplace_back();
    const double best = row.of(ranked.front().totals.time);
    for (const RankedProgram& r : ranked) {
      char cell[64];
      const double value = row.of(r.totals.time);
      if (r.rank == 1)
        std::snprintf(cell, sizeof cell, "%.1f", value);
      else
        std::snprintf(cell, sizeof cell, "%.1f (%+.1f)", value, value - best);
      cells.back().push_back(cell);
    }
  }
  print_rows("time by what it is spent on, s (difference to the best):", "time", names, rows,
             cells);
  std::printf("\n");
  for (std::size_t i = 1; i < ranked.size(); ++i) {
    const RankedProgram& r = ranked[i];
    const ProgramTotals& best = ranked.front().totals;
    // The cause first in time (what a programmer changes), then the peak, then the energy's
    // components.
    const std::string in_time =
        explain_time_difference(r.totals.time, best.time, r.totals.removal && best.removal);
    char longer[96];
    std::snprintf(longer, sizeof longer, "%.1f s %s", std::abs(r.time_diff_s),
                  r.time_diff_s >= 0 ? "longer" : "shorter");
    const std::string cause = in_time.empty() ? "" : " (" + in_time + ")";
    const std::string time_text = longer + cause;
    char peak[96];
    std::snprintf(peak, sizeof peak, "peak %.1f kW (%+.1f)", r.totals.peak_power_w / 1000,
                  (r.totals.peak_power_w - best.peak_power_w) / 1000);
    if (by == RankBy::Time)
      std::printf("%s takes %s than %s%s; %s", names[i].c_str(), longer, names[0].c_str(),
                  cause.c_str(), peak);
    else if (by == RankBy::Cost)
      std::printf("%s costs %.4f %s more than %s: %s; %s", names[i].c_str(), r.cost_diff,
                  printable(r.totals.currency).c_str(), names[0].c_str(), time_text.c_str(), peak);
    else
      std::printf("%s uses %.2f kJ more than %s: %s; %s; energy in %s", names[i].c_str(),
                  r.energy_diff_j / 1000, names[0].c_str(), time_text.c_str(), peak,
                  explain_difference(r).c_str());
    const std::string ops = explain_by_operation(r, ranked.front(), by);
    std::printf("; by operation: %s\n",
                ops.empty() ? "no operation differs" : printable(ops).c_str());
  }
}

int run_compare(const CompareOptions& o) {
  if (o.files.size() < 2) {
    std::cerr << "ncjoule compare: give two or more programs to compare\n";
    return kUsage;
  }
  MachineProfile machine;
  std::vector<EstimatedProgram> programs;
  const int status = estimate_files(o.files, o.settings, machine, programs);
  if (status != kOk && status != kInputError) return status;
  for (const EstimatedProgram& p : programs)
    if (p.estimate.failed) return failed_status(p.estimate);
  if (programs.size() < o.files.size()) return status;

  std::vector<ProgramTotals> totals;
  for (const EstimatedProgram& p : programs)
    totals.push_back(program_totals(p.estimate));
  const RankBy by = parse_rank_by(o.by).value_or(RankBy::Energy); // CLI11 checked the word
  const std::vector<RankedProgram> ranked = rank_programs(totals, by);
  if (o.json)
    std::cout << comparison_json(ranked, machine, 1, by) << '\n';
  else
    print_table(ranked, machine, by);
  std::cout.flush();
  return status;
}

const Registration registration([](CLI::App& app, int& exit_code) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Rank alternative programs for the same part by energy, time or cost on one "
                 "machine, with SEC, CO2, the difference to the best and its reasons by "
                 "component and by operation");
  cmd->add_option("files", options->files, "NC programs to compare (two or more)")->required();
  add_estimate_settings(*cmd, options->settings);
  cmd->add_option("--by", options->by,
                  "Rank by energy (default), time, or cost (electricity plus the machine-hour "
                  "rate, --machine-rate or the profile's machine_rate_per_hour)")
      ->check(CLI::IsMember({"energy", "time", "cost"}));
  cmd->add_flag("--json", options->json, "Print the ranking as JSON (docs/report.md)");
  cmd->footer("Exit codes: 0 ranked; 1 bad command line; 2 a program or the profile cannot be "
              "read or estimated; 5 a work budget (--max-moves, --max-path-samples, "
              "--max-removal-work) stopped the run.");
  cmd->callback([options, &exit_code] { exit_code = run_compare(*options); });
});

} // namespace
} // namespace ncjoule::cli
