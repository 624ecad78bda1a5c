// Shape words and sizes in CAM tool descriptions.
#include "tool_words.hpp"

#include <cctype>
#include <cstdlib>
#include <regex>

namespace ncjoule::detail {
namespace {

bool has(std::string_view text, std::string_view word) {
  return text.find(word) != std::string_view::npos;
}

// Tools made by their point: spot drills, countersinks, chamfer mills.
bool names_point_angle(std::string_view t) {
  return has(t, "SPOT") || has(t, "COUNTER SINK") || has(t, "COUNTERSINK") || has(t, "CSINK") ||
         has(t, "CHAMFER");
}

// The included angles such tools are sold with (degrees).
bool is_standard_point_angle(double v) {
  for (const double angle : {60.0, 82.0, 90.0, 100.0, 110.0, 118.0, 120.0, 135.0, 140.0, 142.0})
    if (v == angle) return true;
  return false;
}

} // namespace

std::optional<ShapeGuess> guess_shape(std::string_view t) {
  ShapeGuess g;
  // Order matters: "BALL END MILL" is a ball, "SPOT DRILL" is a 90-degree drill, and
  // "CHAMFER" wins over "MILL".
  if (has(t, "BALL") || has(t, "LOLLIPOP")) {
    g.shape = ToolShape::BallEndMill;
  } else if (has(t, "BULL") || has(t, "TORUS") || has(t, "TOROID")) {
    g.shape = ToolShape::BullNose;
  } else if (has(t, "CHAMFER") || has(t, "V-BIT") || has(t, "VBIT") || has(t, "V BIT") ||
             has(t, "V-CUTTER") || has(t, "ENGRAV") || has(t, "TAPERED MILL")) {
    g.shape = ToolShape::Chamfer;
    g.default_tip_angle_deg = 90;
    g.taper_is_half_angle = true;
  } else if (has(t, "SPOT") || has(t, "COUNTER SINK") || has(t, "COUNTERSINK") || has(t, "CSINK")) {
    g.shape = ToolShape::Drill;
    g.default_tip_angle_deg = 90;
  } else if (has(t, "DRILL")) { // twist drills; a centre drill is read by its point
    g.shape = ToolShape::Drill;
  } else if (has(t, "END MILL") || has(t, "ENDMILL") || has(t, "FLAT") || has(t, "FACE") ||
             has(t, "SLOT") || has(t, "MILL") || has(t, "REAM") || has(t, "BOR") || has(t, "TAP") ||
             has(t, "CUTTER") || has(t, "BIT")) { // router bits, pcb2gcode's "cutter"
    g.shape = ToolShape::FlatEndMill;
  } else {
    return std::nullopt;
  }
  return g;
}

std::optional<double> size_in_description(std::string_view t, bool inch) {
  // "6mm", "0.25 inch", "1/4\"", "{0.5 inches}" (Vectric), "6 MM".
  static const std::regex with_unit(R"((?:(\d+)/(\d+)|(\d+(?:\.\d*)?|\.\d+))\s*(MM|IN\b|INCH|"))");
  static const std::regex leading(R"(^\s*(?:(\d+)/(\d+)|(\d+(?:\.\d*)?|\.\d+))(?:\s|$|[^\d/]))");
  std::cmatch m;
  const char* b = t.data();
  const char* e = t.data() + t.size();
  if (std::regex_search(b, e, m, with_unit)) {
    double v;
    if (m[1].matched) {
      const double den = std::strtod(m[2].str().c_str(), nullptr);
      if (den == 0) return std::nullopt;
      v = std::strtod(m[1].str().c_str(), nullptr) / den;
    } else {
      v = std::strtod(m[3].str().c_str(), nullptr);
    }
    return m[4].str() == "MM" ? v : v * 25.4;
  }
  if (std::regex_search(b, e, m, leading)) {
    double v;
    if (m[1].matched) {
      const double den = std::strtod(m[2].str().c_str(), nullptr);
      if (den == 0) return std::nullopt;
      v = std::strtod(m[1].str().c_str(), nullptr) / den;
    } else {
      v = std::strtod(m[3].str().c_str(), nullptr);
      // "90 SPOT DRILL", "82 COUNTERSINK": the bare number of a tool named by its point is its
      // point angle, not a 90 mm (or 90 inch) diameter no such tool has.
      if (names_point_angle(t) && is_standard_point_angle(v)) return std::nullopt;
    }
    return inch ? v * 25.4 : v;
  }
  return std::nullopt;
}

std::optional<double> angle_in_description(std::string_view t) {
  static const std::regex angle(R"((\d+(?:\.\d*)?)\s*(?:DEG|\xC2\xB0))");
  std::cmatch m;
  if (std::regex_search(t.data(), t.data() + t.size(), m, angle))
    return std::strtod(m[1].str().c_str(), nullptr);
  // "82 COUNTERSINK": the leading bare number size_in_description leaves as an angle.
  static const std::regex leading(R"(^\s*(\d+(?:\.\d*)?)(?:\s|$))");
  if (names_point_angle(t) && std::regex_search(t.data(), t.data() + t.size(), m, leading))
    if (const double v = std::strtod(m[1].str().c_str(), nullptr); is_standard_point_angle(v))
      return v;
  return std::nullopt;
}

} // namespace ncjoule::detail
