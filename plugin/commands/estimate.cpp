// `ncjoule estimate FILE --machine PROFILE [--dialect NAME] [--json | --csv]`: interprets the
// program, plans it on the machine, and prints its time, energy and cost in total, by component
// and by operation (docs/json.md describes the JSON form, docs/report.md the CSV).
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
#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"
#include "ncjoule/report.hpp"
#include "progress.hpp"

namespace ncjoule::cli {
namespace {

struct EstimateCliOptions {
  std::string file;
  std::string machine;
  std::string dialect;
  std::string stock;              // "box:..." or an STL file; empty: the box of the cutting moves
  std::string job;                // job file (TOML): stock and tool table
  std::vector<std::string> tools; // --tool N:TYPE:D[...], repeatable
  std::string engine = "dexel";
  double grid_mm = 0;
  bool no_removal = false;
  std::optional<double> co2_kg_per_kwh, price_per_kwh;
  bool json = false;
  bool csv = false;
};

// ---------------------------------------------------------------------------------------------
// Human summary
// ---------------------------------------------------------------------------------------------

std::string clock_text(double seconds) {
  const long whole = static_cast<long>(seconds);
  char text[64];
  if (whole >= 3600)
    std::snprintf(text, sizeof text, "%ld h %02ld min %04.1f s", whole / 3600, whole / 60 % 60,
                  seconds - static_cast<double>(whole / 60 * 60));
  else if (whole >= 60)
    std::snprintf(text, sizeof text, "%ld min %04.1f s", whole / 60,
                  seconds - static_cast<double>(whole / 60 * 60));
  else
    std::snprintf(text, sizeof text, "%.1f s", seconds);
  return text;
}

// Where the program's time goes, by what the machine does.
struct TimeBreakdown {
  double rapid_s = 0, cutting_s = 0, tool_change_s = 0, other_s = 0;
  int tool_changes = 0;
};

TimeBreakdown break_down(const Timeline& timeline) {
  TimeBreakdown b;
  for (const TimedCommand& c : timeline.commands) {
    switch (c.kind) {
    case CanonKind::Traverse:
      b.rapid_s += c.duration_s;
      break;
    case CanonKind::Feed:
    case CanonKind::Arc:
    case CanonKind::Probe:
      b.cutting_s += c.duration_s;
      break;
    case CanonKind::ChangeTool:
      b.tool_change_s += c.duration_s;
      ++b.tool_changes;
      break;
    default:
      b.other_s += c.duration_s;
      break;
    }
  }
  return b;
}

void print_summary(const SourceFile& source, const MachineProfile& machine,
                   const Timeline& timeline, const EnergyResult& energy, std::size_t block_count) {
  const TimeBreakdown b = break_down(timeline);
  std::printf("%s on %s\n", source.path.c_str(), machine.name.c_str());
  std::printf("  model       %s\n", energy.model_description.c_str());
  std::printf("  time        %s (%.3f s), %zu blocks\n", clock_text(timeline.total_s).c_str(),
              timeline.total_s, block_count);
  std::printf("  rapids      %s\n", clock_text(b.rapid_s).c_str());
  std::printf("  feed moves  %s\n", clock_text(b.cutting_s).c_str());
  std::printf("  tool change %s (%d)\n", clock_text(b.tool_change_s).c_str(), b.tool_changes);
  std::printf("  other       %s (dwell, spindle ramps)\n", clock_text(b.other_s).c_str());
  std::printf("  energy      %.4f kWh (%.1f kJ), mean power %.0f W, peak %.0f W\n",
              energy.energy_j / 3.6e6, energy.energy_j / 1000, energy.mean_power_w,
              energy.peak_power_w);
  std::printf("  removed     %.0f mm^3, SEC %.2f J/mm^3\n", energy.removed_mm3, energy.sec_j_mm3);
  std::printf("  CO2         %.4f kg, cost %.4f %s\n", energy.co2_kg, energy.cost,
              energy.currency.c_str());
  for (std::size_t i = 0; i < kPowerComponentCount; ++i) {
    if (energy.components_j[i] == 0) continue;
    std::printf("    %-12s %10.1f kJ (%.1f%%)\n",
                std::string(component_name(PowerComponent(i))).c_str(),
                energy.components_j[i] / 1000,
                energy.energy_j > 0 ? 100 * energy.components_j[i] / energy.energy_j : 0.0);
  }
}

// Time, volume and energy per operation (from one tool change to the next).
void print_operations(const std::vector<OperationSummary>& ops, const EnergyResult& energy) {
  if (ops.empty()) return;
  std::size_t width = 9;
  for (const OperationSummary& op : ops)
    width = std::max(width, std::min<std::size_t>(op.name.size(), 32));
  std::printf("  by operation:\n");
  std::printf("    %-*s %4s %5s %14s %10s %10s %7s\n", static_cast<int>(width), "operation", "tool",
              "line", "time", "mm^3", "kJ", "share");
  for (const OperationSummary& op : ops) {
    std::printf("    %-*s %4s %5s %14s %10.0f %10.1f %6.1f%%\n", static_cast<int>(width),
                op.name.substr(0, 32).c_str(),
                op.tool > 0 ? ("T" + std::to_string(op.tool)).c_str() : "-",
                op.line >= 0 ? std::to_string(op.line + 1).c_str() : "-",
                clock_text(op.time_s).c_str(), op.removed_mm3, op.energy_j / 1000,
                energy.energy_j > 0 ? 100 * op.energy_j / energy.energy_j : 0.0);
  }
}

// ---------------------------------------------------------------------------------------------

int run_estimate(const EstimateCliOptions& o) {
  MachineProfile machine;
  try {
    machine = load_profile(o.machine);
  } catch (const ProfileError& e) {
    std::cerr << "ncjoule: bad machine profile: " << e.what() << '\n';
    return kInputError;
  }
  auto source = read_source(o.file);
  if (!source) return kInputError;

  EstimateOptions options;
  if (!o.dialect.empty()) {
    options.dialect = dialect_from_option(o.dialect);
    if (!options.dialect) return kUsage;
  }
  options.simulate_removal = !o.no_removal;
  // Tools: the job file's, then the command line's, each replacing the one before (and the
  // program's header comments) for the same number.
  if (!o.job.empty()) {
    std::vector<Diagnostic> job_diagnostics;
    const auto job = read_job_file(o.job, job_diagnostics);
    print_diagnostics(job_diagnostics);
    if (!job) return kInputError;
    if (job->stock) options.stock = job->stock;
    options.tools = job->tools;
  }
  for (const std::string& text : o.tools) {
    std::string error;
    const auto tool = parse_tool_spec(text, &error);
    if (!tool) {
      std::cerr << "ncjoule: bad --tool '" << text << "': " << error << '\n';
      return kUsage;
    }
    options.tools[tool->number] = *tool;
  }
  if (!o.stock.empty()) {
    std::string error;
    options.stock = parse_stock_spec(o.stock, &error);
    if (!options.stock) {
      std::cerr << "ncjoule: bad --stock '" << o.stock << "': " << error << '\n';
      return kUsage;
    }
  }
  options.removal.engine = o.engine == "voxel" ? EngineKind::Voxel : EngineKind::Dexel;
  options.removal.grid_mm = o.grid_mm;
  options.energy.co2_kg_per_kwh = o.co2_kg_per_kwh;
  options.energy.price_per_kwh = o.price_per_kwh;

  ProgressBar progress("estimating", 1);
  progress.begin(0, source->path);
  const Estimate e = estimate_program(*source, machine, options);
  progress.finish();
  if (e.failed) {
    print_diagnostics(e.diagnostics);
    std::cerr << "ncjoule: " << source->path
              << " cannot be estimated (see above); define the "
                 "tools in the program's header comments, a job file (--job) or with --tool, "
                 "or use --no-removal\n";
    return kInputError;
  }
  if (o.json) {
    std::cout << estimate_json(e, *source, machine) << '\n';
  } else if (o.csv) {
    std::cout << estimate_csv(e, *source);
  } else {
    print_summary(*source, machine, e.timeline, e.energy, e.lines.size());
    if (e.removal)
      std::printf(
          "  stock       %s\n              %s engine, %.3f mm grid, %zu columns, %.1f MiB\n",
          e.removal->stock_description.c_str(), std::string(engine_name(e.removal->engine)).c_str(),
          e.removal->grid.dx, e.removal->grid.columns(),
          double(e.removal->memory_bytes) / (1 << 20));
    print_operations(operations(*source, e), e.energy);
  }
  std::cout.flush();
  print_diagnostics(e.diagnostics);
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
  cmd->add_option("-m,--machine", options->machine, "Machine profile (.toml)")->required();
  cmd->add_option("--dialect", options->dialect,
                  "Controller dialect (linuxcnc, fanuc, haas, grbl, mach3, siemens); "
                  "default: the machine profile's, else detected from the file");
  cmd->add_option("--stock", options->stock,
                  "Stock: box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (mm) or an STL file; "
                  "default: the bounding box of the cutting moves");
  cmd->add_option("--job", options->job,
                  "Job file (TOML): stock = \"box:...\" or stock_stl = \"part.stl\", and "
                  "[[tool]] entries; --stock and --tool override it");
  cmd->add_option("--tool", options->tools,
                  "Tool N:TYPE:DIAMETER[:EXTRA], e.g. 1:flat:6, 2:ball:6, 3:bullnose:10:1.5, "
                  "4:drill:6.8:118, 5:chamfer:12:90 (repeatable; overrides header comments)")
      ->allow_extra_args(false); // one tool per --tool, so the program's file name is not taken
  cmd->add_option("--engine", options->engine, "Removal engine: dexel (default) or voxel")
      ->check(CLI::IsMember({"dexel", "voxel"}));
  cmd->add_option("--grid", options->grid_mm,
                  "Removal grid spacing in mm (default: from the tools)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--no-removal", options->no_removal,
                "Do not simulate material removal (no tools needed; cutting power is zero)");
  cmd->add_option("--co2", options->co2_kg_per_kwh, "kg of CO2 per kWh (overrides the profile)");
  cmd->add_option("--price", options->price_per_kwh, "Price per kWh (overrides the profile)");
  auto* json = cmd->add_flag("--json", options->json,
                             "Print the totals, operations and every block as JSON (docs/json.md)");
  cmd->add_flag("--csv", options->csv,
                "Print one CSV row per block, with a header row (docs/report.md)")
      ->excludes(json);
  cmd->callback([options, &exit_code] { exit_code = run_estimate(*options); });
});

} // namespace
} // namespace ncjoule::cli
