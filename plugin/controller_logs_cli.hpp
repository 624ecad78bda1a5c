// What `ncjoule check-log` and `ncjoule calibrate --timing` share: the options that say how to
// read a controller's logs, reading them with the programs into LogEvidence, and the tables that
// say what the logs hold and how the machine's times compare with a prediction.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "ncjoule/calibrate_timing.hpp"

namespace ncjoule::cli {

struct LogOptions {
  std::vector<std::string> logs;
  std::string devices;        // the agent's device file
  std::string mapping;        // a mapping file
  std::string device;         // read only this device
  std::string line_numbering; // auto, file-line, file-line-from-zero, n-word
};

// Adds --devices, --log-mapping, --device and --line-numbering (the command adds --log).
void add_log_options(CLI::App& cmd, LogOptions& options);

// Reads the logs and the programs, aligns the runs and judges them, planning every program with
// runs on `machine` (`times`: one per program). Prints the problems found; kOk or an exit code.
int read_evidence(const LogOptions& options, const std::vector<std::string>& programs,
                  const EstimateOptions& estimate_options, const MachineProfile& machine,
                  LogEvidence& evidence, std::vector<LineTimes>& times);

// What was read: files, devices, items used, runs found and the programs' runs.
void print_log_summary(const LogEvidence& evidence);
// One row per run of a program given: when, how long, how it ended, overrides, usable or why not.
void print_run_table(const LogEvidence& evidence);
// Per program: totals, operations and the worst stretches, measured against predicted.
void print_program_checks(const LogEvidence& evidence, const std::vector<ProgramCheck>& checks);
// For `ncjoule report --log`: the logs read with the programs and checked as check-log checks
// them (`dialect` as its --dialect), one overlay per program, in order; kOk or an exit code.
int measured_overlays(const LogOptions& options, const std::vector<std::string>& programs,
                      const std::string& dialect, const MachineProfile& machine,
                      std::vector<MeasuredOverlay>& overlays);
// The same as one JSON document (docs/controller-logs.md): the runs and the checks.
std::string check_json(const LogEvidence& evidence, const std::vector<ProgramCheck>& checks,
                       const MachineProfile& machine);

} // namespace ncjoule::cli
