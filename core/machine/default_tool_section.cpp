// [default_tool]: the tool a machine profile assumes where a program neither selects nor
// describes one (see assign_tools in removal.hpp).
#include "sections.hpp"

namespace ncjoule::profile_detail {

Tool read_default_tool(TableReader table, std::vector<std::string>& sources) {
  read_source(table, "default_tool", sources);
  ToolFields fields;
  fields.type = table.choice("type", {"flat", "ball", "bullnose", "drill", "chamfer"});
  fields.diameter_mm = table.quantity("diameter", Dimension::Length, Range::Positive);
  fields.corner_radius_mm =
      table.optional_quantity("corner_radius", Dimension::Length, Range::NonNegative);
  fields.point_angle_deg = table.optional_number("point_angle_deg", Range::Positive, 1, 180);
  fields.tip_diameter_mm =
      table.optional_quantity("tip_diameter", Dimension::Length, Range::NonNegative);
  fields.description = table.optional_string("description").value_or("");
  table.finish();
  std::string error;
  std::optional<Tool> tool = make_tool(fields, &error);
  if (!tool) {
    // make_tool names the field first ("diameter_mm: ..."), except for sizes that do not fit
    // together (a corner radius over the radius), which concern the diameter too.
    const std::size_t colon = error.find(": ");
    const bool named = colon != std::string::npos && error.find(' ') > colon;
    table.fail(named ? error.substr(0, colon) : "diameter_mm",
               named ? error.substr(colon + 2) : error);
  }
  if (tool->description == tool_shape_name(tool->shape))
    tool->description = "default tool of the machine profile";
  return *tool;
}

} // namespace ncjoule::profile_detail
