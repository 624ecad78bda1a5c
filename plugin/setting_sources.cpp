#include "setting_sources.hpp"

#include <cstdio>

#include "ncjoule/diagnostic.hpp"

namespace ncjoule::cli {
namespace {

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// One candidate for a setting: its value (empty: it gives none) and where it is written.
struct Candidate {
  std::optional<std::string> value;
  std::string from;
};

std::optional<std::string> text_of(const std::string& value) {
  return value.empty() ? std::nullopt : std::optional<std::string>(value);
}

std::optional<std::string> text_of(const std::optional<double>& value) {
  return value ? std::optional<std::string>(number_text(*value)) : std::nullopt;
}

// The profile's own value of `key` as written (a string without its quotes).
std::optional<std::string> profile_text(const MachineProfile& machine, const std::string& key) {
  const auto it = machine.values.find(key);
  if (it == machine.values.end()) return std::nullopt;
  std::string text = it->second.text;
  if (text.size() >= 2 && text.front() == '"' && text.back() == '"')
    text = text.substr(1, text.size() - 2);
  return text;
}

} // namespace

std::string profile_value_source(const MachineProfile& machine, const std::string& key) {
  const auto it = machine.values.find(key);
  if (it == machine.values.end()) return "default";
  const bool own = it->second.file == machine.source_path;
  return std::string(own ? "profile " : "base profile ") + it->second.file + ":" +
         std::to_string(it->second.line);
}

ResolvedSettings resolve_settings(const EstimateSettings& given, const UserConfig& config,
                                  const MachineProfile& machine, const std::string& job_path,
                                  const std::string& job_material) {
  const MachineSection* section = machine_section(config, machine.source_path, machine.name);
  const std::string section_from =
      section ? "user config " + config.path + " [machines.\"" + section->name + "\"]" : "";
  const std::string top_from = "user config " + config.path + " (shop-wide)";
  const ConfigSettings none;
  const ConfigSettings& in_section = section ? *section : none;
  ResolvedSettings out;

  // The first candidate with a value wins; `profile_key` marks the one that is the profile's
  // own (the estimate takes it from the profile: nothing is set).
  auto pick = [&](const std::string& name, std::vector<Candidate> candidates,
                  const std::string& profile_key, const std::string& fallback) -> std::string {
    for (const Candidate& c : candidates) {
      if (!c.value) continue;
      const bool from_profile = c.from == "profile";
      out.shown.push_back(
          {name, *c.value, from_profile ? profile_value_source(machine, profile_key) : c.from});
      return from_profile ? std::string() : *c.value;
    }
    out.shown.push_back({name, fallback, "default"});
    return {};
  };
  auto profile_candidate = [&](const std::string& key) {
    return Candidate{profile_text(machine, key), "profile"};
  };

  // The machine's own values before the shop-wide ones, unless the config asks otherwise.
  auto own_first = [&](Candidate profile, Candidate top) {
    return config.override_profiles ? std::vector<Candidate>{top, profile}
                                    : std::vector<Candidate>{profile, top};
  };
  auto join = [](std::vector<Candidate> head, const std::vector<Candidate>& tail) {
    head.insert(head.end(), tail.begin(), tail.end());
    return head;
  };

  out.material = pick(
      "material",
      join({{text_of(given.material), "command line (--material)"},
            {text_of(job_material), "job file " + job_path},
            {text_of(in_section.material), section_from}},
           own_first(profile_candidate("power.material"), {text_of(config.material), top_from})),
      "power.material", "none (the profile's cutting term is fitted)");
  const std::string rate =
      pick("machine_rate_per_hour",
           join({{text_of(given.machine_rate_per_hour), "command line (--machine-rate)"},
                 {text_of(in_section.machine_rate_per_hour), section_from}},
                own_first(profile_candidate("power.machine_rate_per_hour"),
                          {text_of(config.machine_rate_per_hour), top_from})),
           "power.machine_rate_per_hour", "0 (machine time not costed)");
  if (!rate.empty()) out.machine_rate_per_hour = std::stod(rate);
  const std::string price = pick("price_per_kwh",
                                 {{text_of(given.price_per_kwh), "command line (--price)"},
                                  {text_of(in_section.price_per_kwh), section_from},
                                  {text_of(config.price_per_kwh), top_from},
                                  profile_candidate("power.price_per_kwh")},
                                 "power.price_per_kwh", "");
  if (!price.empty()) out.price_per_kwh = std::stod(price);
  const std::string co2 = pick("co2_kg_per_kwh",
                               {{text_of(given.co2_kg_per_kwh), "command line (--co2)"},
                                {text_of(in_section.co2_kg_per_kwh), section_from},
                                {text_of(config.co2_kg_per_kwh), top_from},
                                profile_candidate("power.co2_kg_per_kwh")},
                               "power.co2_kg_per_kwh", "");
  if (!co2.empty()) out.co2_kg_per_kwh = std::stod(co2);
  out.currency = pick("currency",
                      {{text_of(given.currency), "command line"},
                       {text_of(in_section.currency), section_from},
                       {text_of(config.currency), top_from},
                       profile_candidate("power.currency")},
                      "power.currency", "EUR");
  out.dialect = pick("dialect",
                     {{text_of(given.dialect), "command line (--dialect)"},
                      {text_of(in_section.dialect), section_from},
                      {text_of(config.dialect), top_from},
                      profile_candidate("dialect")},
                     "dialect", "auto (detected from the program)");
  // A tool table's units go with the table that names them.
  const bool table_given = !given.tool_table.empty();
  const bool table_in_section = !table_given && !in_section.tool_table.empty();
  out.tool_table = pick("tool_table",
                        {{text_of(given.tool_table), "command line (--tool-table)"},
                         {text_of(in_section.tool_table), section_from},
                         {text_of(config.tool_table), top_from}},
                        "", "none");
  out.tool_units = pick(
      "tool_units",
      {{text_of(given.tool_units), "command line (--tool-units)"},
       {table_given ? std::nullopt : text_of(in_section.tool_units), section_from},
       {table_given || table_in_section ? std::nullopt : text_of(config.tool_units), top_from}},
      "", "mm");
  return out;
}

void print_settings(const std::string& program, const MachineProfile& machine,
                    const std::string& machine_from, const ResolvedSettings& settings) {
  std::printf("settings for %s\n", printable(program).c_str());
  std::printf("  %-22s %-28s %s\n", "machine", printable(machine.source_path).c_str(),
              printable(machine_from).c_str());
  for (const std::string& base : machine.base_paths)
    std::printf("  %-22s %-28s %s\n", "base profile", printable(base).c_str(),
                "named by `base` in the profile above it");
  for (const SourcedSetting& s : settings.shown)
    std::printf("  %-22s %-28s %s\n", s.name.c_str(), printable(s.value).c_str(),
                printable(s.from).c_str());
  std::printf("profile values (%zu), each from its file:\n", machine.values.size());
  for (const auto& [key, value] : machine.values)
    std::printf("  %s = %s    %s\n", key.c_str(), printable(value.text).c_str(),
                printable(profile_value_source(machine, key)).c_str());
}

} // namespace ncjoule::cli
