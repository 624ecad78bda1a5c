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
//       override_profiles = false        # true: the top's material and rate win over a profile's
//       [machines."haas-vf2"]            # one machine's own: material, tool_table, tool_units,
//       machine_rate_per_hour = 95       # dialect and the costs above
//   PROGRAM.ncjoule.toml next to PROGRAM.nc: a job file (stock, material, [[tool]] entries)
//   PROGRAM.stock next to PROGRAM.nc: one stock, as --stock takes it
//
// Which wins (setting_sources.hpp): the command line, then a program's own files, then the
// config's section for the machine, then the machine profile's own material and rate over the
// config's shop-wide ones (unless override_profiles); the config's shop-wide electricity price,
// CO2 and currency win over the profile's (the shop buys the electricity).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::cli {

// What a user config gives for estimating, shop-wide at its top or for one machine.
struct ConfigSettings {
  std::string material, tool_table, tool_units, dialect, currency;
  // The shop's costs: --price, --machine-rate and --co2 override them.
  std::optional<double> price_per_kwh, machine_rate_per_hour, co2_kg_per_kwh;
};

// A [machines."NAME"] section: the settings of the machine whose profile's file is NAME.toml
// (or whose profile is named NAME), any case.
struct MachineSection : ConfigSettings {
  std::string name; // as written
  int line = 0;     // of the section's header
};

struct UserConfig : ConfigSettings {
  std::string path; // the file read; empty when there is none
  std::string machine, stock;
  TextOrigin stock_origin; // where `stock` is written, for its diagnostics
  // The work budgets (shop-wide only); the command line's --max-moves, ... override them.
  std::optional<double> max_moves, max_path_samples, max_removal_work;
  // The top's material and machine rate win over a profile's own (not only fill in for it).
  bool override_profiles = false;
  std::map<std::string, MachineSection> machines; // by lower-case name
};

// The section of `config` for the profile read from `profile_path` named `profile_name`: by the
// file's stem, else by the profile's name (any case); null when there is none.
const MachineSection* machine_section(const UserConfig& config, const std::string& profile_path,
                                      const std::string& profile_name);

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
