// Subcommands of the ncjoule program register themselves here: a file in commands/ defines a
// static Registration whose setup function adds a CLI11 subcommand and its callback.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <vector>

namespace ncjoule::cli {

// Exit codes of the ncjoule program (documented in the README).
enum ExitCode : int {
  kOk = 0,
  kUsage = 1,         // bad command line
  kInputError = 2,    // unreadable input, bad profile, unknown tool, program errors
  kOutputError = 3,   // could not write the output; the original is untouched
  kInternalError = 4, // a bug: please report it
  // A work budget (--max-moves, --max-path-samples, --max-removal-work) stopped the run: the
  // program may be one a control runs; nothing was written.
  kBudgetExceeded = 5
};

using SetupFunction = std::function<void(CLI::App& app, int& exit_code)>;

std::vector<SetupFunction>& registry();

struct Registration {
  explicit Registration(SetupFunction setup) { registry().push_back(std::move(setup)); }
};

} // namespace ncjoule::cli
