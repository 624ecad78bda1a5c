// `ncjoule calibrate --timing`: the timing keys of a base profile fitted to a machine's own
// MTConnect logs of the programs it ran, and the calibrated profile written. The calibrate
// command (commands/calibrate.cpp) adds these options and hands over when --timing is given.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "controller_logs_cli.hpp"

namespace ncjoule::cli {

struct TimingCalibrationOptions {
  bool on = false;                   // --timing
  LogOptions logs;                   // --log (set by calibrate) and the log options
  std::vector<std::string> programs; // --program (set by calibrate)
  std::string machine;               // -m: the base profile (a .toml file)
  std::string name, output, dialect;
};

// Adds --timing and the log options (--devices, --log-mapping, --device, --line-numbering).
void add_timing_options(CLI::App& cmd, TimingCalibrationOptions& options);

int run_timing_calibration(const TimingCalibrationOptions& options);

} // namespace ncjoule::cli
