// `ncjoule report FILE... --machine PROFILE -o report.html`: one self-contained HTML page with
// the programs' totals, power and removal rate over time, energy per operation and component,
// and their comparison when there are several (docs/report.md); with --log, what the machine's
// controller log measured over the prediction (docs/controller-logs.md).
//
// The page is built in core/report (html_report); this file estimates and writes it, through a
// temporary file renamed into place so that a failed run never leaves half a report.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "controller_logs_cli.hpp"
#include "multi_estimate.hpp"
#include "ncjoule/report.hpp"
#include "output_file.hpp"

namespace ncjoule::cli {
namespace {

struct ReportOptions {
  std::vector<std::string> files;
  EstimateSettings settings;
  std::string output = "report.html";
  LogOptions logs; // --log and how to read it: the measured runs over the prediction
};

int run_report(const ReportOptions& o) {
  MachineProfile machine;
  std::vector<EstimatedProgram> programs;
  const int status = estimate_files(o.files, o.settings, machine, programs);
  if (status != kOk && status != kInputError) return status;
  if (programs.size() < o.files.size()) return status;
  for (const EstimatedProgram& p : programs)
    if (p.estimate.failed) return failed_status(p.estimate); // nothing to chart: no report

  std::vector<MeasuredOverlay> measured;
  if (!o.logs.logs.empty())
    if (const int logs = measured_overlays(o.logs, o.files, o.settings.dialect, machine, measured);
        logs != kOk)
      return logs; // a log that cannot be read: no report rather than one without it

  std::vector<ReportProgram> inputs;
  for (std::size_t i = 0; i < programs.size(); ++i)
    inputs.push_back(
        {&programs[i].source, &programs[i].estimate, i < measured.size() ? &measured[i] : nullptr});
  const std::string html = html_report(inputs, machine);
  if (const std::string error = write_output_file(o.output, html); !error.empty()) {
    std::cerr << "ncjoule: " << printable(error) << "; nothing was written\n";
    return kOutputError;
  }
  std::cerr << "ncjoule: wrote " << printable(o.output) << " (" << html.size() / 1024 << " KiB, "
            << programs.size() << (programs.size() == 1 ? " program" : " programs") << ")\n";
  return status;
}

const Registration registration([](CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ReportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "report", "Write one self-contained HTML page (opens offline) with charts of power and "
                "MRR over time, energy per operation and component, and the comparison of "
                "several programs");
  cmd->add_option("files", options->files, "NC programs (one or more)")->required();
  add_estimate_settings(*cmd, options->settings);
  cmd->add_option("-o,--output", options->output, "HTML file to write (default: report.html)");
  CLI::Option* log =
      cmd->add_option(
             "--log", options->logs.logs,
             "Controller log of runs of the programs (SHDR or an agent's Streams document; "
             "repeat for several): the measured runs are drawn over the prediction")
          ->check(CLI::ExistingFile);
  add_log_options(*cmd, options->logs);
  for (const char* name : {"--devices", "--log-mapping", "--device", "--line-numbering"})
    cmd->get_option(name)->needs(log);
  cmd->footer(
      "Exit codes: 0 written; 1 bad command line; 2 a program, the profile or a --log "
      "cannot be read or estimated (no page is written when a program has no numbers); 3 the "
      "page could not be written (an existing file is left as it was); 5 a work budget "
      "(--max-moves, --max-path-samples, --max-removal-work) stopped the run: no page.");
  cmd->callback([options, &exit_code] { exit_code = run_report(*options); });
});

} // namespace
} // namespace ncjoule::cli
