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

namespace {

namespace fs = std::filesystem;

// A chain of bases longer than this is a mistake, not a machine.
constexpr std::size_t kMaxBaseDepth = 16;

toml::table parse_document(std::string_view text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    throw ProfileError(path, "", "not valid TOML: " + std::string(e.description()), int(where.line),
                       int(where.column));
  }
}

// Moves every value of `over` into `under`: a table into the table of the same name key by key,
// anything else (a number, a string, an array) in place of the one below. Moving keeps each
// value's file and line, so that an error names the file that wrote it.
void overlay(toml::table& under, toml::table& over) {
  for (auto&& [key, node] : over) {
    toml::node* below = under.get(key.str());
    if (below && below->is_table() && node.is_table()) {
      overlay(*below->as_table(), *node.as_table());
      continue;
    }
    node.visit([&, &key = key](auto&& value) { under.insert_or_assign(key, std::move(value)); });
  }
}

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

// The file `base` names: beside the profile that names it, else in `dirs` (the shipped
// profiles); with or without ".toml". Empty when there is none.
std::string find_base(const std::string& base, const std::string& from,
                      const std::vector<std::string>& dirs) {
  std::vector<fs::path> folders{fs::path(from).parent_path()};
  if (base.find_first_of("/\\") == std::string::npos)
    for (const std::string& dir : dirs)
      folders.emplace_back(dir);
  for (const fs::path& folder : folders)
    for (const std::string& name : {base, base + ".toml"})
      if (is_file(folder / name)) return (folder / name).lexically_normal().string();
  return {};
}

std::string same_file_key(const std::string& path) {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(path, ec);
  return ec ? path : canonical.string();
}

// The document of `path` with the bases it names laid under it, and those bases' files in
// `bases` (nearest first). `chain` holds the files on the way here, to refuse a cycle.
toml::table layered(std::string_view text, const std::string& path,
                    const std::vector<std::string>& dirs, std::vector<std::string>& chain,
                    std::vector<std::string>& bases) {
  toml::table document = parse_document(text, path);
  const toml::node* base = document.get("base");
  if (!base) return document;
  const auto where = base->source().begin;
  auto refuse = [&](const std::string& reason) {
    throw ProfileError(path, "base", reason, int(where.line), int(where.column));
  };
  if (!base->is_string() || base->value<std::string>()->empty())
    refuse("must name the profile this one starts from (\"haas-vf2\", \"mill.toml\")");
  const std::string name = *base->value<std::string>();
  const std::string file = find_base(name, path, dirs);
  if (file.empty())
    refuse("no profile \"" + name + "\" beside this one" +
           (dirs.empty() ? std::string() : " nor among the shipped profiles"));
  const std::string key = same_file_key(file);
  for (std::size_t k = 0; k < chain.size(); ++k)
    if (chain[k] == key) {
      std::string cycle;
      for (const std::string& link : bases)
        cycle += link + " -> ";
      refuse("profiles that start from each other: " + path + " -> " + cycle + file);
    }
  if (chain.size() > kMaxBaseDepth)
    refuse("more than " + std::to_string(kMaxBaseDepth) + " bases in a row");
  std::vector<Diagnostic> problems;
  const std::optional<std::string> base_text =
      read_text_file(file, "a machine profile (.toml)", problems);
  if (!base_text) refuse("the base profile " + file + ": " + problems.front().message);
  chain.push_back(key);
  bases.push_back(file);
  toml::table under = layered(*base_text, file, dirs, chain, bases);
  document.erase("base");
  overlay(under, document);
  return under;
}

} // namespace

MachineProfile parse_profile(std::string_view text, const std::string& path,
                             const std::vector<std::string>& base_dirs) {
  using namespace profile_detail;
  std::vector<std::string> chain{same_file_key(path)}, bases;
  toml::table document = layered(text, path, base_dirs, chain, bases);
  MachineProfile profile;
  TableReader root(document, path, "", &profile.values);
  profile.base_paths = bases;
  profile.source_path = path;
  profile.name = root.string("name");
  profile.summary = root.optional_string("summary").value_or("");
  if (const toml::node* node = root.raw("estimated")) {
    // What of the profile stands for a class of machine rather than one measured.
    const toml::array* list = node->as_array();
    if (!list) root.fail("estimated", "must be a list of \"power\", \"timing\", \"rates\"");
    for (const toml::node& item : *list) {
      const std::optional<std::string> word = item.value<std::string>();
      if (!word || (*word != "power" && *word != "timing" && *word != "rates"))
        root.fail("estimated", "must be a list of \"power\", \"timing\", \"rates\"");
      profile.estimated.push_back(*word);
    }
  }
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

MachineProfile load_profile(const std::string& path, const std::vector<std::string>& base_dirs) {
  std::vector<Diagnostic> problems;
  const std::optional<std::string> text =
      read_text_file(path, "a machine profile (.toml)", problems);
  if (!text) throw ProfileError(path, "", problems.front().message);
  return parse_profile(*text, path, base_dirs);
}

} // namespace ncjoule
