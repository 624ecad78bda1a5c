// ncjoule tools: the cutters a program runs with, described by their profile (shape, sizes),
// and the ways a user writes them down (--tool N:TYPE:D, the tables of job files and machine
// profiles). Shared by the machine profile (its default tool) and material removal, which gives
// the shapes their lower envelopes (core/removal/tool.cpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/diagnostic.hpp"

namespace ncjoule {

// The largest tool number ncjoule takes, from the command line (--tool), a job file or a tool
// table alike: controls number tools in the hundreds or thousands; beyond a million a number is
// a slip (and past 2^31 it would wrap into another tool's).
inline constexpr int kMaxToolNumber = 1000000;

enum class ToolShape : std::uint8_t {
  FlatEndMill,
  BallEndMill,
  BullNose, // flat bottom with a corner radius
  Drill,    // conical point of tip_angle_deg (included angle)
  Chamfer,  // V-bit / chamfer mill: cone of tip_angle_deg, optionally with a flat tip
};

// A rotating 3-axis tool, described by its profile. The tool is a solid of revolution around a
// vertical axis through its tip; only its lower envelope matters for removal from above.
struct Tool {
  int number = 0;
  ToolShape shape = ToolShape::FlatEndMill;
  double diameter_mm = 0;       // cutting diameter
  double corner_radius_mm = 0;  // bull nose (a ball end mill has diameter/2)
  double tip_angle_deg = 118;   // drill and chamfer: included angle of the cone
  double tip_diameter_mm = 0;   // chamfer: diameter of the flat at the tip (0 = pointed)
  double cutting_length_mm = 0; // flute length above the tip; 0 = unknown
  double shank_diameter_mm = 0; // 0 = same as diameter_mm
  int flutes = 0;               // cutting edges; 0 = unknown
  std::string description;      // as the source wrote it

  double radius() const { return diameter_mm / 2; }
  // The widest radius whose lower surface can touch the stock: the cutting radius, or the
  // shank's when the shank is wider than the cutter (and the cutting length is known).
  double reach_radius() const;
  // Height of the tool's lower surface above its tip at radial distance r from its axis
  // (0 at the tip); +infinity beyond reach_radius().
  double envelope_height(double r) const;
  // The inverse: radius of the tool's cross-section at height t above the tip (cutter part
  // only, capped at radius()); negative below the tip.
  double section_radius(double t) const;
  // tan(tip_angle_deg / 2) of a drill or chamfer tool, to 1e-12: the same on every C library
  // (their tan differs in the last bit, and the stock's columns on a cone's edge with it).
  double tan_half_tip_angle() const;
};

std::string_view tool_shape_name(ToolShape shape); // "flat end mill", ...

// The cutting edges a tool of its kind and size typically has, where nothing says (for the
// chip thickness of the cutting term): drills and engraving V-bits 2; end mills 2 below 3 mm,
// 3 to 12 mm, 4 to 25 mm; larger cutters (face and shell mills) one insert per 12 mm of
// diameter, at least 4.
int typical_flutes(const Tool& tool);

// Checks a tool for sizes removal cannot use (no diameter, corner radius larger than the
// radius, tip angle outside (0, 180)); empty when it is usable.
std::string tool_problem(const Tool& tool);

// The tool types of tool tables and of --tool: "flat", "ball", "bullnose", "drill",
// "chamfer" (any case); std::nullopt for anything else.
std::optional<ToolShape> tool_shape_from_name(std::string_view name);

// A tool written as "N:TYPE:DIAMETER[:EXTRA[:EXTRA]]" (mm and degrees), as on the command line:
//   1:flat:6   2:ball:6   3:bullnose:10:1.5 (corner radius)   4:drill:6.8:118 (point angle,
//   118 when left out)   5:chamfer:12:90:0.5 (included angle, 90 when left out; tip flat).
// Returns std::nullopt, with an error in `diagnostics` placed at the field it concerns within
// `origin`, when the text is not understood or the tool is unusable.
std::optional<Tool> parse_tool_spec(std::string_view text,
                                    std::vector<Diagnostic>* diagnostics = nullptr,
                                    const TextOrigin& origin = {});

// A tool as the table of a job file or a machine profile writes it: the type name and sizes in mm
// and degrees; what is left out takes the type's default (a ball end mill's corner radius is
// half its diameter, a drill's point 118 degrees, a chamfer mill's angle 90 degrees).
struct ToolFields {
  int number = 0;
  std::string type; // "flat", "ball", "bullnose", "drill", "chamfer" (any case)
  double diameter_mm = 0;
  std::optional<double> corner_radius_mm, point_angle_deg, tip_diameter_mm;
  std::optional<double> flute_length_mm, shank_diameter_mm;
  int flutes = 0; // 0: unknown
  std::string description;
};
// Returns std::nullopt with *error set (naming the field) when the type is unknown or the sizes
// are unusable: a check for readers, which place the message in their own diagnostics.
std::optional<Tool> make_tool(const ToolFields& fields, std::string* error = nullptr);

} // namespace ncjoule
