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
  struct Key {
    const char* name;
    std::string UserConfig::*field;
    bool is_path;
  };
  static const Key keys[] = {
      {"machine", &UserConfig::machine, true},       {"material", &UserConfig::material, false},
      {"tool_table", &UserConfig::tool_table, true}, {"tool_units", &UserConfig::tool_units, false},
      {"stock", &UserConfig::stock, false},          {"dialect", &UserConfig::dialect, false},
      {"currency", &UserConfig::currency, false}};
  // The shop's costs and the work budgets: numbers with the range the command line's options
  // take (max, min).
  struct NumberKey {
    const char* name;
    std::optional<double> UserConfig::*field;
    double max, min;
  };
  static const NumberKey number_keys[] = {
      {"price_per_kwh", &UserConfig::price_per_kwh, 1e6, 0},
      {"machine_rate_per_hour", &UserConfig::machine_rate_per_hour, 1e7, 0},
      {"co2_kg_per_kwh", &UserConfig::co2_kg_per_kwh, 100, 0},
      {"max_moves", &UserConfig::max_moves, 1e15, 1},
      {"max_path_samples", &UserConfig::max_path_samples, 1e15, 1},
      {"max_removal_work", &UserConfig::max_removal_work, 1e18, 1}};
  for (const auto& [name, node] : document) {
    const auto where = node.source().begin;
    const Key* key = nullptr;
    for (const Key& k : keys)
      if (name.str() == k.name) key = &k;
    const NumberKey* number_key = nullptr;
    for (const NumberKey& k : number_keys)
      if (name.str() == k.name) number_key = &k;
    if (number_key) {
      const std::optional<double> value = node.value<double>(); // an integer is taken too
      if (!value || !std::isfinite(*value) || *value < number_key->min ||
          *value > number_key->max) {
        char text[160];
        std::snprintf(text, sizeof text, "%s: must be a number from %g to %g", number_key->name,
                      number_key->min, number_key->max);
        diagnostics.push_back({Severity::Error, path, int(where.line), int(where.column), text});
        failed = true;
        continue;
      }
      config.*(number_key->field) = *value;
      continue;
    }
    if (!key) {
      diagnostics.push_back({Severity::Warning, path, int(where.line), int(where.column),
                             std::string(name.str()) +
                                 ": unknown key, ignored (known: machine, material, tool_table, "
                                 "tool_units, stock, dialect, price_per_kwh, "
                                 "machine_rate_per_hour, currency, co2_kg_per_kwh, "
                                 "max_moves, max_path_samples, max_removal_work)"});
      continue;
    }
    if (!node.is_string() || node.value<std::string>()->empty()) {
      diagnostics.push_back({Severity::Error, path, int(where.line), int(where.column),
                             std::string(key->name) + ": must be a non-empty string"});
      failed = true;
      continue;
    }
    std::string value = *node.value<std::string>();
    // A machine named by a shipped profile's name ("haas-vf2") stays a name for -m's lookup;
    // a file beside the config, or a path, is a path.
    const bool bare_name = key->field == &UserConfig::machine &&
                           value.find_first_of("/\\") == std::string::npos &&
                           !is_file(relative_to(path, value));
    if (key->is_path && !bare_name) value = relative_to(path, value);
    if (key->field == &UserConfig::stock) {
      // The value's first character is just after the opening quote.
      config.stock_origin = {path, int(where.line), int(where.column) + 1};
      if (value.rfind("box:", 0) != 0) value = relative_to(path, value); // an STL file
    }
    if (key->field == &UserConfig::tool_units && value != "mm" && value != "inch") {
      diagnostics.push_back({Severity::Error, path, int(where.line), int(where.column),
                             "tool_units: must be \"mm\" or \"inch\""});
      failed = true;
      continue;
    }
    config.*(key->field) = value;
  }
  if (failed) return std::nullopt;
  return config;
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
