// Tool descriptions in the header comments CAM posts write (Fusion 360/HSM, FreeCAD,
// Mastercam), and the check that every tool a program uses is described somewhere.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <regex>

#include "ncjoule/removal.hpp"
#include "tool_words.hpp"

namespace ncjoule {
namespace {

using detail::to_upper;

struct Comment {
  std::string text; // without its delimiters
  int column = 0;   // 1-based position of the opening delimiter
};

// The comments of one line, and the code outside them.
void split_line(std::string_view line, std::vector<Comment>& comments, std::string& code) {
  comments.clear();
  code.clear();
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '(') {
      const std::size_t close = line.find(')', i + 1);
      const std::size_t end = close == std::string_view::npos ? line.size() : close;
      comments.push_back({std::string(line.substr(i + 1, end - i - 1)), int(i) + 1});
      i = end;
    } else if (line[i] == ';') {
      comments.push_back({std::string(line.substr(i + 1)), int(i) + 1});
      break;
    } else {
      code += line[i];
    }
  }
}

// G20 anywhere in the code (outside comments) before any G21: the program is in inches.
bool program_in_inches(const SourceFile& source) {
  static const std::regex units(R"(G0*(20|21)(?![\d.]))", std::regex::icase);
  std::vector<Comment> comments;
  std::string code;
  for (std::size_t l = 0; l < source.lines.size(); ++l) {
    split_line(source.line_text(l), comments, code);
    std::smatch m;
    if (std::regex_search(code, m, units)) return m[1].str() == "20";
  }
  return false;
}

double number(const std::string& s) {
  return std::strtod(s.c_str(), nullptr);
}

// Sets shape and angle from a description, applying a corner radius where one was given.
void apply_shape(Tool& tool, const std::string& upper_type, std::optional<double> taper_deg,
                 Diagnostic& note) {
  const auto guess = detail::guess_shape(upper_type);
  if (!guess) {
    note.severity = upper_type.empty() ? Severity::Note : Severity::Warning;
    note.message = "tool T" + std::to_string(tool.number) +
                   (upper_type.empty() ? std::string(": no tool type given")
                                       : ": unknown tool type '" + upper_type + "'") +
                   ", treated as a flat end mill";
  }
  tool.shape = guess ? guess->shape : ToolShape::FlatEndMill;
  if (tool.shape == ToolShape::Drill || tool.shape == ToolShape::Chamfer) {
    double angle = guess->default_tip_angle_deg;
    if (taper_deg)
      angle = guess->taper_is_half_angle ? 2 * *taper_deg : *taper_deg;
    else if (auto a = detail::angle_in_description(upper_type))
      angle = *a;
    tool.tip_angle_deg = angle;
  }
  const double r = tool.radius();
  if (tool.shape == ToolShape::BallEndMill) tool.corner_radius_mm = r;
  if (tool.shape == ToolShape::FlatEndMill && tool.corner_radius_mm > 0)
    tool.shape = tool.corner_radius_mm >= r - 1e-9 ? ToolShape::BallEndMill : ToolShape::BullNose;
  if (tool.shape == ToolShape::BullNose && tool.corner_radius_mm >= r - 1e-9)
    tool.shape = ToolShape::BallEndMill;
}

// Fusion 360 / HSM: "T1 D=6. CR=0. TAPER=118deg - ZMIN=-5. - FLAT END MILL".
std::optional<Tool> read_fusion(const std::string& upper, double unit, Diagnostic& note) {
  static const std::regex head(R"(^\s*T(\d+)\s+D=([-+\d.]+))");
  std::smatch m;
  if (!std::regex_search(upper, m, head)) return std::nullopt;
  Tool tool;
  tool.number = std::atoi(m[1].str().c_str());
  tool.diameter_mm = number(m[2]) * unit;
  static const std::regex cr(R"(\bCR=([-+\d.]+))"), taper(R"(\bTAPER=([-+\d.]+)\s*DEG)");
  if (std::regex_search(upper, m, cr)) tool.corner_radius_mm = number(m[1]) * unit;
  std::optional<double> taper_deg;
  if (std::regex_search(upper, m, taper)) taper_deg = number(m[1]);
  // The type is the last " - " field.
  const std::size_t dash = upper.rfind(" - ");
  std::string type = dash == std::string::npos ? std::string() : upper.substr(dash + 3);
  while (!type.empty() && type.back() == ' ')
    type.pop_back();
  tool.description = type;
  apply_shape(tool, type, taper_deg, note);
  return tool;
}

// Mastercam (MPFAN and its descendants):
//   "1/2 FLAT ENDMILL TOOL - 1 DIA. OFF. - 1 LEN. - 1 DIA. - .5"
//   " T1 | 1/2 FLAT ENDMILL | H1 | D1 | TOOL DIA. - .5" (any of the later fields may be missing)
std::optional<Tool> read_mastercam(const std::string& upper, bool inch, Diagnostic& note) {
  const double unit = inch ? 25.4 : 1.0;
  static const std::regex classic(R"(^(.*?)\s*\bTOOL\s*-\s*(\d+)\b.*\bDIA\.\s*-\s*([\d.]+))");
  static const std::regex piped(R"(^\s*T(\d+)\s*\|\s*([^|]*?)\s*(?:\||$))");
  static const std::regex dia(R"(\bDIA\.?\s*-\s*([\d.]+)\s*$)");
  std::smatch m;
  Tool tool;
  if (std::regex_search(upper, m, classic)) {
    tool.number = std::atoi(m[2].str().c_str());
    tool.diameter_mm = number(m[3]) * unit;
    tool.description = m[1];
  } else if (std::regex_search(upper, m, piped)) {
    tool.number = std::atoi(m[1].str().c_str());
    tool.description = m[2];
    std::smatch d;
    if (std::regex_search(upper, d, dia))
      tool.diameter_mm = number(d[1]) * unit;
    else if (auto size = detail::size_in_description(tool.description, inch))
      tool.diameter_mm = *size;
  } else {
    return std::nullopt;
  }
  static const std::regex corner(R"(\b(?:CORNER\s*RAD(?:IUS)?|CRAD|RAD)\.?\s*[-=]\s*([\d.]+))");
  if (std::regex_search(upper, m, corner)) tool.corner_radius_mm = number(m[1]) * unit;
  apply_shape(tool, tool.description, std::nullopt, note);
  return tool;
}

// FreeCAD: the tool controller's label, "TC: 6mm Ball End"; its number is on the M6 that
// follows.
std::optional<Tool> read_freecad(const std::string& upper, bool inch, Diagnostic& note) {
  static const std::regex label(R"(^\s*TC\s*:\s*(.*?)\s*$)");
  std::smatch m;
  if (!std::regex_search(upper, m, label)) return std::nullopt;
  Tool tool;
  tool.description = m[1];
  if (auto size = detail::size_in_description(tool.description, inch)) tool.diameter_mm = *size;
  apply_shape(tool, tool.description, std::nullopt, note);
  return tool;
}

// The T word of the first tool change at or after `line` (FreeCAD writes "M6 T1" right after
// the tool controller's comment).
std::optional<int> next_tool_number(const SourceFile& source, std::size_t line) {
  // A T word after anything but a letter: "T2", "M6 T2", and posts that glue words ("M6T2").
  static const std::regex tword(R"((?:^|[^A-Za-z])T\s*(\d+))", std::regex::icase);
  std::vector<Comment> comments;
  std::string code;
  for (std::size_t l = line; l < source.lines.size() && l < line + 8; ++l) {
    split_line(source.line_text(l), comments, code);
    std::smatch m;
    if (std::regex_search(code, m, tword)) return std::atoi(m[1].str().c_str());
  }
  return std::nullopt;
}

bool same_geometry(const Tool& a, const Tool& b) {
  auto close = [](double x, double y) { return std::abs(x - y) <= 1e-6 * (1 + std::abs(x)); };
  return a.shape == b.shape && close(a.diameter_mm, b.diameter_mm) &&
         close(a.corner_radius_mm, b.corner_radius_mm) && close(a.tip_angle_deg, b.tip_angle_deg);
}

} // namespace

std::map<int, Tool> parse_tool_comments(const SourceFile& source,
                                        std::vector<Diagnostic>& diagnostics) {
  std::map<int, Tool> tools;
  const bool inch = program_in_inches(source);
  std::vector<Comment> comments;
  std::string code;
  for (std::size_t l = 0; l < source.lines.size(); ++l) {
    split_line(source.line_text(l), comments, code);
    for (const Comment& c : comments) {
      const std::string upper = to_upper(c.text);
      // Cheap filters first: most comments describe no tool.
      const bool maybe_fusion = upper.find("D=") != std::string::npos;
      const bool maybe_mastercam =
          upper.find("TOOL") != std::string::npos || upper.find('|') != std::string::npos;
      const bool maybe_freecad = upper.find("TC") != std::string::npos;
      if (!maybe_fusion && !maybe_mastercam && !maybe_freecad) continue;

      Diagnostic note{Severity::Note, source.path, int(l) + 1, c.column, {}};
      std::optional<Tool> tool;
      if (maybe_fusion) tool = read_fusion(upper, inch ? 25.4 : 1.0, note);
      if (!tool && maybe_mastercam) tool = read_mastercam(upper, inch, note);
      if (!tool && maybe_freecad) {
        tool = read_freecad(upper, inch, note);
        if (tool) {
          const auto number = next_tool_number(source, l + 1);
          if (!number) {
            diagnostics.push_back({Severity::Warning, source.path, int(l) + 1, c.column,
                                   "tool controller '" + tool->description +
                                       "' is not followed by a tool change: ignored"});
            continue;
          }
          tool->number = *number;
        }
      }
      if (!tool) continue;
      if (!note.message.empty()) diagnostics.push_back(note);
      if (const std::string problem = tool_problem(*tool); !problem.empty()) {
        diagnostics.push_back({Severity::Warning, source.path, int(l) + 1, c.column,
                               "tool T" + std::to_string(tool->number) + " ('" + tool->description +
                                   "') " + problem + ": ignored"});
        continue;
      }
      const auto [it, inserted] = tools.emplace(tool->number, *tool);
      if (!inserted && !same_geometry(it->second, *tool))
        diagnostics.push_back({Severity::Warning, source.path, int(l) + 1, c.column,
                               "tool T" + std::to_string(tool->number) +
                                   " is described again with another geometry; the first "
                                   "description is kept"});
    }
  }
  return tools;
}

} // namespace ncjoule
