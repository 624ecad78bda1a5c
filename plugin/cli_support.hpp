// Small helpers the subcommands share: reading input files, reporting diagnostics.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::cli {

// Reads a file ("-" = standard input) into a SourceFile; prints why on failure.
std::optional<SourceFile> read_source(const std::string& path);

// Prints diagnostics to stderr, one per line, in file:line:column form.
// Prints each on its own line (control bytes escaped), then how many were left out.
void print_diagnostics(const std::vector<Diagnostic>& diagnostics, std::size_t dropped = 0);

// Looks up a dialect by name, or prints the known names and returns nullopt.
std::optional<Dialect> dialect_from_option(const std::string& name);

} // namespace ncjoule::cli
