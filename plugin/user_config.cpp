#include "user_config.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <toml++/toml.h>

#include "cli_support.hpp"
#include "platform.hpp"

#include "ncjoule/text.hpp"
#include "ncjoule/text_file.hpp"

namespace ncjoule::cli {
namespace {

namespace fs = std::filesystem;

std::string env(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

using platform::path_from_utf8;
using platform::utf8_from_path;

// A path from a file, relative to that file's folder.
std::string relative_to(const std::string& file, const std::string& path) {
  if (path.empty() || path_from_utf8(path).is_absolute()) return path;
  return utf8_from_path(
      (path_from_utf8(file).parent_path() / path_from_utf8(path)).lexically_normal());
}

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

bool is_file(const std::string& p) {
  return is_file(path_from_utf8(p));
}

// The folder ncjoule runs from, empty when it cannot be told.
fs::path program_folder() {
  return platform::program_file().parent_path();
}

} // namespace

std::string user_config_path() {
  if (const char* named = std::getenv("NCJOULE_CONFIG")) return named;
  const std::string folder = platform::user_config_folder();
  if (folder.empty()) return {};
#ifdef _WIN32
  return folder + "\\config.toml";
#else
  return folder + "/config.toml";
#endif
}

namespace {

// The keys a machine's section takes; the top takes these and machine, stock and
// override_profiles.
constexpr const char* kSectionKeys = "material, tool_table, tool_units, dialect, price_per_kwh, "
                                     "machine_rate_per_hour, currency, co2_kg_per_kwh";

// Reads one key of `table` into `out` when it is a setting of ConfigSettings; false when the key
// is none of them. Errors go to `diagnostics` and set `failed`.
bool read_setting(const std::string& name, const toml::node& node, const std::string& path,
                  ConfigSettings& out, std::vector<Diagnostic>& diagnostics, bool& failed) {
  const auto where = node.source().begin;
  struct Key {
    const char* name;
    std::string ConfigSettings::*field;
    bool is_path;
  };
  static const Key keys[] = {{"material", &ConfigSettings::material, false},
                             {"tool_table", &ConfigSettings::tool_table, true},
                             {"tool_units", &ConfigSettings::tool_units, false},
                             {"dialect", &ConfigSettings::dialect, false},
                             {"currency", &ConfigSettings::currency, false}};
  // The shop's costs, numbers with the range the command line's options take.
  struct NumberKey {
    const char* name;
    std::optional<double> ConfigSettings::*field;
    double max;
  };
  static const NumberKey number_keys[] = {
      {"price_per_kwh", &ConfigSettings::price_per_kwh, 1e6},
      {"machine_rate_per_hour", &ConfigSettings::machine_rate_per_hour, 1e7},
      {"co2_kg_per_kwh", &ConfigSettings::co2_kg_per_kwh, 100}};
  for (const NumberKey& k : number_keys) {
    if (name != k.name) continue;
    const std::optional<double> value = node.value<double>(); // an integer is taken too
    if (!value || !std::isfinite(*value) || *value < 0 || *value > k.max) {
      char text[160];
      std::snprintf(text, sizeof text, "%s: must be a number from 0 to %g", k.name, k.max);
      diagnostics.push_back({Severity::Error, path, int(where.line), int(where.column), text});
      failed = true;
    } else {
      out.*(k.field) = *value;
    }
    return true;
  }
  for (const Key& k : keys) {
    if (name != k.name) continue;
    if (!node.is_string() || node.value<std::string>()->empty()) {
      diagnostics.push_back({Severity::Error, path, int(where.line), int(where.column),
                             std::string(k.name) + ": must be a non-empty string"});
      failed = true;
      return true;
    }
    std::string value = *node.value<std::string>();
    if (k.field == &ConfigSettings::tool_units && value != "mm" && value != "inch") {
      diagnostics.push_back({Severity::Error, path, int(where.line), int(where.column),
                             "tool_units: must be \"mm\" or \"inch\""});
      failed = true;
      return true;
    }
    out.*(k.field) = k.is_path ? relative_to(path, value) : value;
    return true;
  }
  return false;
}

// The work budgets, shop-wide only: numbers from 1 with the range the command line's options
// take. False when the key is none of them.
bool read_budget(const std::string& name, const toml::node& node, const std::string& path,
                 UserConfig& config, std::vector<Diagnostic>& diagnostics, bool& failed) {
  struct BudgetKey {
    const char* name;
    std::optional<double> UserConfig::*field;
    double max;
  };
  static const BudgetKey keys[] = {{"max_moves", &UserConfig::max_moves, 1e15},
                                   {"max_path_samples", &UserConfig::max_path_samples, 1e15},
                                   {"max_removal_work", &UserConfig::max_removal_work, 1e18}};
  for (const BudgetKey& k : keys) {
    if (name != k.name) continue;
    const std::optional<double> value = node.value<double>(); // an integer is taken too
    if (!value || !std::isfinite(*value) || *value < 1 || *value > k.max) {
      const auto where = node.source().begin;
      char text[160];
      std::snprintf(text, sizeof text, "%s: must be a number from 1 to %g", k.name, k.max);
      diagnostics.push_back({Severity::Error, path, int(where.line), int(where.column), text});
      failed = true;
    } else {
      config.*(k.field) = *value;
    }
    return true;
  }
  return false;
}

// The [machines."NAME"] sections.
void read_machine_sections(const toml::node& node, const std::string& path, UserConfig& config,
                           std::vector<Diagnostic>& diagnostics, bool& failed) {
  const auto where = node.source().begin;
  const toml::table* sections = node.as_table();
  if (!sections) {
    diagnostics.push_back({Severity::Error, path, int(where.line), int(where.column),
                           "machines: must be tables, one per machine: [machines.\"haas-vf2\"]"});
    failed = true;
    return;
  }
  for (const auto& [name, section_node] : *sections) {
    const auto at = section_node.source().begin;
    const toml::table* section = section_node.as_table();
    if (!section) {
      diagnostics.push_back({Severity::Error, path, int(at.line), int(at.column),
                             "machines." + std::string(name.str()) +
                                 ": must be a table of that machine's settings (" + kSectionKeys +
                                 ")"});
      failed = true;
      continue;
    }
    MachineSection machine;
    machine.name = std::string(name.str());
    machine.line = int(at.line);
    for (const auto& [key, value] : *section)
      if (!read_setting(std::string(key.str()), value, path, machine, diagnostics, failed)) {
        const auto key_at = value.source().begin;
        diagnostics.push_back({Severity::Warning, path, int(key_at.line), int(key_at.column),
                               "machines." + machine.name + "." + std::string(key.str()) +
                                   ": unknown key, ignored (a machine's section takes " +
                                   kSectionKeys + ")"});
      }
    config.machines[to_lower(machine.name)] = std::move(machine);
  }
}

} // namespace

std::optional<UserConfig> parse_user_config(std::string_view text, const std::string& path,
                                            std::vector<Diagnostic>& diagnostics) {
  toml::table document;
  try {
    document = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    diagnostics.push_back({Severity::Error, path, int(where.line), int(where.column),
                           "not valid TOML: " + std::string(e.description())});
    return std::nullopt;
  }
  UserConfig config;
  config.path = path;
  bool failed = false;
  for (const auto& [key, node] : document) {
    const std::string name(key.str());
    const auto where = node.source().begin;
    if (read_setting(name, node, path, config, diagnostics, failed)) continue;
    if (name == "machines") {
      read_machine_sections(node, path, config, diagnostics, failed);
      continue;
    }
    if (read_budget(name, node, path, config, diagnostics, failed)) continue;
    if (name == "override_profiles") {
      if (!node.is_boolean()) {
        diagnostics.push_back({Severity::Error, path, int(where.line), int(where.column),
                               "override_profiles: must be true or false"});
        failed = true;
      } else {
        config.override_profiles = *node.value<bool>();
      }
      continue;
    }
    if (name != "machine" && name != "stock") {
      diagnostics.push_back({Severity::Warning, path, int(where.line), int(where.column),
                             name + ": unknown key, ignored (known: machine, stock, " +
                                 kSectionKeys +
                                 ", max_moves, max_path_samples, max_removal_work, "
                                 "override_profiles, [machines.\"NAME\"])"});
      continue;
    }
    if (!node.is_string() || node.value<std::string>()->empty()) {
      diagnostics.push_back({Severity::Error, path, int(where.line), int(where.column),
                             name + ": must be a non-empty string" +
                                 (name == "machine" && node.is_table()
                                      ? " (one machine's own settings go in [machines.\"NAME\"])"
                                      : "")});
      failed = true;
      continue;
    }
    std::string value = *node.value<std::string>();
    if (name == "machine") {
      // A machine named by a shipped profile's name ("haas-vf2") stays a name for -m's lookup;
      // a file beside the config, or a path, is a path.
      const bool bare_name =
          value.find_first_of("/\\") == std::string::npos && !is_file(relative_to(path, value));
      config.machine = bare_name ? value : relative_to(path, value);
    } else {
      // The value's first character is just after the opening quote.
      config.stock_origin = {path, int(where.line), int(where.column) + 1};
      config.stock = value.rfind("box:", 0) == 0 ? value : relative_to(path, value); // an STL
    }
  }
  if (failed) return std::nullopt;
  return config;
}

const MachineSection* machine_section(const UserConfig& config, const std::string& profile_path,
                                      const std::string& profile_name) {
  if (config.machines.empty()) return nullptr;
  const std::string stem = to_lower(utf8_from_path(path_from_utf8(profile_path).stem()));
  if (auto it = config.machines.find(stem); it != config.machines.end()) return &it->second;
  if (auto it = config.machines.find(to_lower(profile_name)); it != config.machines.end())
    return &it->second;
  return nullptr;
}

const std::optional<UserConfig>& user_config() {
  static const std::optional<UserConfig> config = []() -> std::optional<UserConfig> {
    const std::string path = user_config_path();
    // The usual places may hold nothing; a file NCJOULE_CONFIG names is read whatever it is (a
    // device too, within the settings files' size limit), so that a wrong one is said.
    const bool named = std::getenv("NCJOULE_CONFIG") != nullptr;
    std::error_code ec;
    if (path.empty() || (named ? !fs::exists(path_from_utf8(path), ec) : !is_file(path)))
      return UserConfig{};
    std::vector<Diagnostic> diagnostics;
    const std::optional<std::string> text =
        read_text_file(path, "a user config (TOML)", diagnostics);
    auto parsed = text ? parse_user_config(*text, path, diagnostics) : std::nullopt;
    print_diagnostics(diagnostics);
    if (!parsed)
      std::cerr << "ncjoule: fix " << path << " (or point NCJOULE_CONFIG at another file)\n";
    return parsed;
  }();
  return config;
}

std::string program_job_file(const std::string& program) {
  if (program.empty() || program == "-") return {};
  fs::path job = path_from_utf8(program);
  job.replace_extension(".ncjoule.toml");
  return is_file(job) ? utf8_from_path(job) : std::string();
}

std::string program_stock_file(const std::string& program) {
  if (program.empty() || program == "-") return {};
  fs::path stock = path_from_utf8(program);
  stock.replace_extension(".stock");
  return is_file(stock) ? utf8_from_path(stock) : std::string();
}

std::vector<std::string> machine_profile_dirs() {
  std::vector<std::string> dirs;
  if (const std::string data = env("NCJOULE_DATA_DIR"); !data.empty())
    dirs.push_back(data + "/machines");
  const fs::path here = program_folder();
  if (!here.empty())
    dirs.push_back(utf8_from_path(here.parent_path() / "share" / "ncjoule" / "machines"));
#ifdef NCJOULE_SOURCE_MACHINES_DIR
  dirs.push_back(NCJOULE_SOURCE_MACHINES_DIR); // running from the build folder
#endif
  return dirs;
}

std::map<std::string, std::string> shipped_profiles() {
  std::map<std::string, std::string> found;
  for (const std::string& dir : machine_profile_dirs()) {
    std::error_code ec;
    for (fs::directory_iterator it(path_from_utf8(dir), ec), end; !ec && it != end;
         it.increment(ec))
      if (it->path().extension() == ".toml" && it->is_regular_file(ec))
        found.emplace(utf8_from_path(it->path().stem()), utf8_from_path(it->path()));
  }
  return found;
}

std::string resolve_machine(const std::string& name) {
  std::error_code ec;
  if (name.empty() || fs::exists(path_from_utf8(name), ec) || name.find('/') != std::string::npos ||
      name.find('\\') != std::string::npos)
    return name;
  std::string wanted = to_lower(name);
  if (wanted.size() > 5 && wanted.compare(wanted.size() - 5, 5, ".toml") == 0)
    wanted.resize(wanted.size() - 5);
  const auto shipped = shipped_profiles();
  std::vector<std::string> starting;
  for (const auto& [stem, path] : shipped) {
    const std::string low = to_lower(stem);
    if (low == wanted) return path;
    if (low.rfind(wanted, 0) == 0) starting.push_back(path);
  }
  return starting.size() == 1 ? starting.front() : name;
}

std::string default_machine_profile() {
  for (const std::string& dir : machine_profile_dirs())
    if (is_file(dir + "/generic-3axis.toml")) return dir + "/generic-3axis.toml";
  return {};
}

} // namespace ncjoule::cli
