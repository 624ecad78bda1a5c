// `ncjoule report FILE... --machine PROFILE -o report.html`: one self-contained HTML page with
// the programs' totals, power and removal rate over time, energy per operation and component,
// and their comparison when there are several (docs/report.md).
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

#include "command_registry.hpp"
#include "multi_estimate.hpp"
#include "ncjoule/report.hpp"
#include "output_file.hpp"

namespace ncjoule::cli {
namespace {

struct ReportOptions {
  std::vector<std::string> files;
  EstimateSettings settings;
  std::string output = "report.html";
};

int run_report(const ReportOptions& o) {
  MachineProfile machine;
  std::vector<EstimatedProgram> programs;
  const int status = estimate_files(o.files, o.settings, machine, programs);
  if (status != kOk && status != kInputError) return status;
  if (programs.size() < o.files.size()) return status;
  for (const EstimatedProgram& p : programs)
    if (p.estimate.failed) return kInputError; // nothing to chart: no report is written

  std::vector<ReportProgram> inputs;
  for (const EstimatedProgram& p : programs)
    inputs.push_back({&p.source, &p.estimate});
  const std::string html = html_report(inputs, machine);
  if (const std::string error = write_output_file(o.output, html); !error.empty()) {
    std::cerr << "ncjoule: " << error << "; nothing was written\n";
    return kOutputError;
  }
  std::cerr << "ncjoule: wrote " << o.output << " (" << html.size() / 1024 << " KiB, "
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
  cmd->footer("Exit codes: 0 written; 1 bad command line; 2 a program or the profile cannot be "
              "read or estimated (no page is written when a program has no numbers); 3 the "
              "page could not be written (an existing file is left as it was).");
  cmd->callback([options, &exit_code] { exit_code = run_report(*options); });
});

} // namespace
} // namespace ncjoule::cli
