// Tools written out by hand: the type names of tool tables and the compact "N:TYPE:D[:...]"
// form of the command line.
#include <cctype>
#include <charconv>
#include <cmath>
#include <string>
#include <vector>

#include "ncjoule/removal.hpp"
#include "ncjoule/text.hpp"

namespace ncjoule {
namespace {

std::vector<std::string_view> split(std::string_view text, char separator) {
  std::vector<std::string_view> fields;
  for (;;) {
    const std::size_t at = text.find(separator);
    fields.push_back(text.substr(0, at));
    if (at == std::string_view::npos) return fields;
    text.remove_prefix(at + 1);
  }
}

} // namespace

std::optional<ToolShape> tool_shape_from_name(std::string_view name) {
  std::string low(name);
  for (char& c : low)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  if (low == "flat") return ToolShape::FlatEndMill;
  if (low == "ball") return ToolShape::BallEndMill;
  if (low == "bullnose") return ToolShape::BullNose;
  if (low == "drill") return ToolShape::Drill;
  if (low == "chamfer") return ToolShape::Chamfer;
  return std::nullopt;
}

std::optional<Tool> make_tool(const ToolFields& f, std::string* error) {
  auto fail = [&](std::string message) -> std::optional<Tool> {
    if (error) *error = std::move(message);
    return std::nullopt;
  };
  const auto shape = tool_shape_from_name(f.type);
  if (!shape)
    return fail("type: '" + f.type + "' is not one of flat, ball, bullnose, drill, chamfer");
  // Below a micrometre or above two metres is a typing or unit slip, and a stock model fine
  // enough for it would not fit in memory.
  if (!(f.diameter_mm >= 0.001 && f.diameter_mm <= 2000))
    return fail("diameter_mm: must be given, in mm, from 0.001 to 2000");
  Tool tool;
  tool.number = f.number;
  tool.shape = *shape;
  tool.diameter_mm = f.diameter_mm;
  if (tool.shape == ToolShape::BallEndMill) tool.corner_radius_mm = tool.diameter_mm / 2;
  if (tool.shape == ToolShape::Chamfer) tool.tip_angle_deg = 90;
  if (f.corner_radius_mm) tool.corner_radius_mm = *f.corner_radius_mm;
  if (f.point_angle_deg) tool.tip_angle_deg = *f.point_angle_deg;
  if (f.tip_diameter_mm) tool.tip_diameter_mm = *f.tip_diameter_mm;
  if (f.flute_length_mm) tool.cutting_length_mm = *f.flute_length_mm;
  if (f.shank_diameter_mm) tool.shank_diameter_mm = *f.shank_diameter_mm;
  if (f.flutes < 0 || f.flutes > 100) return fail("flutes: must be from 1 to 100 (0: unknown)");
  tool.flutes = f.flutes;
  tool.description =
      f.description.empty() ? std::string(tool_shape_name(tool.shape)) : f.description;
  if (const std::string problem = tool_problem(tool); !problem.empty())
    return fail("tool T" + std::to_string(tool.number) + " " + problem);
  return tool;
}

std::optional<Tool> parse_tool_spec(std::string_view text, std::vector<Diagnostic>* diagnostics,
                                    const TextOrigin& origin) {
  // A problem with the field at `field` (a view into `text`), or with the whole text.
  auto fail = [&](std::string message, std::string_view field = {}) -> std::optional<Tool> {
    const std::size_t offset = field.data() ? std::size_t(field.data() - text.data()) : 0;
    if (diagnostics) diagnostics->push_back(origin.at(offset, std::move(message)));
    return std::nullopt;
  };
  const std::vector<std::string_view> f = split(text, ':');
  if (f.size() < 3)
    return fail("a tool is N:TYPE:DIAMETER, e.g. 1:flat:6, 2:ball:6, 3:drill:6.8:118");
  ToolFields fields;
  const std::optional<double> number = parse_number(f[0]);
  if (!number || *number < 0 || *number != std::floor(*number) || *number > kMaxToolNumber)
    return fail("tool number '" + std::string(f[0]) + "' is not a whole number from 0 to " +
                    std::to_string(kMaxToolNumber),
                f[0]);
  fields.number = int(*number);
  fields.type = std::string(f[1]);
  const auto shape = tool_shape_from_name(f[1]);
  if (!shape)
    return fail("tool type '" + std::string(f[1]) +
                    "' is not one of flat, ball, bullnose, drill, chamfer",
                f[1]);
  // Which fields are lengths (mm, or with their unit: 0.25in): the diameter, a bull nose's
  // corner radius, a chamfer mill's tip diameter; the others are angles.
  const bool length_field[4] = {true, *shape == ToolShape::BullNose, *shape == ToolShape::Chamfer,
                                false};
  double v[4] = {0, 0, 0, 0};
  for (std::size_t k = 2; k < f.size(); ++k) {
    if (k - 2 >= 4) return fail("tool value '" + std::string(f[k]) + "' is one too many", f[k]);
    if (length_field[k - 2]) {
      const auto length = parse_length(f[k]);
      if (!length)
        return fail("tool value '" + std::string(f[k]) +
                        "' is not a length (a number in mm, or with its unit: 0.25in, 6mm)",
                    f[k]);
      v[k - 2] = length->second == LengthUnit::Inch ? length->first * 25.4 : length->first;
    } else {
      const std::optional<double> value = parse_number(f[k]);
      if (!value) return fail("tool value '" + std::string(f[k]) + "' is not a number", f[k]);
      v[k - 2] = *value;
    }
  }
  const std::size_t extras = f.size() - 3;
  fields.diameter_mm = v[0];
  switch (*shape) {
  case ToolShape::FlatEndMill:
  case ToolShape::BallEndMill:
    if (extras > 0) return fail("a flat or ball end mill takes only a diameter", f[3]);
    break;
  case ToolShape::BullNose:
    if (extras != 1) return fail("a bull nose is N:bullnose:DIAMETER:CORNER_RADIUS");
    fields.corner_radius_mm = v[1];
    break;
  case ToolShape::Drill:
    if (extras > 1) return fail("a drill is N:drill:DIAMETER[:POINT_ANGLE]", f[4]);
    if (extras) fields.point_angle_deg = v[1];
    break;
  case ToolShape::Chamfer:
    if (extras > 2)
      return fail("a chamfer mill is N:chamfer:DIAMETER[:ANGLE[:TIP_DIAMETER]]", f[5]);
    if (extras) fields.point_angle_deg = v[1];
    if (extras > 1) fields.tip_diameter_mm = v[2];
    break;
  }
  fields.description = std::string(text);
  std::string problem;
  std::optional<Tool> tool = make_tool(fields, &problem);
  // The sizes: about the diameter, or the sizes together.
  if (!tool) return fail(problem, f[2]);
  return tool;
}

} // namespace ncjoule
