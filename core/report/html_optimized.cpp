#include "html_optimized.hpp"

#include <map>
#include <vector>

#include "ncjoule/optimize.hpp"
#include "svg_chart.hpp"

namespace ncjoule::report_detail {
namespace {

// The blocks listed in full; a program with more says how many more (the counts stay whole).
constexpr std::size_t kListed = 500;

// "AIR", "RAPID", "LOAD", "RESTORE": the word after the mark.
std::string rule_of(std::string_view line, std::size_t mark) {
  std::size_t k = mark + std::string_view(kOptimizeMark).size();
  while (k < line.size() && line[k] == ' ')
    ++k;
  std::size_t end = k;
  while (end < line.size() && line[end] >= 'A' && line[end] <= 'Z')
    ++end;
  return end > k ? std::string(line.substr(k, end - k)) : "OTHER";
}

} // namespace

std::string optimized_blocks_section(const SourceFile& source) {
  struct Changed {
    std::size_t line;
    std::string rule;
  };
  std::vector<Changed> changed;
  std::map<std::string, std::size_t> by_rule;
  for (std::size_t i = 0; i < source.lines.size(); ++i) {
    const std::string_view text = source.line_text(i);
    const std::size_t mark = text.find(kOptimizeMark);
    if (mark == std::string_view::npos) continue;
    const std::size_t first = text.find_first_not_of(" \t");
    if (text[first] == '(' || text[first] == ';') continue; // the header: comment lines only
    changed.push_back({i, rule_of(text, mark)});
    ++by_rule[changed.back().rule];
  }
  if (changed.empty()) return {};
  std::string counts;
  for (const auto& [rule, n] : by_rule)
    counts += (counts.empty() ? "" : ", ") + std::to_string(n) + " " + html_escaped(rule);
  std::string html = "<h3>Blocks changed by ncjoule optimize</h3><p class=\"note\">" +
                     std::to_string(changed.size()) + " block(s) carry the optimizer's mark (" +
                     counts +
                     "); every other block is as the post wrote it. Compare it with the original "
                     "(ncjoule compare ORIGINAL OPTIMIZED).</p><table class=\"optimized\"><thead>"
                     "<tr><th>Line</th><th>Rule</th><th class=\"name\">Block</th></tr></thead>"
                     "<tbody>";
  for (std::size_t k = 0; k < changed.size() && k < kListed; ++k)
    html += "<tr data-line=\"" + std::to_string(changed[k].line + 1) + "\"><td>" +
            std::to_string(changed[k].line + 1) + "</td><td>" + html_escaped(changed[k].rule) +
            "</td><td class=\"name\"><code>" +
            html_escaped(std::string(source.line_text(changed[k].line))) + "</code></td></tr>";
  html += "</tbody></table>";
  if (changed.size() > kListed)
    html += "<p class=\"note\">" + std::to_string(changed.size() - kListed) +
            " more changed block(s) not listed.</p>";
  return html;
}

} // namespace ncjoule::report_detail
