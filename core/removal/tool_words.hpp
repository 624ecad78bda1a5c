// Reading a tool's shape and sizes from the free text CAM systems write about it.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "ncjoule/removal.hpp"

namespace ncjoule::detail {

// The shape a description names ("FLAT END MILL", "6mm Ball End", "1/2 BULLNOSE", "SPOT DRILL",
// "90 DEG CHAMFER", ...), with the tip angle a shape implies when the text gives none.
// std::nullopt when no known word is found.
struct ShapeGuess {
  ToolShape shape = ToolShape::FlatEndMill;
  double default_tip_angle_deg = 118;
  // Fusion 360 gives chamfer mills' TAPER from the axis (half the included angle).
  bool taper_is_half_angle = false;
};
std::optional<ShapeGuess> guess_shape(std::string_view upper_text);

// A size written at the start of a description or next to a unit: "1/2", "10.", "6mm", "0.25in".
// Returns the size in mm; `inch` says what a bare number means.
std::optional<double> size_in_description(std::string_view upper_text, bool inch);

// An angle written as "60 DEG", "90DEG", "90 DEGREE", "118°" in a description.
std::optional<double> angle_in_description(std::string_view upper_text);

} // namespace ncjoule::detail
