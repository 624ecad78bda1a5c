#include "multi_estimate.hpp"

#include <iostream>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "ncjoule/profile.hpp"
#include "progress.hpp"

namespace ncjoule::cli {

int estimate_files(const std::vector<std::string>& files, const EstimateSettings& s,
                   MachineProfile& machine, std::vector<EstimatedProgram>& programs) {
  int status = kOk;
  // One machine for all: the first program's job file may name it.
  if (!load_machine(s, machine, files.empty() ? std::string() : files.front())) return kInputError;

  // Read everything first, so that a missing file or a bad setting is reported before minutes of
  // estimating. Each program has its options: its own job and stock files.
  std::vector<SourceFile> sources;
  std::vector<EstimateOptions> options;
  for (const std::string& file : files) {
    auto these = estimate_options(s, file, machine, status);
    if (!these) return status;
    options.push_back(std::move(*these));
    auto source = read_source(file, input_limit_bytes(s), memory_budget_bytes(s));
    if (!source) return kInputError;
    sources.push_back(std::move(*source));
  }
  ProgressBar progress("estimating", sources.size());
  for (std::size_t i = 0; i < sources.size(); ++i) {
    progress.begin(i, sources[i].path);
    EstimateOptions with_progress = options[i];
    with_progress.progress = progress.callback();
    Estimate e = estimate_program(sources[i], machine, with_progress);
    programs.push_back({std::move(sources[i]), std::move(e)});
  }
  progress.finish();
  for (const EstimatedProgram& p : programs) {
    print_diagnostics(p.estimate.diagnostics, p.estimate.diagnostics_dropped);
    bool error = p.estimate.failed;
    for (const Diagnostic& d : p.estimate.diagnostics)
      error = error || d.severity == Severity::Error;
    if (p.estimate.failed)
      std::cerr << "ncjoule: " << p.source.path << " cannot be estimated (see above)"
                << (p.estimate.removal_failed ? "; --no-removal estimates it without the "
                                                "material removal stage"
                                              : "")
                << '\n';
    if (p.estimate.budget_exceeded)
      status = kBudgetExceeded;
    else if (error && status != kBudgetExceeded)
      status = kInputError;
  }
  return status;
}

} // namespace ncjoule::cli
