// What `compare` and `report` share: the options that say how to estimate (machine, stock,
// dialect, removal, prices) and estimating several programs in a row behind a progress bar.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "ncjoule/estimate.hpp"
#include "ncjoule/machine.hpp"

namespace ncjoule::cli {

struct EstimateSettings {
  std::string machine;
  std::string dialect;
  std::string stock; // "box:..." or an STL file; empty: the box of the cutting moves
  std::string engine = "dexel";
  double grid_mm = 0;
  bool no_removal = false;
  std::optional<double> co2_kg_per_kwh, price_per_kwh;
};

// Adds --machine, --dialect, --stock, --engine, --grid, --no-removal, --co2, --price.
void add_estimate_settings(CLI::App& cmd, EstimateSettings& settings);

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
