#include <filesystem>
#include <fstream>
#include <sstream>
#include <toml++/toml.h>

#include "ncjoule/profile.hpp"
#include "ncjoule/text_file.hpp"
#include "sections.hpp"
#include "table_reader.hpp"

namespace ncjoule {
namespace profile_detail {

void read_source(TableReader& table, std::string_view table_name,
                 std::vector<std::string>& sources) {
  std::string source = table.string("source");
  if (source.empty()) table.fail("source", "must say where the values come from");
  sources.push_back(std::string(table_name) + ": " + source);
}

} // namespace profile_detail

MachineProfile parse_profile(std::string_view text, const std::string& path) {
  using namespace profile_detail;
  toml::table document;
  try {
    document = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    throw ProfileError(path, "", "not valid TOML: " + std::string(e.description()), int(where.line),
                       int(where.column));
  }
  TableReader root(document, path, "");
  MachineProfile profile;
  profile.source_path = path;
  profile.name = root.string("name");
  profile.summary = root.optional_string("summary").value_or("");
  if (profile.name.empty()) root.fail("name", "must not be empty");
  std::string known;
  for (const std::string& name : dialect_names())
    known += (known.empty() ? "" : ", ") + name;
  profile.dialect = root.optional_string("dialect").value_or("auto");
  if (profile.dialect != "auto" && !find_dialect(profile.dialect))
    root.fail("dialect",
              "\"" + profile.dialect + "\" is not a dialect ncjoule knows (auto, " + known + ")");
  profile.fallback_dialect = root.optional_string("fallback_dialect").value_or("");
  if (!profile.fallback_dialect.empty() && !find_dialect(profile.fallback_dialect))
    root.fail("fallback_dialect", "\"" + profile.fallback_dialect +
                                      "\" is not a dialect ncjoule knows (" + known + ")");
  read_source(root, "profile", profile.sources);
  profile.kinematics = read_kinematics(root.table("kinematics"), profile.sources);
  if (auto setup = root.optional_table("setup"))
    profile.setup = read_setup(*setup, profile.sources);
  for (std::string& dir : profile.setup.macro_dirs) // relative to the profile's folder
    if (std::filesystem::path(dir).is_relative())
      dir = (std::filesystem::path(path).parent_path() / dir).lexically_normal().string();
  profile.power = read_power(root.table("power"), profile.sources);
  if (auto tool = root.optional_table("default_tool"))
    profile.default_tool = read_default_tool(*tool, profile.sources);
  root.finish();
  return profile;
}

MachineProfile load_profile(const std::string& path) {
  std::vector<Diagnostic> problems;
  const std::optional<std::string> text =
      read_text_file(path, "a machine profile (.toml)", problems);
  if (!text) throw ProfileError(path, "", problems.front().message);
  return parse_profile(*text, path);
}

} // namespace ncjoule
