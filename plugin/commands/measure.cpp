// `ncjoule measure LOG.csv`: energy of a logged run (trapezoidal rule over time_s,power_w),
// optionally with the idle power taken off, to set beside a prediction.
#include <cstdio>
#include <string>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "ncjoule/calibrate.hpp"

namespace ncjoule::cli {
namespace {

struct MeasureCliOptions {
  std::string log;
  double idle_w = -1;
  double idle_from_first_s = -1;
};

int run_measure(const MeasureCliOptions& o) {
  std::vector<Diagnostic> diagnostics;
  const auto log = read_power_log(o.log, diagnostics);
  print_diagnostics(diagnostics);
  if (!log) return kInputError;
  // No figures from a log with a bad cell: they would be the energy of another run.
  for (const Diagnostic& d : diagnostics)
    if (d.severity == Severity::Error) return kInputError;
  MeasureOptions options;
  if (o.idle_w >= 0) options.idle_w = o.idle_w;
  if (o.idle_from_first_s > 0) options.idle_from_first_s = o.idle_from_first_s;
  const MeasuredEnergy m = measure_energy(*log, options);
  std::printf("log            %s (%zu samples)\n", o.log.c_str(), m.samples);
  std::printf("duration       %.3f s\n", m.duration_s);
  std::printf("energy         %.1f J (%.6f kWh)\n", m.energy_j, m.energy_j / 3.6e6);
  std::printf("mean power     %.1f W\n", m.mean_power_w);
  std::printf("peak power     %.1f W\n", m.peak_power_w);
  if (options.idle_w || options.idle_from_first_s) {
    std::printf("idle power     %.1f W%s\n", m.idle_w,
                options.idle_from_first_s ? " (mean of the log's first seconds)" : "");
    std::printf("net energy     %.1f J (%.6f kWh)\n", m.net_energy_j, m.net_energy_j / 3.6e6);
  }
  return kOk;
}

const Registration registration([](CLI::App& app, int& exit_code) {
  auto options = std::make_shared<MeasureCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "measure", "Energy of a logged run from a power meter's CSV (time_s,power_w), by the "
                 "trapezoidal rule, optionally minus the idle power");
  cmd->add_option("log", options->log, "CSV with columns time_s and power_w (or power_kw)")
      ->required()
      ->check(CLI::ExistingFile);
  auto* idle = cmd->add_option("--idle-w", options->idle_w,
                               "Subtract this idle power (W) over the whole run")
                   ->check(CLI::Range(0.0, 1e6)); // up to 1 MW, as a log's powers
  cmd->add_option("--idle-from-first", options->idle_from_first_s,
                  "Subtract the mean power of the log's first S seconds (machine idle before "
                  "the run, as Mora measured it)")
      ->check(CLI::Range(1e-6, 1e10))
      ->excludes(idle);
  cmd->callback([options, &exit_code] { exit_code = run_measure(*options); });
});

} // namespace
} // namespace ncjoule::cli
