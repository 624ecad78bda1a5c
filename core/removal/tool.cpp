// Tool profiles: the lower envelope of each tool shape and its inverse.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "ncjoule/removal.hpp"

namespace ncjoule {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool has_wider_shank(const Tool& tool) {
  return tool.cutting_length_mm > 0 && tool.shank_diameter_mm > tool.diameter_mm;
}

} // namespace

double Tool::tan_half_tip_angle() const {
  return std::nearbyint(std::tan(tip_angle_deg * std::numbers::pi / 360.0) * 1e12) * 1e-12;
}

double Tool::reach_radius() const {
  return has_wider_shank(*this) ? shank_diameter_mm / 2 : radius();
}

double Tool::envelope_height(double r) const {
  const double R = radius();
  if (r > R) {
    // Beyond the cutter only a wider shank can reach down, from the top of the flutes.
    if (has_wider_shank(*this) && r <= shank_diameter_mm / 2) return cutting_length_mm;
    return kInf;
  }
  switch (shape) {
  case ToolShape::FlatEndMill:
    return 0;
  case ToolShape::BallEndMill:
    return R - std::sqrt(std::max(0.0, R * R - r * r));
  case ToolShape::BullNose: {
    const double rc = std::min(corner_radius_mm, R);
    const double flat = R - rc;
    if (r <= flat) return 0;
    const double d = r - flat;
    return rc - std::sqrt(std::max(0.0, rc * rc - d * d));
  }
  case ToolShape::Drill:
    return r / tan_half_tip_angle();
  case ToolShape::Chamfer: {
    const double rt = tip_diameter_mm / 2;
    return r <= rt ? 0 : (r - rt) / tan_half_tip_angle();
  }
  }
  return 0;
}

double Tool::section_radius(double t) const {
  const double R = radius();
  if (t < 0) return -1;
  switch (shape) {
  case ToolShape::FlatEndMill:
    return R;
  case ToolShape::BallEndMill:
    return t >= R ? R : std::sqrt(std::max(0.0, R * R - (R - t) * (R - t)));
  case ToolShape::BullNose: {
    const double rc = std::min(corner_radius_mm, R);
    if (t >= rc) return R;
    return (R - rc) + std::sqrt(std::max(0.0, rc * rc - (rc - t) * (rc - t)));
  }
  case ToolShape::Drill:
    return std::min(R, t * tan_half_tip_angle());
  case ToolShape::Chamfer:
    return std::min(R, tip_diameter_mm / 2 + t * tan_half_tip_angle());
  }
  return R;
}

int typical_flutes(const Tool& tool) {
  const double d = tool.diameter_mm;
  if (tool.shape == ToolShape::Drill || tool.shape == ToolShape::Chamfer || d < 3) return 2;
  if (d <= 12) return 3;
  if (d <= 25) return 4;
  return std::max(4, int(std::lround(d / 12)));
}

std::string_view tool_shape_name(ToolShape shape) {
  switch (shape) {
  case ToolShape::FlatEndMill:
    return "flat end mill";
  case ToolShape::BallEndMill:
    return "ball end mill";
  case ToolShape::BullNose:
    return "bull nose end mill";
  case ToolShape::Drill:
    return "drill";
  case ToolShape::Chamfer:
    return "chamfer mill";
  }
  return "tool";
}

std::string tool_problem(const Tool& tool) {
  if (!(tool.diameter_mm > 0) || !std::isfinite(tool.diameter_mm))
    return "has no diameter (or a diameter that is not positive)";
  if (tool.shape == ToolShape::BullNose &&
      !(tool.corner_radius_mm >= 0 && tool.corner_radius_mm <= tool.radius() + 1e-9))
    return "has a corner radius larger than its radius";
  if ((tool.shape == ToolShape::Drill || tool.shape == ToolShape::Chamfer) &&
      !(tool.tip_angle_deg > 0 && tool.tip_angle_deg < 180))
    return "has a tip angle outside (0, 180) degrees";
  if (tool.shape == ToolShape::Chamfer &&
      !(tool.tip_diameter_mm >= 0 && tool.tip_diameter_mm < tool.diameter_mm))
    return "has a tip diameter not smaller than its diameter";
  return {};
}

} // namespace ncjoule
