// A mapping file (TOML) for a control whose log does not name its data by MTConnect type: which
// item is which signal, the scale of its values and its own execution words. Small and strict:
// an unknown key or signal is an error at its line, so that a misspelt mapping is never read as
// an empty one.
#include <cmath>
#include <toml++/toml.h>

#include "ncjoule/logs.hpp"
#include "ncjoule/text_file.hpp"

namespace ncjoule {
namespace {

struct MappingReader {
  const std::string& path;
  std::vector<Diagnostic>& diagnostics;
  bool failed = false;

  void error(const toml::node& node, const std::string& message) {
    const auto& where = node.source().begin;
    diagnostics.push_back({Severity::Error, path, int(where.line), int(where.column), message});
    failed = true;
  }
};

std::optional<double> number(const toml::node& node) {
  if (const auto* i = node.as_integer()) return static_cast<double>(i->get());
  if (const auto* f = node.as_floating_point()) return f->get();
  return std::nullopt;
}

std::string signal_list() {
  std::string list;
  for (std::size_t i = 0; i < kLogSignalCount; ++i)
    list += (i ? ", " : "") + std::string(log_signal_name(static_cast<LogSignal>(i)));
  return list;
}

} // namespace

std::optional<LogMapping> parse_log_mapping(std::string_view text, const std::string& path,
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
  MappingReader reader{path, diagnostics};
  LogMapping mapping;
  mapping.path = path;
  for (const auto& [key, node] : document) {
    const std::string name(key.str());
    if (name == "source" || name == "name") continue; // where the mapping comes from
    if (name == "line_numbering") {
      const auto value = node.value<std::string>();
      const auto numbering = value ? line_numbering_from_name(*value) : std::nullopt;
      if (!numbering)
        reader.error(node, "line_numbering must be \"auto\", \"file-line\", "
                           "\"file-line-from-zero\" or \"n-word\"");
      else
        mapping.line_numbering = *numbering;
      continue;
    }
    const toml::table* table = node.as_table();
    if (!table || (name != "items" && name != "scale" && name != "execution")) {
      reader.error(node, "unknown key '" + name +
                             "': a mapping has [items], [scale], [execution] and line_numbering");
      continue;
    }
    for (const auto& [entry_key, value] : *table) {
      const std::string entry(entry_key.str());
      if (name == "execution") {
        const auto word = value.value<std::string>();
        if (!word)
          reader.error(value, "[execution] " + entry +
                                  " must be a string: the MTConnect word "
                                  "(ACTIVE, FEED_HOLD, ...)");
        else
          mapping.execution[entry] = *word;
        continue;
      }
      const auto signal = log_signal_from_name(entry);
      if (!signal) {
        reader.error(value,
                     "unknown signal '" + entry + "' in [" + name + "]; known: " + signal_list());
        continue;
      }
      if (name == "items") {
        const auto item = value.value<std::string>();
        if (!item || item->empty())
          reader.error(value, "[items] " + entry + " must be the item's name or id (a string)");
        else
          mapping.items[*signal] = *item;
      } else {
        const auto factor = number(value);
        if (!factor || !std::isfinite(*factor) || *factor <= 0)
          reader.error(value, "[scale] " + entry + " must be a number above zero");
        else
          mapping.scale[*signal] = *factor;
      }
    }
  }
  if (reader.failed) return std::nullopt;
  return mapping;
}

std::optional<LogMapping> read_log_mapping(const std::string& path,
                                           std::vector<Diagnostic>& diagnostics) {
  auto text = read_text_file(path, "a log mapping file (.toml)", diagnostics);
  if (!text) return std::nullopt;
  return parse_log_mapping(*text, path, diagnostics);
}

} // namespace ncjoule
