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

namespace ncjoule::cli {
namespace {

struct ReportOptions {
  std::vector<std::string> files;
  EstimateSettings settings;
  std::string output = "report.html";
};

// Writes `text` next to `path` under a temporary name, then renames it over `path`: readers see
// the old file or the whole new one, never a part.
bool write_atomically(const std::string& path, const std::string& text, std::string* error) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string pattern = (dir / ("." + target.filename().string() + ".XXXXXX")).string();
  const int fd = mkstemp(pattern.data());
  if (fd < 0) {
    *error = std::string("cannot create a file in ") + dir.string() + ": " + std::strerror(errno);
    return false;
  }
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      *error = std::string("cannot write ") + path + ": " + std::strerror(errno);
      ::close(fd);
      ::unlink(pattern.c_str());
      return false;
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    *error = std::string("cannot write ") + path + ": " + std::strerror(errno);
    ::unlink(pattern.c_str());
    return false;
  }
  ::chmod(pattern.c_str(), 0644); // mkstemp makes it 0600; a report is meant to be shared
  if (std::rename(pattern.c_str(), path.c_str()) != 0) {
    *error = std::string("cannot replace ") + path + ": " + std::strerror(errno);
    ::unlink(pattern.c_str());
    return false;
  }
  return true;
}

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
  std::string error;
  if (!write_atomically(o.output, html, &error)) {
    std::cerr << "ncjoule: " << error << '\n';
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
