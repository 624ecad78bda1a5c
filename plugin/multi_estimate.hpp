// What `compare` and `report` share: the options that say how to estimate (machine, stock,
// dialect, removal, prices) and estimating several programs in a row behind a progress bar.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "estimate_settings.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/machine.hpp"

namespace ncjoule::cli {

struct EstimatedProgram {
  SourceFile source;
  Estimate estimate;
};

// Loads the machine profile and estimates every file in order. Prints diagnostics and why a
// program cannot be estimated on stderr; returns an exit code (kOk when every program has
// numbers to show) and leaves the results in `programs`.
int estimate_files(const std::vector<std::string>& files, const EstimateSettings& settings,
                   MachineProfile& machine, std::vector<EstimatedProgram>& programs);

} // namespace ncjoule::cli
