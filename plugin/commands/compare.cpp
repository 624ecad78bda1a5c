// `ncjoule compare A.nc B.nc ... --machine PROFILE [--json]`: estimates alternatives of the same
// part on one machine and ranks them by energy, with the difference of each to the best, and
// component by component, why (docs/report.md).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command_registry.hpp"
#include "multi_estimate.hpp"
#include "ncjoule/report.hpp"

namespace ncjoule::cli {
namespace {

struct CompareOptions {
  std::vector<std::string> files;
  EstimateSettings settings;
  bool json = false;
};

std::string label_of(const std::string& path) {
  const std::string name = std::filesystem::path(path).filename().string();
  return name.empty() ? path : name;
}

std::string time_text(double s) {
  char text[32];
  if (s >= 60)
    std::snprintf(text, sizeof text, "%ld:%04.1f", static_cast<long>(s) / 60,
                  s - 60 * std::floor(s / 60));
  else
    std::snprintf(text, sizeof text, "%.1f s", s);
  return text;
}

std::string diff_text(double diff, double pct, const char* unit, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%+.*f %s (%+.1f%%)", decimals, diff, unit, pct);
  return text;
}

void print_table(const std::vector<RankedProgram>& ranked, const MachineProfile& machine) {
  std::size_t width = 7;
  for (const RankedProgram& r : ranked)
    width = std::max(width, label_of(r.totals.file).size());
  const std::string currency = ranked.front().totals.currency;
  std::printf("%zu alternatives on %s, least energy first\n\n", ranked.size(),
              machine.name.c_str());
  std::printf(" #  %-*s %10s %10s %9s %9s %9s %10s  %-22s %s\n", static_cast<int>(width), "program",
              "time", "energy kJ", "kWh", "SEC J/mm3", "CO2 g", ("cost " + currency).c_str(),
              "energy vs best", "time vs best");
  for (const RankedProgram& r : ranked) {
    const ProgramTotals& t = r.totals;
    const bool best = r.rank == 1;
    std::printf("%2d  %-*s %10s %10.2f %9.5f %9.2f %9.2f %10.4f  %-22s %s\n", r.rank,
                static_cast<int>(width), label_of(t.file).c_str(), time_text(t.time_s).c_str(),
                t.energy_j / 1000, t.energy_j / 3.6e6, t.sec_j_mm3, t.co2_kg * 1000, t.cost,
                best ? "best"
                     : diff_text(r.energy_diff_j / 1000, r.energy_diff_pct, "kJ", 2).c_str(),
                best ? "-" : diff_text(r.time_diff_s, r.time_diff_pct, "s", 1).c_str());
  }

  // Component by component, each program with its difference to the best.
  std::printf("\nenergy by component, kJ (difference to the best):\n");
  std::printf("  %-12s", "component");
  for (const RankedProgram& r : ranked)
    std::printf(" %24s", label_of(r.totals.file).substr(0, 24).c_str());
  std::printf("\n");
  for (std::size_t c = 0; c < kPowerComponentCount; ++c) {
    bool any = false;
    for (const RankedProgram& r : ranked)
      any = any || r.totals.components_j[c] != 0;
    if (!any) continue;
    std::printf("  %-12s", std::string(component_name(PowerComponent(c))).c_str());
    for (const RankedProgram& r : ranked) {
      char cell[64];
      if (r.rank == 1)
        std::snprintf(cell, sizeof cell, "%.2f", r.totals.components_j[c] / 1000);
      else
        std::snprintf(cell, sizeof cell, "%.2f (%+.2f)", r.totals.components_j[c] / 1000,
                      r.component_diff_j[c] / 1000);
      std::printf(" %24s", cell);
    }
    std::printf("\n");
  }
  std::printf("\n");
  for (const RankedProgram& r : ranked)
    if (r.rank > 1)
      std::printf("%s uses %.2f kJ more than %s: %s\n", label_of(r.totals.file).c_str(),
                  r.energy_diff_j / 1000, label_of(ranked.front().totals.file).c_str(),
                  explain_difference(r).c_str());
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
    if (p.estimate.failed) return kInputError;
  if (programs.size() < o.files.size()) return status;

  std::vector<ProgramTotals> totals;
  for (const EstimatedProgram& p : programs)
    totals.push_back(program_totals(p.estimate));
  const std::vector<RankedProgram> ranked = rank_programs(totals);
  if (o.json)
    std::cout << comparison_json(ranked, machine) << '\n';
  else
    print_table(ranked, machine);
  std::cout.flush();
  return status;
}

const Registration registration([](CLI::App& app, int& exit_code) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Rank alternative programs for the same part by energy on one machine, with "
                 "time, SEC, CO2, cost, the difference to the best and its reasons by component");
  cmd->add_option("files", options->files, "NC programs to compare (two or more)")->required();
  add_estimate_settings(*cmd, options->settings);
  cmd->add_flag("--json", options->json, "Print the ranking as JSON (docs/report.md)");
  cmd->footer("Exit codes: 0 ranked; 1 bad command line; 2 a program or the profile cannot be "
              "read or estimated.");
  cmd->callback([options, &exit_code] { exit_code = run_compare(*options); });
});

} // namespace
} // namespace ncjoule::cli
