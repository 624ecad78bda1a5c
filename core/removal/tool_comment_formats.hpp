// The tool descriptions CAM posts write in comments, one reader per format. Each reader takes
// one comment (upper case, without its delimiters) and gives the tool it describes, or nothing
// when the comment is not in its format. parse_tool_comments (tool_comments.cpp) decides which
// reader to try and where the tool's number comes from when the comment gives none.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "ncjoule/gcode.hpp"
#include "ncjoule/tool.hpp"

namespace ncjoule::detail {

// How the numbers of a description are read: the program's units (a bare "6" or ".5").
struct DescriptionUnits {
  bool inch = false;
  double mm_per_unit() const { return inch ? 25.4 : 1.0; }
};

// A tool a comment describes. `numbered` is false when the comment names no tool number (a
// FreeCAD tool controller, an Estlcam tool list, a description next to a tool change): the
// number is then the one the program selects nearby.
struct DescribedTool {
  Tool tool;
  bool numbered = true;
  // A note or warning about the description (an unknown type, read as a flat end mill); its
  // message does not name the tool, whose number the caller may only learn later.
  std::optional<Diagnostic> remark;
};

// Fusion 360 / HSM and the posts built on it (Fanuc, Haas, Mach3, LinuxCNC, Tormach, grbl and
// personal-use): "T1 D=6. CR=0. TAPER=118deg - ZMIN=-5. - FLAT END MILL".
std::optional<DescribedTool> read_fusion_tool(const std::string& upper, DescriptionUnits units);

// Mastercam: "1/2 FLAT ENDMILL TOOL - 1 DIA. OFF. - 1 LEN. - 1 DIA. - .5" and the piped form
// of its newer posts, " T1 | 1/2 FLAT ENDMILL | H1 | D1 | TOOL DIA. - .5".
std::optional<DescribedTool> read_mastercam_tool(const std::string& upper, DescriptionUnits units);

// CamBam: "T3 : 3.0" and "T0 : 50.8 SURFACING BIT" (diameter in program units, then the tool's
// comment), and its older "T0  3.175".
std::optional<DescribedTool> read_cambam_tool(const std::string& upper, DescriptionUnits units);

// A number, "=", and a description with a size: the shop style "T1 = .5 ENDMILL" and Vectric's
// tool list "5 = END MILL {0.2500 INCH} UPDOWN", "T2 = END MILL {0.5 INCHES}", "1 = END MILL
// {6 MM}".
std::optional<DescribedTool> read_numbered_list_tool(const std::string& upper,
                                                     DescriptionUnits units);

// A tool number and a diameter written with a key, as NX, SolidCAM, SolidWorks CAM and many
// hand-made posts write them: "T1 D10. R0.5 MILL_D10R0.5", "TOOL 3 DIA 12.0 CORNER RAD 1.",
// "T02 - 1/2 FLAT END MILL", "TOOL #4: 6MM BALL". The number stands alone: "TOOL: 1/8 IN END
// MILL" is a description, not tool 1.
std::optional<DescribedTool> read_keyed_tool(const std::string& upper, DescriptionUnits units);

// BlenderCAM / Fabex: "TOOL: D = 3.0 MM  TYPE END FLUTES 2" (metric scenes) or
// "TOOL: D = 0.125''  TYPE BALL FLUTES 2" (imperial), unnumbered, next to the tool change when
// the post writes one. Types END, BALL, BULLNOSE, VCARVE; the cone types are read as the nearest
// shape with a note.
std::optional<DescribedTool> read_blendercam_tool(const std::string& upper, DescriptionUnits units);

// FreeCAD: the tool controller's label, "TC: 6MM BALL END" (unnumbered).
std::optional<DescribedTool> read_freecad_tool(const std::string& upper, DescriptionUnits units);

// A free description with a size and a known tool word, as posts write it next to a tool change
// ("CHANGE TOOL: END MILL 3MM", "TOOL: END MILL {0.2500 INCH} UPDOWN", "1/4 FLAT ENDMILL") or in
// a tool list (Estlcam's "HSS 1-FLUTE ENDMILL, 3.175MM"). Unnumbered.
std::optional<DescribedTool> read_free_tool(const std::string& upper, DescriptionUnits units);

} // namespace ncjoule::detail
