// The options that say how to estimate (machine, dialect, stock, tools, removal, prices), shared
// by every command that runs the pipeline: estimate, annotate, compare and report.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "ncjoule/estimate.hpp"
#include "ncjoule/machine.hpp"
#include "ncjoule/text_file.hpp"

namespace ncjoule::cli {

struct EstimateSettings {
  std::string machine;
  std::string dialect;
  std::string stock;              // "box:..." or an STL file; empty: the box of the cutting moves
  std::string stock_from;         // --stock-from: the CAM hook that passed --stock (fusion360, ...)
  std::string job;                // job file (TOML): stock and tool table
  std::vector<std::string> tools; // --tool N:TYPE:D[...], repeatable
  std::string tool_table;         // LinuxCNC .tbl
  std::string material;           // workpiece material; empty: the job file's, else the profile's
  std::string tool_units;         // units of the tool table: "mm" (empty) or "inch"
  std::vector<std::string> macro_dirs; // --macro-dir: folders of the control's programs
  std::string engine = "dexel";
  double grid_mm = 0;
  double memory_limit_mib = 0; // 0: default_memory_budget_bytes()
  double input_limit_mib = double(kDefaultMaxProgramBytes >> 20);
  bool no_removal = false;
  // The work budgets (ncjoule/budget.hpp): --max-moves, --max-path-samples, --max-removal-work,
  // else the user config's max_moves, max_path_samples, max_removal_work, else the defaults.
  std::optional<double> max_moves, max_path_samples, max_removal_work;
  std::optional<double> co2_kg_per_kwh, price_per_kwh, machine_rate_per_hour;
  std::string currency; // of the price and the rate; empty: the profile's
  // Filled in by estimate_options from the program's .stock file and the user config.
  std::string program_stock, config_stock;
  TextOrigin program_stock_origin, config_stock_origin; // where those two stocks are written
};

// Adds --machine, --dialect, --stock, --stock-from, --job, --tool, --tool-table, --tool-units,
// --macro-dir,
// --engine,
// --grid, --no-removal, --co2 and --price to a subcommand.
void add_estimate_settings(CLI::App& cmd, EstimateSettings& settings);

// The memory budget and the input limit the settings give, in bytes.
std::size_t memory_budget_bytes(const EstimateSettings& settings);
std::size_t input_limit_bytes(const EstimateSettings& settings);

// Loads the machine profile: --machine, else the one the job file of `program` names (--job, or
// PROGRAM.ncjoule.toml), else the user config's, else the generic one (with a note); prints why
// and returns false when it is wrong.
// `from`, when given, receives where the machine was named.
bool load_machine(const EstimateSettings& settings, MachineProfile& machine,
                  const std::string& program = "", std::string* from = nullptr);

// The pipeline's options for one program ("-": standard input) from the settings, completed from
// the program's own files and the user config (user_config.hpp). Tools: the job file's, then the
// command line's, each replacing the one before (and the program's header comments) for the same
// number; a project beside the program (projects.hpp) adds the tools it describes under them.
// Stock: --stock, the job file's, PROGRAM.stock, a project beside the program, the user config's
// (docs/stock.md). On a bad setting it
// prints why, sets `exit_code` and returns nullopt.
// The machine (load_machine) decides which section of the user config applies and which of its
// own values win (setting_sources.hpp).
std::optional<EstimateOptions> estimate_options(const EstimateSettings& settings,
                                                const std::string& program,
                                                const MachineProfile& machine, int& exit_code);

} // namespace ncjoule::cli
