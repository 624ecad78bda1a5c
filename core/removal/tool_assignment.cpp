// Which tool each move cuts with, when the program, its comments and the user describe some
// tools and not others (see assign_tools in removal.hpp).
#include <algorithm>
#include <set>

#include "ncjoule/removal.hpp"
#include "ncjoule/text.hpp"
#include "tool_words.hpp"

namespace ncjoule {
namespace {

std::string describe(const Tool& tool) {
  char size[32];
  std::snprintf(size, sizeof size, "%g mm", tool.diameter_mm);
  return "T" + std::to_string(tool.number) + " (" + size + " " +
         std::string(tool_shape_name(tool.shape)) + ")";
}

constexpr const char* kHowToDescribe =
    "give it with --tool N:TYPE:DIAMETER (e.g. --tool 1:flat:6), a job file (--job), a LinuxCNC "
    "tool table (--tool-table) or the machine profile's [default_tool]";

} // namespace

void ToolUsage::add(const CanonCommand& c) {
  if (!is_move(c.kind)) return;
  first_move.emplace(c.state.tool, c.line);
  if (is_feed_move(c.kind)) first_cut.emplace(c.state.tool, c.line);
}

ToolAssignment assign_tools(const std::vector<CanonCommand>& commands,
                            const std::map<int, Tool>& described,
                            const std::optional<Tool>& default_tool, std::string_view file) {
  ToolUsage usage;
  for (const CanonCommand& c : commands)
    usage.add(c);
  return assign_tools(usage, described, default_tool, file);
}

ToolAssignment assign_tools(const ToolUsage& usage, const std::map<int, Tool>& described,
                            const std::optional<Tool>& default_tool, std::string_view file) {
  ToolAssignment out;
  out.tools = described;
  std::map<int, int> first_move = usage.first_move, first_cut = usage.first_cut;
  auto say = [&](Severity severity, int line, std::string message) {
    out.diagnostics.push_back({severity, std::string(file), line + 1, 0, std::move(message)});
  };

  // Tool 0: no tool selected.
  if (first_move.count(0) && !described.count(0)) {
    const bool cuts = first_cut.count(0) > 0;
    const int line = cuts ? first_cut[0] : first_move[0];
    std::set<int> selected; // tool numbers the program itself moves with
    for (const auto& [number, _] : first_move)
      if (number != 0) selected.insert(number);
    std::optional<Tool> fallback;
    std::string why;
    Severity severity = Severity::Warning;
    if (described.size() == 1) {
      fallback = described.begin()->second;
      why = "the one tool described";
      if (selected.empty()) severity = Severity::Note; // a program that never selects a tool
    } else if (selected.size() == 1 && described.count(*selected.begin())) {
      fallback = described.at(*selected.begin());
      why = "the program's only tool";
    } else if (default_tool) {
      fallback = *default_tool;
      why = "the machine profile's default tool";
    }
    if (fallback) {
      out.tools[0] = *fallback;
      out.fallback = cuts;
      if (cuts)
        say(severity, line,
            std::string(selected.empty() ? "the program selects no tool"
                                         : "feed moves before the first tool change have no "
                                           "tool selected") +
                ": they cut with " + describe(*fallback) + ", " + why);
    } else if (cuts) {
      out.unsimulated.push_back(0);
      say(Severity::Warning, line,
          "feed moves with no tool selected, and no tool is described: they are timed but "
          "remove nothing (no cutting power); " +
              std::string(kHowToDescribe));
    }
  }
  // Numbered tools nothing describes.
  for (const auto& [number, line] : first_move) {
    if (number == 0 || described.count(number)) continue;
    out.unsimulated.push_back(number);
    const bool cuts = first_cut.count(number) > 0;
    say(Severity::Warning, cuts ? first_cut[number] : line,
        "tool T" + std::to_string(number) +
            " is described nowhere (no CAM tool comment, tool table entry, job file or --tool): "
            "its moves are timed but remove nothing (no cutting power); " +
            std::string(kHowToDescribe));
  }
  std::sort(out.unsimulated.begin(), out.unsimulated.end());
  return out;
}

std::map<int, Tool> tools_from_table(const ToolTable& table, std::vector<Diagnostic>& diagnostics,
                                     std::string_view file) {
  std::map<int, Tool> tools;
  for (const auto& [number, entry] : table) {
    if (!(entry.diameter > 0)) continue;
    Tool tool;
    tool.number = number;
    tool.diameter_mm = entry.diameter;
    tool.description = entry.comment;
    const std::string upper = to_upper(entry.comment);
    if (const auto guess = detail::guess_shape(upper)) {
      tool.shape = guess->shape;
      if (tool.shape == ToolShape::BallEndMill) tool.corner_radius_mm = tool.radius();
      if (tool.shape == ToolShape::Drill || tool.shape == ToolShape::Chamfer)
        tool.tip_angle_deg =
            detail::angle_in_description(upper).value_or(guess->default_tip_angle_deg);
      if (tool.shape == ToolShape::BullNose) tool.shape = ToolShape::FlatEndMill; // no radius
    } else {
      diagnostics.push_back({Severity::Note, std::string(file), 0, 0,
                             "tool table: T" + std::to_string(number) +
                                 " has no shape in its comment: taken as a flat end mill"});
    }
    if (!tool_problem(tool).empty()) continue;
    tools[number] = tool;
  }
  return tools;
}

} // namespace ncjoule
