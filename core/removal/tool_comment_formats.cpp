// Readers of the tool descriptions CAM posts write (tool_comment_formats.hpp). The patterns are
// taken from what each post writes; where a post has several styles, each one is here.
#include "tool_comment_formats.hpp"

#include <cstdlib>
#include <regex>

#include "tool_words.hpp"

namespace ncjoule::detail {
namespace {

double number(const std::string& s) {
  return std::strtod(s.c_str(), nullptr);
}

// Without the blanks and separators (",", "-", ":") posts put around a tool's name.
std::string trim_separators(std::string s) {
  const std::size_t first = s.find_first_not_of(" \t,-:");
  if (first == std::string::npos) return {};
  const std::size_t last = s.find_last_not_of(" \t,-:");
  return s.substr(first, last - first + 1);
}

// Sets shape and tip angle from the tool's type words, with its corner radius where one was
// given; a remark when the type is missing or unknown (read as a flat end mill).
void apply_shape(DescribedTool& d, const std::string& upper_type,
                 std::optional<double> taper_deg = std::nullopt) {
  Tool& tool = d.tool;
  const auto guess = guess_shape(upper_type);
  if (!guess) {
    Diagnostic remark;
    remark.severity = upper_type.empty() ? Severity::Note : Severity::Warning;
    remark.message = (upper_type.empty() ? std::string("no tool type given")
                                         : "unknown tool type '" + upper_type + "'") +
                     ", treated as a flat end mill";
    d.remark = remark;
  }
  tool.shape = guess ? guess->shape : ToolShape::FlatEndMill;
  if (tool.shape == ToolShape::Drill || tool.shape == ToolShape::Chamfer) {
    double angle = guess->default_tip_angle_deg;
    if (taper_deg)
      angle = guess->taper_is_half_angle ? 2 * *taper_deg : *taper_deg;
    else if (auto a = angle_in_description(upper_type))
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

// A number as posts write it: "6", "6.", ".5", "0.25".
#define NCJ_NUMBER R"((\d+(?:\.\d*)?|\.\d+))"

// A corner radius written with a key: "CR=1", "CORNER RAD 1.", "RAD. - .03", "R0.5" (a bare R
// needs a decimal point or "=", so "R1" offset words and "R" in words are not read).
std::optional<double> keyed_corner_radius(const std::string& upper) {
  static const std::regex keyed(R"((?:^|[^A-Z])(?:CR|CRAD|RAD|RADIUS|CORNER\s*RAD(?:IUS)?)\.?)"
                                R"([\s=:\-]*)" NCJ_NUMBER);
  static const std::regex bare_r(R"((?:^|[^A-Z])R(?:\s*=\s*)" NCJ_NUMBER R"(|(\d*\.\d*)))");
  std::smatch m;
  if (std::regex_search(upper, m, keyed)) return number(m[1]);
  if (std::regex_search(upper, m, bare_r)) return number(m[1].matched ? m[1] : m[2]);
  return std::nullopt;
}

// A diameter written with a key: "DIA 12", "DIA. - .5", "DIAMETER: 6", "Ø6", "D=6", "D10."
// (a bare D needs a decimal point or "=": "D1" is a cutter compensation offset).
std::optional<double> keyed_diameter(const std::string& upper) {
  static const std::regex keyed(
      R"((?:^|[^A-Z])(?:DIA|DIAM|DIAMETER|\xC3\x98)\.?[\s=:\-]*)" NCJ_NUMBER);
  static const std::regex bare_d(R"((?:^|[^A-Z])D(?:\s*=\s*)" NCJ_NUMBER R"(|(\d*\.\d*)))");
  std::smatch m;
  if (std::regex_search(upper, m, keyed)) return number(m[1]);
  if (std::regex_search(upper, m, bare_d)) return number(m[1].matched ? m[1] : m[2]);
  return std::nullopt;
}

// A tool from free text that names its size: the diameter (a size with its unit first, then a
// keyed one, then a bare size in program units), a keyed corner radius, the shape words.
// std::nullopt when the text gives no size. A missing type is only a note: free text need not
// name one.
std::optional<DescribedTool> sized_description(const std::string& text, int number, bool numbered,
                                               DescriptionUnits units) {
  static const std::regex unit_size(R"(\d\s*(?:MM|IN\b|INCH|"))");
  DescribedTool d;
  d.numbered = numbered;
  d.tool.number = number;
  d.tool.description = text;
  std::optional<double> with_unit;
  if (std::regex_search(text, unit_size)) with_unit = size_in_description(text, units.inch);
  if (with_unit)
    d.tool.diameter_mm = *with_unit;
  else if (auto dia = keyed_diameter(text))
    d.tool.diameter_mm = *dia * units.mm_per_unit();
  else if (auto size = size_in_description(text, units.inch))
    d.tool.diameter_mm = *size;
  else
    return std::nullopt;
  if (auto r = keyed_corner_radius(text)) d.tool.corner_radius_mm = *r * units.mm_per_unit();
  apply_shape(d, text);
  if (d.remark) d.remark->severity = Severity::Note;
  return d;
}

} // namespace

std::optional<DescribedTool> read_fusion_tool(const std::string& upper, DescriptionUnits units) {
  static const std::regex head(R"(^\s*T(\d+)\s+D=)" NCJ_NUMBER);
  std::smatch m;
  if (!std::regex_search(upper, m, head)) return std::nullopt;
  DescribedTool d;
  Tool& tool = d.tool;
  tool.number = std::atoi(m[1].str().c_str());
  tool.diameter_mm = number(m[2]) * units.mm_per_unit();
  static const std::regex cr(R"(\bCR=)" NCJ_NUMBER), taper(R"(\bTAPER=)" NCJ_NUMBER R"(\s*DEG)");
  if (std::regex_search(upper, m, cr)) tool.corner_radius_mm = number(m[1]) * units.mm_per_unit();
  std::optional<double> taper_deg;
  if (std::regex_search(upper, m, taper)) taper_deg = number(m[1]);
  // The type is the last " - " field.
  const std::size_t dash = upper.rfind(" - ");
  tool.description =
      dash == std::string::npos ? std::string() : trim_separators(upper.substr(dash + 3));
  apply_shape(d, tool.description, taper_deg);
  return d;
}

std::optional<DescribedTool> read_mastercam_tool(const std::string& upper, DescriptionUnits units) {
  static const std::regex classic(R"(^(.*?)\s*\bTOOL\s*-\s*(\d+)\b.*\bDIA\.\s*-\s*)" NCJ_NUMBER);
  static const std::regex piped(R"(^\s*T(\d+)\s*\|\s*([^|]*?)\s*(?:\||$))");
  static const std::regex dia(R"(\bDIA\.?\s*-\s*)" NCJ_NUMBER R"(\s*$)");
  std::smatch m;
  DescribedTool d;
  Tool& tool = d.tool;
  if (std::regex_search(upper, m, classic)) {
    tool.number = std::atoi(m[2].str().c_str());
    tool.diameter_mm = number(m[3]) * units.mm_per_unit();
    tool.description = m[1];
  } else if (std::regex_search(upper, m, piped)) {
    tool.number = std::atoi(m[1].str().c_str());
    tool.description = m[2];
    std::smatch dm;
    if (std::regex_search(upper, dm, dia))
      tool.diameter_mm = number(dm[1]) * units.mm_per_unit();
    else if (auto size = size_in_description(tool.description, units.inch))
      tool.diameter_mm = *size;
  } else {
    return std::nullopt;
  }
  if (auto r = keyed_corner_radius(upper)) tool.corner_radius_mm = *r * units.mm_per_unit();
  apply_shape(d, tool.description);
  return d;
}

std::optional<DescribedTool> read_cambam_tool(const std::string& upper, DescriptionUnits units) {
  static const std::regex with_colon(R"(^T(\d+)\s*:\s*)" NCJ_NUMBER R"((?:\s+(.*))?$)");
  static const std::regex bare(R"(^T(\d+)\s+)" NCJ_NUMBER R"($)");
  std::smatch m;
  if (!std::regex_match(upper, m, with_colon) && !std::regex_match(upper, m, bare))
    return std::nullopt;
  DescribedTool d;
  d.tool.number = std::atoi(m[1].str().c_str());
  d.tool.diameter_mm = number(m[2]) * units.mm_per_unit();
  d.tool.description = m.size() > 3 && m[3].matched ? trim_separators(m[3]) : std::string();
  // CamBam's tool comment is free text: "surfacing bit" names no shape; a flat end mill then,
  // with only a note (its lists are mostly end mills).
  apply_shape(d, d.tool.description);
  if (d.remark) d.remark->severity = Severity::Note;
  return d;
}

std::optional<DescribedTool> read_numbered_list_tool(const std::string& upper,
                                                     DescriptionUnits units) {
  static const std::regex entry(R"(^T?\s*(\d+)\s*=\s*(.+)$)");
  std::smatch m;
  if (!std::regex_match(upper, m, entry)) return std::nullopt;
  return sized_description(trim_separators(m[2]), std::atoi(m[1].str().c_str()), true, units);
}

std::optional<DescribedTool> read_keyed_tool(const std::string& upper, DescriptionUnits units) {
  static const std::regex head(
      R"(^\s*(?:T|TOOL\s*(?:NO\.?|NUMBER|#)?)\s*[#:.\-]?\s*0*(\d+)(?=[\s\-:,]|$)\s*[-:,]?\s*(.*)$)");
  std::smatch m;
  if (!std::regex_match(upper, m, head)) return std::nullopt;
  return sized_description(trim_separators(m[2]), std::atoi(m[1].str().c_str()), true, units);
}

std::optional<DescribedTool> read_blendercam_tool(const std::string& upper,
                                                  DescriptionUnits units) {
  static const std::regex entry(R"(^\s*TOOL\s*:\s*D\s*=\s*)" NCJ_NUMBER
                                R"(\s*(MM|''|"|IN)?\s*TYPE\s+([A-Z_]+)(?:\s+FLUTES\s+(\d+))?)");
  std::smatch m;
  if (!std::regex_search(upper, m, entry)) return std::nullopt;
  DescribedTool d;
  d.numbered = false;
  const std::string unit = m[2];
  const double mm_per_unit = unit == "MM" ? 1.0 : unit.empty() ? units.mm_per_unit() : 25.4;
  d.tool.diameter_mm = number(m[1]) * mm_per_unit;
  const std::string type = m[3];
  if (m[4].matched) d.tool.flutes = std::atoi(m[4].str().c_str());
  d.tool.description = "BlenderCAM " + type + " cutter";
  // BlenderCAM's type names, in the words apply_shape knows.
  static const std::pair<const char*, const char*> names[] = {
      {"END", "END MILL"}, {"BALL", "BALL END MILL"},     {"BULLNOSE", "END MILL"},
      {"VCARVE", "V-BIT"}, {"BALLCONE", "BALL END MILL"}, {"CYLCONE", "V-BIT"}};
  std::string words = type;
  for (const auto& [name, as] : names)
    if (type == name) words = as;
  apply_shape(d, words);
  // The comment gives no corner radius or cone angle: the nearest shape, said.
  const char* nearest = type == "BALLCONE"   ? "a ball end mill"
                        : type == "CYLCONE"  ? "a 90-degree V-bit"
                        : type == "BULLNOSE" ? "a flat end mill (no corner radius given)"
                                             : nullptr;
  if (nearest) {
    Diagnostic remark;
    remark.severity = Severity::Note;
    remark.message = "a " + type + " cutter is simulated as " + nearest + " of its diameter";
    d.remark = remark;
  }
  return d;
}

std::optional<DescribedTool> read_freecad_tool(const std::string& upper, DescriptionUnits units) {
  static const std::regex label(R"(^\s*TC\s*:\s*(.*?)\s*$)");
  std::smatch m;
  if (!std::regex_search(upper, m, label)) return std::nullopt;
  DescribedTool d;
  d.numbered = false;
  d.tool.description = m[1];
  if (auto size = size_in_description(d.tool.description, units.inch)) d.tool.diameter_mm = *size;
  apply_shape(d, d.tool.description);
  return d;
}

std::optional<DescribedTool> read_free_tool(const std::string& upper, DescriptionUnits units) {
  // "CHANGE TOOL: ...", "TOOL: ...", pcb2gcode's "MSG, CHANGE TOOL BIT TO CUTTER DIAMETER
  // 0.05906IN", a header's "USE A 1/32INCH BIT".
  static const std::regex prefix(
      R"(^\s*(?:MSG\s*,\s*)?(?:CHANGE\s+TOOL(?:\s+BIT\s+TO)?|TOOL\s*CHANGE|TOOL|USE\s+AN?)\s*:?\s*)");
  const std::string text = trim_separators(std::regex_replace(upper, prefix, ""));
  if (!guess_shape(text)) return std::nullopt;
  return sized_description(text, 0, false, units);
}

#undef NCJ_NUMBER

} // namespace ncjoule::detail
