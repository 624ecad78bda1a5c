// Tool descriptions in the comments CAM posts write (parse_tool_comments in removal.hpp): which
// reader a comment goes to, and where a tool's number comes from when its comment gives none.
// The formats themselves are in tool_comment_formats.cpp.
#include <algorithm>
#include <cmath>
#include <iterator>

#include "ncjoule/removal.hpp"
#include "ncjoule/text.hpp"
#include "tool_comment_formats.hpp"
#include "tool_words.hpp"

namespace ncjoule {
namespace {

using detail::DescribedTool;
using detail::DescriptionUnits;

// Lines around a tool change where a free description belongs to it: FreeCAD writes the tool
// controller's label up to a few lines before "M6 T2"; posts write the tool's name on the tool
// change line or next to it.
constexpr int kLabelLinesBefore = 8;
constexpr int kNameLinesAround = 4; // pcb2gcode: T1, M5, G04, then its MSG naming the cutter

// A comment that names a tool number and its size, in any of the numbered formats.
std::optional<DescribedTool> read_numbered(const std::string& upper, DescriptionUnits units) {
  if (upper.find("D=") != std::string::npos)
    if (auto t = detail::read_fusion_tool(upper, units)) return t;
  if (upper.find("TOOL") != std::string::npos || upper.find('|') != std::string::npos)
    if (auto t = detail::read_mastercam_tool(upper, units)) return t;
  if (upper.find('=') != std::string::npos)
    if (auto t = detail::read_numbered_list_tool(upper, units)) return t;
  if (!upper.empty() && upper[0] == 'T') {
    if (auto t = detail::read_cambam_tool(upper, units)) return t;
    if (auto t = detail::read_keyed_tool(upper, units)) return t;
  }
  return std::nullopt;
}

bool same_geometry(const Tool& a, const Tool& b) {
  auto close = [](double x, double y) { return std::abs(x - y) <= 1e-6 * (1 + std::abs(x)); };
  return a.shape == b.shape && close(a.diameter_mm, b.diameter_mm) &&
         close(a.corner_radius_mm, b.corner_radius_mm) && close(a.tip_angle_deg, b.tip_angle_deg);
}

// Gathers the tools, numbered descriptions first: a description a post writes without a number
// (next to a tool change, in a list) only fills in a number no numbered comment described.
class ToolCollector {
public:
  ToolCollector(const SourceFile& source, std::vector<Diagnostic>& diagnostics)
      : source_(source), diagnostics_(diagnostics) {}

  void add(DescribedTool d, int line, int column, bool numbered_format) {
    Tool& tool = d.tool;
    const std::string name = "tool T" + std::to_string(tool.number);
    if (d.remark) {
      d.remark->file = source_.path;
      d.remark->line = line + 1;
      d.remark->column = column;
      d.remark->message = name + ": " + d.remark->message;
      diagnostics_.push_back(*d.remark);
    }
    if (const std::string problem = tool_problem(tool); !problem.empty()) {
      say(Severity::Warning, line, column,
          name + " ('" + tool.description + "') " + problem + ": ignored");
      return;
    }
    auto& into = numbered_format ? numbered_ : unnumbered_;
    const auto [it, inserted] = into.emplace(tool.number, tool);
    if (!inserted && !same_geometry(it->second, tool))
      say(Severity::Warning, line, column,
          name + " is described again with another geometry; the first description is kept");
  }

  void say(Severity severity, int line, int column, std::string message) {
    diagnostics_.push_back({severity, source_.path, line + 1, column, std::move(message)});
  }

  std::map<int, Tool> take() {
    std::map<int, Tool> tools = std::move(numbered_);
    for (auto& [number, tool] : unnumbered_) {
      const auto [it, inserted] = tools.emplace(number, tool);
      if (!inserted && !same_geometry(it->second, tool))
        say(Severity::Note, 0, 0,
            "tool T" + std::to_string(number) + ": the comment at its tool change ('" +
                tool.description + "') differs from the tool list; the list is kept");
    }
    return tools;
  }

private:
  const SourceFile& source_;
  std::vector<Diagnostic>& diagnostics_;
  std::map<int, Tool> numbered_, unnumbered_;
};

// A description without a number, where it was read.
struct Listed {
  DescribedTool tool;
  int line, column;
};

// The tool number selected at or after `line` within `span` lines, or at or before it.
std::optional<int> selected_after(const std::map<int, int>& selected, int line, int span) {
  const auto it = selected.lower_bound(line);
  if (it == selected.end() || it->first > line + span) return std::nullopt;
  return it->second;
}
std::optional<int> selected_before(const std::map<int, int>& selected, int line, int span) {
  auto it = selected.upper_bound(line);
  if (it == selected.begin()) return std::nullopt;
  --it;
  if (it->first < line - span) return std::nullopt;
  return it->second;
}

} // namespace

void ToolCommentContext::add(const CanonCommand& c) {
  if (!units_known && (c.kind == CanonKind::LengthUnits || is_move(c.kind))) {
    inch = c.state.inch;
    units_known = true;
  }
  if (c.kind == CanonKind::SelectTool) selected_tools.emplace(c.line, int(c.value));
  if (is_move(c.kind) && selected_tools.empty()) moves_before_first_tool = true;
}

std::map<int, Tool> parse_tool_comments(const SourceFile& source, const ToolCommentContext& context,
                                        std::vector<Diagnostic>& diagnostics) {
  const DescriptionUnits units{context.inch};
  ToolCollector tools(source, diagnostics);
  // Estlcam's "(Required tools:)" list: the comment-only lines after it, one tool each, in the
  // order the program uses them.
  bool in_tool_list = false;
  std::vector<Listed> listed;
  // A program that selects no tool may name the one it cuts with in its header (Eagle's
  // stepcraft.ulp "(Use a 1/32inch Bit)"): the comment-only lines before its first code. Only
  // where no list is given: a header's prose also says "a 1.5mm slot" of the part.
  bool in_header = context.selected_tools.empty();
  std::vector<Listed> header;
  // The free descriptions next to tool changes ("T2 M06 (Change tool: ...)"), one per change.
  std::vector<Tool> named_at_changes;
  for (std::size_t index = 0; index < source.lines.size(); ++index) {
    const int line = int(index);
    const LineComments lc = line_comments(source.line_text(index), context.dialect);
    if (lc.has_code) in_tool_list = in_header = false;
    for (const LineComment& c : lc.comments) {
      const std::string upper = to_upper(c.text);
      if (upper == "REQUIRED TOOLS:") {
        in_tool_list = true;
        continue;
      }
      if (in_tool_list) {
        if (auto t = detail::read_free_tool(upper, units)) listed.push_back({*t, line, c.column});
        continue;
      }
      if (in_header && !read_numbered(upper, units))
        if (auto t = detail::read_free_tool(upper, units)) {
          header.push_back({*t, line, c.column});
          continue;
        }
      if (auto t = read_numbered(upper, units)) {
        tools.add(*t, line, c.column, true);
        continue;
      }
      if (upper.find("TYPE") != std::string::npos)
        if (auto t = detail::read_blendercam_tool(upper, units)) {
          // Numbered by the tool change next to it; a program that selects none cuts with it.
          auto number = selected_after(context.selected_tools, line, kNameLinesAround);
          if (!number) number = selected_before(context.selected_tools, line, kNameLinesAround);
          if (number) {
            t->tool.number = *number;
            tools.add(*t, line, c.column, true);
          } else {
            listed.push_back({*t, line, c.column});
          }
          continue;
        }
      if (upper.find("TC") != std::string::npos) {
        if (auto t = detail::read_freecad_tool(upper, units)) {
          const auto number = selected_after(context.selected_tools, line, kLabelLinesBefore);
          if (!number) {
            tools.say(Severity::Warning, line, c.column,
                      "tool controller '" + t->tool.description +
                          "' is not followed by a tool change: ignored");
            continue;
          }
          t->tool.number = *number;
          tools.add(*t, line, c.column, true);
          continue;
        }
      }
      // A tool's name next to the tool change that selects it: on its line, just before it
      // (CAMotics, "(Tool: 1/8 in Carbide End Mill)" then "T2 M6"), else just after it
      // (Vectric, "N120T5M06" then "N130 (Tool: ...)").
      auto number = selected_after(context.selected_tools, line, kNameLinesAround);
      if (!number) number = selected_before(context.selected_tools, line, kNameLinesAround);
      if (number)
        if (auto t = detail::read_free_tool(upper, units)) {
          t->tool.number = *number;
          named_at_changes.push_back(t->tool);
          tools.add(*t, line, c.column, false);
        }
    }
  }

  // The list names tools, not numbers. A program that never selects a tool cuts with the one it
  // lists (tool 0), or the one its header names; several descriptions of one geometry are one
  // tool ("(Tool is an HSS 2mm 2-flute endmill)" above Estlcam's list).
  const std::vector<Listed>& named = listed.empty() ? header : listed;
  if (context.selected_tools.empty() && !named.empty()) {
    const bool one_tool = std::all_of(named.begin(), named.end(), [&](const Listed& l) {
      return same_geometry(l.tool.tool, named[0].tool.tool);
    });
    if (one_tool) {
      DescribedTool only = named[0].tool;
      only.tool.number = 0;
      tools.add(only, named[0].line, named[0].column, false);
    } else {
      tools.say(Severity::Warning, named[0].line, named[0].column,
                "the program lists " + std::to_string(named.size()) +
                    " tools but selects none: which one cuts is not known; none is used");
    }
  } else if (!listed.empty() && context.moves_before_first_tool) {
    // Estlcam's start code changes no tool: the program starts with the first tool of its list,
    // the one no tool change names (each change names one listed tool).
    std::vector<bool> matched(listed.size(), false);
    for (const Tool& changed : named_at_changes)
      for (std::size_t k = 0; k < listed.size(); ++k)
        if (!matched[k] && same_geometry(listed[k].tool.tool, changed)) {
          matched[k] = true;
          break;
        }
    const auto first = std::find(matched.begin(), matched.end(), false);
    if (first != matched.end()) {
      const Listed& start = listed[std::size_t(first - matched.begin())];
      DescribedTool at_start = start.tool;
      at_start.tool.number = 0;
      tools.say(Severity::Note, start.line, start.column,
                "tool T0 (in the spindle before the first tool change): '" +
                    at_start.tool.description +
                    "', the first listed tool that no tool change names");
      tools.add(at_start, start.line, start.column, false);
    }
  }
  return tools.take();
}

} // namespace ncjoule
