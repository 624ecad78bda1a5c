// Small helpers the subcommands share: reading input files, reporting diagnostics.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "ncjoule/estimate.hpp"
#include "ncjoule/gcode.hpp"
#include "ncjoule/text_file.hpp"

namespace ncjoule::cli {

// Reads a file ("-" = standard input) into a SourceFile; prints why on failure. A file larger
// than `max_bytes`, or one whose lines would need more than `memory_budget` bytes to estimate
// (estimated_program_memory; 0: not checked), is refused before its lines are split.
std::optional<SourceFile> read_source(const std::string& path,
                                      std::size_t max_bytes = kDefaultMaxProgramBytes,
                                      std::size_t memory_budget = 0);

// Prints diagnostics to stderr, one per line, in file:line:column form.
// Prints each on its own line (control bytes escaped), then how many were left out.
void print_diagnostics(const std::vector<Diagnostic>& diagnostics, std::size_t dropped = 0);

// The exit status of an estimate that failed: kBudgetExceeded when a work budget stopped it
// (the program may be fine), else kInputError.
int failed_status(const Estimate& e);

// Looks up a dialect by name, or prints the known names and returns nullopt.
std::optional<Dialect> dialect_from_option(const std::string& name);

} // namespace ncjoule::cli
