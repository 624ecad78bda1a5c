// `ncjoule check-log PROGRAM... --log LOG...`: what the machine did against what ncjoule
// predicts. The controller's MTConnect log (SHDR or Streams documents) is cut into runs, each
// run aligned with the program it ran; the usable runs are compared with the prediction on the
// machine profile, in total, per operation and for the worst blocks (docs/controller-logs.md).
#include <cstdio>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "controller_logs_cli.hpp"
#include "estimate_settings.hpp"

namespace ncjoule::cli {
namespace {

struct CheckLogCliOptions {
  std::vector<std::string> programs;
  LogOptions logs;
  EstimateSettings settings;
  std::size_t worst = 10;
  bool json = false;
};

int run_check_log(const CheckLogCliOptions& o) {
  MachineProfile machine;
  if (!load_machine(o.settings, machine, o.programs.front())) return kInputError;
  EstimateOptions options;
  if (!o.settings.dialect.empty()) {
    options.dialect = dialect_from_option(o.settings.dialect);
    if (!options.dialect) return kUsage;
  }
  LogEvidence evidence;
  std::vector<LineTimes> times;
  if (const int status = read_evidence(o.logs, o.programs, options, machine, evidence, times);
      status != kOk)
    return status;
  const std::vector<ProgramCheck> checks = check_programs(evidence, times, o.worst);
  if (o.json) {
    std::printf("%s\n", check_json(evidence, checks, machine).c_str());
    return kOk;
  }
  std::printf("on %s (%s)\n", printable(machine.name).c_str(),
              printable(machine.source_path).c_str());
  print_log_summary(evidence);
  print_run_table(evidence);
  print_program_checks(evidence, checks);
  return kOk;
}

const Registration registration([](CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CheckLogCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "check-log", "Compare what a machine did (its MTConnect log: SHDR or Streams XML) with "
                   "the prediction for the programs it ran: per run, operation and block");
  cmd->add_option("programs", o->programs, "The NC programs the log recorded")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--log", o->logs.logs,
                  "Controller log: SHDR lines or an agent's Streams "
                  "document (repeat for several files)")
      ->required()
      ->check(CLI::ExistingFile);
  add_log_options(*cmd, o->logs);
  cmd->add_option("-m,--machine", o->settings.machine,
                  "Machine profile: a shipped name (ncjoule profiles) or a .toml file");
  cmd->add_option("--dialect", o->settings.dialect, "Controller dialect of the programs");
  cmd->add_option("--worst", o->worst, "How many of the worst blocks to list (default 10)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--json", o->json, "Print the runs and the comparison as JSON");
  cmd->callback([o, &exit_code] { exit_code = run_check_log(*o); });
});

} // namespace
} // namespace ncjoule::cli
