// Settings a user gives once: the user config file and the files that sit next to a program.
//
//   ~/.config/ncjoule/config.toml ($XDG_CONFIG_HOME, or the file $NCJOULE_CONFIG names):
//       machine = "profiles/mill.toml"   # relative paths are relative to the config's folder
//       material = "aluminium-alloy"
//       tool_table = "/home/me/linuxcnc/tool.tbl"
//       tool_units = "mm"
//       stock = "box:0,0,-20,100,60,0"   # or an STL file
//       dialect = "auto"
//       price_per_kwh = 0.21             # the shop's costs: electricity, in `currency`,
//       machine_rate_per_hour = 85       # the machine's time (depreciation, space, operator)
//       currency = "EUR"                 # the two above are in it (default: the profile's)
//       co2_kg_per_kwh = 0.35            # the shop's electricity mix
//       max_moves = 20000000             # the work budgets (--max-moves, --max-path-samples,
//       max_path_samples = 100000000     # --max-removal-work): a run that passes one stops,
//       max_removal_work = 2e10          # exit 5
//   PROGRAM.ncjoule.toml next to PROGRAM.nc: a job file (stock, material, [[tool]] entries)
//   PROGRAM.stock next to PROGRAM.nc: one stock, as --stock takes it
//
// The command line wins over a program's own files, which win over the user config, which wins
// over the machine profile.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::cli {

struct UserConfig {
  std::string path; // the file read; empty when there is none
  std::string machine, material, tool_table, tool_units, stock, dialect, currency;
  // The shop's costs: each overrides the machine profile's, and --price, --machine-rate and
  // --co2 override them.
  std::optional<double> price_per_kwh, machine_rate_per_hour, co2_kg_per_kwh;
  // The work budgets; the command line's --max-moves, ... override them.
  std::optional<double> max_moves, max_path_samples, max_removal_work;
  TextOrigin stock_origin; // where `stock` is written, for its diagnostics
};

// Where the user config is looked for (whether or not it exists).
std::string user_config_path();

// Parses the text of a user config that lives at `path`; errors (file, line, column, key) go to
// `diagnostics` and give std::nullopt; unknown keys are warnings.
std::optional<UserConfig> parse_user_config(std::string_view text, const std::string& path,
                                            std::vector<Diagnostic>& diagnostics);

// The user config, read once; an empty one when there is no file. Prints what is wrong and gives
// std::nullopt when the file cannot be used.
const std::optional<UserConfig>& user_config();

// The job file and the stock file that belong to a program ("part.nc" -> "part.ncjoule.toml",
// "part.stock"), when they exist; empty strings otherwise, and for standard input.
std::string program_job_file(const std::string& program);
std::string program_stock_file(const std::string& program);

// The machine profile used when neither the command line nor the user config names one: the
// generic 3-axis profile installed with ncjoule (share/ncjoule/machines), or the source tree's
// when ncjoule runs from its build folder. Empty when none is found.
std::string default_machine_profile();

// Folders where installed machine profiles are looked for, in order.
std::vector<std::string> machine_profile_dirs();

// The shipped profiles (file stem -> path), from the first folder that holds each name.
std::map<std::string, std::string> shipped_profiles();

// What --machine names: a file that exists, else a shipped profile by its file's stem
// ("haas-vf2", any case) or the one stem it begins ("haas-vf0" -> haas-vf0-pavanaskar2014).
// The path as given when nothing matches (the reader then says it cannot be opened).
std::string resolve_machine(const std::string& name);

} // namespace ncjoule::cli
