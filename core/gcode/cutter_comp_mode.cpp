// Reading how G41/G42 were posted from a program's comments (cutter_comp_mode.hpp).
#include "cutter_comp_mode.hpp"

#include <cctype>

#include "ncjoule/text.hpp"

namespace ncjoule::detail {
namespace {

// The number after `letter` at `at` in `text` (upper case), if digits follow it.
std::optional<int> number_after(const std::string& text, std::size_t at) {
  std::size_t k = at + 1;
  while (k < text.size() && text[k] == ' ')
    ++k;
  if (k >= text.size() || !std::isdigit(static_cast<unsigned char>(text[k]))) return std::nullopt;
  int n = 0;
  for (; k < text.size() && std::isdigit(static_cast<unsigned char>(text[k])) && n < 100000; ++k)
    n = n * 10 + (text[k] - '0');
  return n;
}

} // namespace

std::optional<CompModeHint> comp_mode_of_comment(std::string_view comment) {
  const std::string text = to_upper(std::string(comment));
  if (text.find("COMP") == std::string::npos) return std::nullopt;
  // Most telling first: "REVERSE WEAR COMP" holds "WEAR COMP", "CUTTER COMP CONTROL TYPE" holds
  // "COMP CONTROL".
  static const std::pair<const char*, CutterCompMode> kWords[] = {
      {"REVERSE WEAR COMP", CutterCompMode::Wear}, {"INVERSE WEAR COMP", CutterCompMode::Wear},
      {"WEAR COMP", CutterCompMode::Wear},         {"COMP WEAR", CutterCompMode::Wear},
      {"COMP REVERSE WEAR", CutterCompMode::Wear}, {"CONTROL COMP", CutterCompMode::Control},
      {"COMP CONTROL", CutterCompMode::Control},
  };
  for (const auto& [words, mode] : kWords)
    if (text.find(words) != std::string::npos) return CompModeHint{mode, 0, words};
  return std::nullopt;
}

CompModeHints scan_comp_mode_hints(const SourceFile& source, const Dialect& dialect) {
  CompModeHints hints;
  for (std::size_t i = 0; i < source.lines.size(); ++i) {
    const std::string_view line = source.line_text(i);
    if (line.find('(') == std::string_view::npos && line.find(';') == std::string_view::npos)
      continue;
    for (const LineComment& c : line_comments(line, dialect).comments) {
      std::optional<CompModeHint> hint = comp_mode_of_comment(c.text);
      if (!hint) continue;
      hint->line = int(i) + 1;
      // A tool line: "T1 | ... | D1 | ...": the hint is that tool's (and its D register's).
      const std::string text = to_upper(std::string(c.text));
      bool tool_line = false;
      if (text.size() > 1 && text[0] == 'T' && text.find('|') != std::string::npos) {
        if (const auto t = number_after(text, 0)) hints.by_tool[*t] = *hint, tool_line = true;
        if (const std::size_t d = text.find("| D"); d != std::string::npos)
          if (const auto n = number_after(text, d + 2)) hints.by_tool[*n] = *hint;
      }
      if (!tool_line) hints.from_line.emplace_back(i, *hint);
    }
  }
  return hints;
}

std::optional<CompModeHint> CompModeHints::at(std::size_t line, int d, int tool) const {
  if (auto it = by_tool.find(d); d > 0 && it != by_tool.end()) return it->second;
  if (auto it = by_tool.find(tool); it != by_tool.end()) return it->second;
  std::optional<CompModeHint> last;
  for (const auto& [from, hint] : from_line) {
    if (from > line) break;
    last = hint;
  }
  return last;
}

} // namespace ncjoule::detail
