// Which value of each estimating setting is used, and where it came from: the command line, a
// program's job file, the user config's section for the machine, the machine profile (or the
// base profile it starts from), the user config's shop-wide top, or ncjoule's default.
//
// Order, first found wins:
//   material, machine_rate_per_hour: command line, job file (material), config section,
//       profile, config top (the config top before the profile with override_profiles = true);
//   price_per_kwh, co2_kg_per_kwh, currency: command line, config section, config top, profile
//       (electricity is bought by the shop; every profile's own price is a stand-in);
//   dialect, tool_table, tool_units: command line, config section, config top, profile.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "estimate_settings.hpp"
#include "ncjoule/machine.hpp"
#include "user_config.hpp"

namespace ncjoule::cli {

// One setting as --show-settings prints it.
struct SourcedSetting {
  std::string name;
  std::string value; // empty: none
  std::string from;  // "command line (--material)", "profile mill.toml", ...
};

struct ResolvedSettings {
  // Empty / nullopt where the profile's own value is used (the estimate takes it from there).
  std::string material, dialect, tool_table, tool_units, currency;
  std::optional<double> price_per_kwh, machine_rate_per_hour, co2_kg_per_kwh;
  std::vector<SourcedSetting> shown; // every setting, for --show-settings
};

// The settings for estimating on `machine`. `job_path` and `job_material` are the job file's
// (empty when there is none).
ResolvedSettings resolve_settings(const EstimateSettings& given, const UserConfig& config,
                                  const MachineProfile& machine, const std::string& job_path,
                                  const std::string& job_material);

// The settings estimate_options (estimate_settings.hpp) uses for `program` on `machine`, each
// with where it came from (--show-settings); nullopt (exit_code set) when a setting is bad.
std::optional<ResolvedSettings> settings_for(const EstimateSettings& settings,
                                             const std::string& program,
                                             const MachineProfile& machine, int& exit_code);

// Prints every setting for `program` with where it came from: the machine, the settings above,
// the stock's candidates, then each value of the profile with its file.
void print_settings(const std::string& program, const MachineProfile& machine,
                    const std::string& machine_from, const ResolvedSettings& settings);

// Where a profile value comes from: "profile FILE" or "base profile FILE".
std::string profile_value_source(const MachineProfile& machine, const std::string& key);

} // namespace ncjoule::cli
