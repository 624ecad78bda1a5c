// `ncjoule estimate FILE --machine PROFILE [--dialect NAME] [--json | --json-compact | --csv]`:
// interprets the program, plans it on the machine, and prints its time, energy and cost in total,
// by component and by operation (docs/json.md describes the JSON form, docs/report.md the CSV).
//
// The pipeline is estimate_program() (core/estimate) and the JSON is estimate_json()
// (core/report); this file turns options into calls and prints.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <spdlog/spdlog.h>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "estimate_settings.hpp"
#include "ncjoule/diagnostic.hpp"
#include "ncjoule/duration.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"
#include "ncjoule/report.hpp"
#include "progress.hpp"
#include "setting_sources.hpp"

namespace ncjoule::cli {
namespace {

struct EstimateCliOptions {
  std::string file;
  EstimateSettings settings;
  bool json = false;
  bool json_compact = false;
  bool csv = false;
  bool show_settings = false;
};

// ---------------------------------------------------------------------------------------------
// Human summary
// ---------------------------------------------------------------------------------------------

std::string clock_text(double seconds) {
  return duration_words(seconds);
}

void print_summary(const SourceFile& source, const MachineProfile& machine, const Estimate& e) {
  const EnergyResult& energy = e.energy;
  const TimeSplit& t = e.time;
  // Names and comments from files (a path, a profile's name, a post's signature, an operation's
  // comment) are printed escaped: an ESC or BEL in them must not drive the terminal.
  std::printf("%s on %s\n", printable(source.path).c_str(), printable(machine.name).c_str());
  std::printf(
      "  dialect     %s\n",
      printable(describe_dialect_choice({e.dialect, e.dialect_origin, e.dialect_reason})).c_str());
  std::printf("  model       %s\n", energy.model_description.c_str());
  if (!machine.estimated.empty()) {
    // A class profile: the reader must know which figures are no measurement of a machine.
    std::string what;
    for (std::size_t k = 0; k < machine.estimated.size(); ++k)
      what += (k == 0                              ? ""
               : k + 1 == machine.estimated.size() ? " and "
                                                   : ", ") +
              machine.estimated[k];
    std::printf("  estimated   this profile's %s are estimates for its class of machine, not "
                "measured on one: the %s figures below are approximate (ncjoule calibrate "
                "measures yours)\n",
                what.c_str(),
                machine.estimated.size() == 1 && machine.estimated[0] == "power"
                    ? "energy and power"
                    : "time, energy and power");
  }
  std::printf("  time        %s (%.3f s), %zu blocks\n", clock_text(e.time_s).c_str(), e.time_s,
              e.lines.size());
  std::printf("  rapids      %s\n", clock_text(t.rapid_s).c_str());
  if (e.removal) {
    std::printf("  cutting     %s\n", clock_text(t.cutting_s()).c_str());
    std::printf("  air cutting %s (feed moves that remove nothing)\n",
                clock_text(t.air_cut_s).c_str());
  } else {
    std::printf("  feed moves  %s (removal not simulated: cutting and air cutting not told "
                "apart)\n",
                clock_text(t.feed_s).c_str());
  }
  std::printf("  tool change %s (%d)\n", clock_text(t.tool_change_s).c_str(), t.tool_changes);
  std::printf("  dwell       %s\n", clock_text(t.dwell_s).c_str());
  std::printf("  spindle     %s (speed changes)\n", clock_text(t.spindle_s).c_str());
  if (t.other_s > 0) std::printf("  other       %s\n", clock_text(t.other_s).c_str());
  // Figures a guessed stock sets are marked '*' and their range said below them.
  const GuessedFigures guess = guessed_figures(e);
  const char* mark = guess.guessed ? "*" : "";
  std::printf("  energy      %.4f kWh%s (%.1f kJ), mean power %.0f W%s, peak %.0f W%s\n",
              energy.energy_j / 3.6e6, mark, energy.energy_j / 1000, energy.mean_power_w, mark,
              energy.peak_power_w, mark);
  if (e.inch) // an inch program's programmer reads in^3 and in^3/min; mm^3 follow for checking
    std::printf("  removed     %.3f in^3%s (%.0f mm^3), mean MRR %.3f in^3/min%s, SEC %.1f "
                "J/in^3%s (%.2f J/mm^3)\n",
                energy.removed_mm3 / kMm3PerIn3, mark, energy.removed_mm3,
                e.time_s > 0 ? energy.removed_mm3 / kMm3PerIn3 / (e.time_s / 60) : 0.0, mark,
                energy.sec_j_mm3 * kMm3PerIn3, mark, energy.sec_j_mm3);
  else
    std::printf("  removed     %.0f mm^3%s, SEC %.2f J/mm^3%s\n", energy.removed_mm3, mark,
                energy.sec_j_mm3, mark);
  if (energy.machine_cost > 0)
    std::printf("  CO2         %.4f kg%s, cost %.2f %s%s (machine time %.2f at %g/h, electricity "
                "%.4f)\n",
                energy.co2_kg, mark, energy.cost, printable(energy.currency).c_str(), mark,
                energy.machine_cost, energy.machine_rate_per_hour, energy.electricity_cost);
  else
    std::printf("  CO2         %.4f kg%s, cost %.4f %s%s\n", energy.co2_kg, mark, energy.cost,
                printable(energy.currency).c_str(), mark);
  if (guess.guessed) {
    const double volume_scale = e.inch ? 1 / kMm3PerIn3 : 1.0;
    const char* volume_unit = e.inch ? "in^3" : "mm^3";
    const int decimals = e.inch ? 3 : 0;
    std::printf("  * on a guessed stock (nothing states it; how it was guessed is under stock "
                "below): energy %.4f to %.4f kWh, removed %.*f to %.*f %s, peak %.0f to %.0f W, "
                "from no cut to the guess. Give the stock (--stock, a job file, PROGRAM.stock) "
                "to know them\n",
                guess.energy_j.low / 3.6e6, guess.energy_j.high / 3.6e6, decimals,
                guess.removed_mm3.low * volume_scale, decimals,
                guess.removed_mm3.high * volume_scale, volume_unit, guess.peak_power_w.low,
                guess.peak_power_w.high);
  }
  for (std::size_t i = 0; i < kPowerComponentCount; ++i) {
    if (energy.components_j[i] == 0) continue;
    std::printf("    %-12s %10.1f kJ (%.1f%%)\n",
                std::string(component_name(PowerComponent(i))).c_str(),
                energy.components_j[i] / 1000,
                energy.energy_j > 0 ? 100 * energy.components_j[i] / energy.energy_j : 0.0);
  }
}

// Time, air cutting, volume and energy per operation.
// Where a setup's stock came from: its kind (docs/stock.md) and where it is written.
void print_stock_from(const SetupSummary& s) {
  if (s.stock_from.empty() || s.stock_from == "none") return;
  std::printf("              from %s%s%s%s\n", s.stock_from.c_str(),
              s.stock_origin.empty() ? "" : " (", s.stock_origin.c_str(),
              s.stock_origin.empty() ? "" : ")");
}

void print_operations(const Estimate& e) {
  const std::vector<OperationSummary>& ops = e.operations;
  if (ops.empty()) return;
  std::size_t width = 9;
  std::vector<std::string> names; // from the program's comments: escaped
  for (const OperationSummary& op : ops) {
    names.push_back(printable(op.name));
    width = std::max(width, names.back().size());
  }
  std::printf("  by operation:\n");
  std::printf("    %-*s %4s %5s %14s %14s %10s %10s %7s\n", static_cast<int>(width), "operation",
              "tool", "line", "time", "air cutting", e.inch ? "in^3" : "mm^3", "kJ", "share");
  for (std::size_t k = 0; k < ops.size(); ++k) {
    const OperationSummary& op = ops[k];
    std::printf("    %-*s %4s %5s %14s %14s %10.*f %10.1f %6.1f%%\n", static_cast<int>(width),
                names[k].c_str(), op.tool > 0 ? ("T" + std::to_string(op.tool)).c_str() : "-",
                op.line >= 0 ? std::to_string(op.line + 1).c_str() : "-",
                clock_text(op.time_s).c_str(),
                e.removal ? clock_text(op.time.air_cut_s).c_str() : "-", e.inch ? 3 : 0,
                e.inch ? op.removed_mm3 / kMm3PerIn3 : op.removed_mm3, op.energy_j / 1000,
                e.energy.energy_j > 0 ? 100 * op.energy_j / e.energy.energy_j : 0.0);
  }
}

// ---------------------------------------------------------------------------------------------

int run_estimate(const EstimateCliOptions& o) {
  int status = kOk;
  MachineProfile machine;
  std::string machine_from;
  if (!load_machine(o.settings, machine, o.file, &machine_from)) return kInputError;
  if (o.show_settings) {
    const std::optional<ResolvedSettings> settings =
        settings_for(o.settings, o.file, machine, status);
    if (!settings) return status;
    print_settings(o.file, machine, machine_from, *settings);
    return kOk;
  }
  const std::optional<EstimateOptions> options =
      estimate_options(o.settings, o.file, machine, status);
  if (!options) return status;
  auto source = read_source(o.file, input_limit_bytes(o.settings), memory_budget_bytes(o.settings));
  if (!source) return kInputError;

  ProgressBar progress("estimating", 1);
  progress.begin(0, source->path);
  EstimateOptions with_progress = *options;
  with_progress.progress = progress.callback();
  const Estimate e = estimate_program(*source, machine, with_progress);
  progress.finish();
  if (e.failed) {
    print_diagnostics(e.diagnostics, e.diagnostics_dropped);
    std::cerr << "ncjoule: " << source->path << " cannot be estimated (see above)"
              << (e.removal_failed
                      ? "; --no-removal estimates it without the material removal stage"
                      : "")
              << '\n';
    return failed_status(e);
  }
  if (o.json) {
    write_estimate_json(std::cout, e, machine);
  } else if (o.json_compact) {
    write_estimate_json_compact(std::cout, e, machine);
  } else if (o.csv) {
    write_estimate_csv(std::cout, e);
  } else {
    print_summary(*source, machine, e);
    if (e.removal)
      std::printf(
          "  stock       %s\n              %s engine, %.3f mm grid, %zu columns, %.1f MiB\n",
          e.setups.size() > 1 ? "one per setup (below)" : e.removal->stock_description.c_str(),
          std::string(engine_name(e.removal->engine)).c_str(), e.removal->grid.dx,
          e.removal->grid.columns(), double(e.removal->memory_bytes) / (1 << 20));
    if (e.removal && e.setups.size() == 1) print_stock_from(e.setups.front());
    if (e.setups.size() > 1)
      for (std::size_t k = 0; k < e.setups.size(); ++k) {
        const SetupSummary& s = e.setups[k];
        std::printf("  setup %zu     from line %d (%s): %.1f s, %.1f kJ, %.*f %s\n", k + 1,
                    s.first_line + 1, s.reason.c_str(), s.time_s, s.energy_j / 1e3, e.inch ? 3 : 0,
                    e.inch ? s.removed_mm3 / kMm3PerIn3 : s.removed_mm3, e.inch ? "in^3" : "mm^3");
        if (!s.stock.empty()) std::printf("              stock %s\n", s.stock.c_str());
        if (e.removal) print_stock_from(s);
      }
    print_operations(e);
    if (!e.unsimulated_tools.empty()) {
      std::printf("  not simulated:");
      for (int t : e.unsimulated_tools)
        std::printf(" T%d", t);
      std::printf(" (described nowhere: their moves remove nothing)\n");
    }
  }
  std::cout.flush();
  print_diagnostics(e.diagnostics, e.diagnostics_dropped);
  for (const Diagnostic& d : e.diagnostics)
    if (d.severity == Severity::Error) return kInputError;
  return kOk;
}

const Registration registration([](CLI::App& app, int& exit_code) {
  auto options = std::make_shared<EstimateCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "estimate", "Predict a program's time, energy, SEC, CO2 and cost on a machine, by "
                  "component, operation and block");
  cmd->add_option("file", options->file, "NC program (- for standard input)")->required();
  add_estimate_settings(*cmd, options->settings);
  auto* json = cmd->add_flag("--json", options->json,
                             "Print the totals, operations and every block as JSON (docs/json.md)");
  auto* json_compact = cmd->add_flag(
      "--json-compact", options->json_compact,
      "Print the same JSON made for large programs: no indentation, the blocks as rows of "
      "values under one list of column names, a row per line (docs/json.md)");
  json_compact->excludes(json);
  cmd->add_flag("--csv", options->csv,
                "Print one CSV row per block, with a header row (docs/report.md)")
      ->excludes(json)
      ->excludes(json_compact);
  cmd->add_flag("--show-settings", options->show_settings,
                "Print every setting (machine, material, prices, dialect, tool table, each value "
                "of the profile) with where it came from, and estimate nothing")
      ->excludes(json)
      ->excludes(json_compact);
  cmd->callback([options, &exit_code] { exit_code = run_estimate(*options); });
});

} // namespace
} // namespace ncjoule::cli
