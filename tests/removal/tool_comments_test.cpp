// Reading tools from the comments CAM posts write: one case per post format, each written from
// the header that post produces.
#include <doctest/doctest.h>

#include "fixture.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

// Reads a program's tool comments as estimate does: the interpreter first (units, the lines
// that select tools), then the comments.
std::map<int, Tool> read_tools(const std::string& text, std::vector<Diagnostic>& diags,
                               std::string_view dialect = {}) {
  const SourceFile f = make_source("t.nc", text);
  InterpreterOptions options;
  if (!dialect.empty()) options.dialect = find_dialect(dialect);
  ToolCommentContext context;
  const InterpretResult run = interpret(f, options, [&](const CanonCommand& c) { context.add(c); });
  for (const Diagnostic& d : run.diagnostics)
    REQUIRE_MESSAGE(d.severity != Severity::Error, d.message);
  context.dialect = run.dialect;
  return parse_tool_comments(f, context, diags);
}

bool has_warning(const std::vector<Diagnostic>& diags) {
  for (const Diagnostic& d : diags)
    if (d.severity != Severity::Note) return true;
  return false;
}

} // namespace

TEST_CASE("Fusion 360 / HSM tool comments") {
  std::vector<Diagnostic> diags;
  const auto tools = read_tools("%\nO1001\n"
                                "(T1 D=6. CR=0. - ZMIN=-5. - FLAT END MILL)\n"
                                "(T2 D=8. CR=4. - ZMIN=-3. - BALL END MILL)\n"
                                "(T3 D=10. CR=1. - ZMIN=-2. - BULLNOSE END MILL)\n"
                                "(T4 D=5. CR=0. TAPER=118deg - ZMIN=-12. - DRILL)\n"
                                "(T5 D=12. CR=0. TAPER=45deg - ZMIN=-1. - CHAMFER MILL)\n"
                                "G90 G94 G17\nG21\nT1 M6\n%\n",
                                diags);
  CHECK(diags.empty());
  REQUIRE(tools.size() == 5);
  CHECK(tools.at(1).shape == ToolShape::FlatEndMill);
  CHECK(tools.at(1).diameter_mm == 6);
  CHECK(tools.at(2).shape == ToolShape::BallEndMill);
  CHECK(tools.at(3).shape == ToolShape::BullNose);
  CHECK(tools.at(3).corner_radius_mm == 1);
  CHECK(tools.at(4).shape == ToolShape::Drill);
  CHECK(tools.at(4).tip_angle_deg == 118);
  CHECK(tools.at(5).shape == ToolShape::Chamfer);
  CHECK(tools.at(5).tip_angle_deg == 90); // Fusion's taper is measured from the axis

  SUBCASE("inch programs") {
    std::vector<Diagnostic> d2;
    const auto inch = read_tools("(T7 D=0.25 CR=0. - ZMIN=-0.2 - FLAT END MILL)\nG20\n", d2);
    REQUIRE(inch.count(7));
    CHECK(inch.at(7).diameter_mm == doctest::Approx(6.35));
  }
  SUBCASE("unknown types and bad sizes are reported") {
    std::vector<Diagnostic> d2;
    const auto t =
        read_tools("(T8 D=3. CR=0. - ZMIN=-1. - WIDGET)\n(T9 D=0. - FLAT END MILL)\n", d2);
    CHECK(t.count(8) == 1);
    CHECK(t.count(9) == 0);
    REQUIRE(d2.size() == 2);
    CHECK(d2[0].severity == Severity::Warning);
    CHECK(d2[0].line == 1);
    CHECK(d2[0].message.find("WIDGET") != std::string::npos);
    CHECK(d2[1].line == 2);
  }
}

TEST_CASE("FreeCAD tool controller comments") {
  std::vector<Diagnostic> diags;
  const auto tools = read_tools("(Exported by FreeCAD)\nG21\n"
                                "(begin operation: TC: 6mm Ball End)\n"
                                "(TC: 6mm Ball End)\nM6 T2\nG43 H2\n"
                                "(TC: 5mm Endmill)\nM6 T1\n"
                                "(TC: 60 Deg V-Bit 10mm)\nM6 T3\n",
                                diags);
  CHECK(diags.empty());
  REQUIRE(tools.size() == 3);
  CHECK(tools.at(2).shape == ToolShape::BallEndMill);
  CHECK(tools.at(2).diameter_mm == 6);
  CHECK(tools.at(1).shape == ToolShape::FlatEndMill);
  CHECK(tools.at(1).diameter_mm == 5);
  CHECK(tools.at(3).shape == ToolShape::Chamfer);
  CHECK(tools.at(3).tip_angle_deg == 60);
  CHECK(tools.at(3).diameter_mm == 10);
}

TEST_CASE("Mastercam tool comments") {
  std::vector<Diagnostic> diags;
  const auto tools = read_tools("%\nO0000(PART)\n(TOOL - 1 DIA. OFF. - 1 LEN. - 1 DIA. - 6.)\n"
                                "(8. BALL ENDMILL TOOL - 2 DIA. OFF. - 2 LEN. - 2 DIA. - 8.)\n"
                                "( T3 | 10. SPOT DRILL | H3 | TOOL DIA. - 10. )\n"
                                "G21\n%\n",
                                diags);
  REQUIRE(tools.size() == 3);
  CHECK(tools.at(1).diameter_mm == 6);
  CHECK(tools.at(1).shape == ToolShape::FlatEndMill);
  CHECK(tools.at(2).diameter_mm == 8);
  CHECK(tools.at(2).shape == ToolShape::BallEndMill);
  CHECK(tools.at(3).diameter_mm == 10);
  CHECK(tools.at(3).shape == ToolShape::Drill);
  CHECK(tools.at(3).tip_angle_deg == 90);
  // Tool 1 gave no type: a note, not a warning.
  for (const Diagnostic& d : diags)
    CHECK(d.severity == Severity::Note);

  SUBCASE("inch") {
    std::vector<Diagnostic> d2;
    const auto in =
        read_tools("(1/2 FLAT ENDMILL TOOL - 4 DIA. OFF. - 4 LEN. - 4 DIA. - .5)\nG20 G90\n", d2);
    REQUIRE(in.count(4));
    CHECK(in.at(4).diameter_mm == doctest::Approx(12.7));
  }
}

TEST_CASE("Fusion 360 personal-use and Tormach headers") {
  std::vector<Diagnostic> diags;
  // The personal-use grbl post writes two spaces after the number; Tormach's inch headers give
  // the taper of a flat end mill as 0deg.
  const auto grbl =
      read_tools("(T1  D=3.175 CR=0 - ZMIN=-1 - flat end mill)\nG90 G21\nT1\n", diags);
  REQUIRE(grbl.count(1));
  CHECK(grbl.at(1).diameter_mm == doctest::Approx(3.175));
  CHECK(grbl.at(1).shape == ToolShape::FlatEndMill);
  const auto tormach = read_tools("(T3 D=0.25 CR=0. TAPER=0deg - ZMIN=-0.5 - flat end mill)\n"
                                  "(T4 D=0.125 CR=0.0625 - ZMIN=-0.2 - ball end mill)\nG20\n",
                                  diags);
  REQUIRE(tormach.size() == 2);
  CHECK(tormach.at(3).diameter_mm == doctest::Approx(6.35));
  CHECK(tormach.at(4).shape == ToolShape::BallEndMill);
  CHECK(tormach.at(4).corner_radius_mm == doctest::Approx(1.5875));
  CHECK_FALSE(has_warning(diags));
}

TEST_CASE("Estlcam: the required tools list and the tool change comments") {
  std::vector<Diagnostic> diags;
  SUBCASE("one tool, never selected: it is tool 0") {
    const auto tools = read_tools("(Project 100)\n(Created by Estlcam version 11 build 11.245)\n"
                                  "(Machining time about 00:00:08 hours)\n\n(Required tools:)\n"
                                  "(HSS 1-Flute Endmill, 3.175mm)\nG21\nG90\nG94\nM03 S24000\n"
                                  "G00 Z5.0000\n\n\n(No. 1: Engraving 1)\nG00 X0.0000 Y25.4000\n"
                                  "G01 Z-1.0000 F600\nM05\nM30\n",
                                  diags);
    REQUIRE(tools.size() == 1);
    REQUIRE(tools.count(0));
    CHECK(tools.at(0).diameter_mm == doctest::Approx(3.175)); // not the "1" of "1-Flute"
    CHECK(tools.at(0).shape == ToolShape::FlatEndMill);
    CHECK_FALSE(has_warning(diags));
  }
  SUBCASE("several tools: numbered by the names at their tool changes") {
    const auto tools = read_tools("(Required tools:)\n(End mill 3mm)\n(Ball nose 6mm)\nG21\nG90\n"
                                  "M05\nT1 M06 (Change tool: End mill 3mm)\nM03\nG01 Z-1 F600\n"
                                  "M05\nT2 M06 (Change tool: Ball nose 6mm)\nM03\nG01 Z-2\nM30\n",
                                  diags);
    REQUIRE(tools.size() == 2);
    CHECK(tools.at(1).diameter_mm == 3);
    CHECK(tools.at(2).diameter_mm == 6);
    CHECK(tools.at(2).shape == ToolShape::BallEndMill);
    CHECK_FALSE(has_warning(diags));
  }
  SUBCASE("the list wins over a header's prose, which also names sizes of the part") {
    // Estlcam 11, as a user's start text writes it above the list.
    const auto tools = read_tools(
        "( Provides a 1.5mm depth cut-out in the spoil-board in which to slot the plates )\n"
        "( Tool is an HSS 3.175mm single-flute endmill running at 18335rpm )\n\n"
        "(Project spoilboard-cutout)\n(Created by Estlcam version 11 build 11.107)\n\n"
        "(Required tools:)\n(Al - HSS 1-Flute Endmill, 3.175mm)\n\nG90\nM03 S18335\n"
        "G00 Z20.0000\nG00 X1.9 Y2.1\nG01 Z-0.5 F60\nG01 X61.6 F1164\nM05\nM30\n",
        diags);
    REQUIRE(tools.size() == 1);
    REQUIRE(tools.count(0));
    CHECK(tools.at(0).diameter_mm == doctest::Approx(3.175));
    CHECK_FALSE(has_warning(diags));
  }
  SUBCASE("a header's descriptions of one geometry are one tool") {
    const auto tools = read_tools("( Tool is an HSS 2mm 2-flute endmill running at 19404rpm )\n"
                                  "( Use a 2mm end mill )\nG21 G90\nG01 Z-1 F600\nM30\n",
                                  diags);
    REQUIRE(tools.count(0));
    CHECK(tools.at(0).diameter_mm == 2);
    CHECK_FALSE(has_warning(diags));
  }
  SUBCASE("the first listed tool no tool change names is in the spindle at the start") {
    // Estlcam 10: its start code changes no tool; the list is in the order of use and a nested
    // "(R)" closes the comment early ("unexpected ')'" from the interpreter).
    const auto tools = read_tools(
        "(Required tools:)\n(HSS Twist Drill, 3mm (R))\n(HSS 1-Flute Endmill, 3.175mm)\n\n"
        "G90\nM03 S9000\nG00 Z5\n(No. 1: Drill Centre Hole)\nG01 Z-2 F300\nG00 Z5\nM05\n"
        "T1 M06 (Change tool: HSS 1-Flute Endmill, 3.175mm)\nM03\nG01 Z-1 F300\nM30\n",
        diags);
    REQUIRE(tools.size() == 2);
    CHECK(tools.at(1).diameter_mm == doctest::Approx(3.175));
    REQUIRE(tools.count(0));
    CHECK(tools.at(0).shape == ToolShape::Drill);
    CHECK(tools.at(0).diameter_mm == 3);
    CHECK_FALSE(has_warning(diags));
  }
  SUBCASE("a program that changes tools before it moves has no tool at the start") {
    // A start code with a tool change: the listed drill no change names is not guessed in.
    const auto tools = read_tools(
        "(Required tools:)\n(HSS Twist Drill, 3mm)\n(HSS 1-Flute Endmill, 3.175mm)\n\nG90\n"
        "T1 M06 (Change tool: HSS 1-Flute Endmill, 3.175mm)\nM03 S9000\nG00 Z5\n"
        "G01 Z-1 F300\nM30\n",
        diags);
    CHECK_FALSE(tools.count(0));
    REQUIRE(tools.count(1));
  }
  SUBCASE("two listed tools of one geometry are used up by two tool changes") {
    // A reamer's pre-drill and finish drill, both 4.5 mm, both changed to as T2.
    const auto tools = read_tools(
        "(Required tools:)\n(HSS Twist Drill, 4.5mm (R))\n(HSS 2-Flute Endmill, 3.175mm)\n"
        "(HSS Twist Drill, 4.5mm (F))\n\nG90\nM03 S16000\nG01 Z-1 F300\nM05\n"
        "T2 M06 (Change tool: HSS Twist Drill, 4.5mm R)\nM03\nG01 Z-2\nM05\n"
        "T1 M06 (Change tool: HSS 2-Flute Endmill, 3.175mm)\nM03\nG01 Z-3\nM05\n"
        "T2 M06 (Change tool: HSS Twist Drill, 4.5mm F)\nM03\nG01 Z-4\nM30\n",
        diags);
    CHECK_FALSE(tools.count(0)); // every listed tool is named by a change
    REQUIRE(tools.count(1));
    CHECK(tools.at(2).shape == ToolShape::Drill);
  }
  SUBCASE("several tools and no tool change: none is guessed") {
    const auto tools =
        read_tools("(Required tools:)\n(End mill 3mm)\n(End mill 6mm)\nG21\nG01 Z-1 F600\n", diags);
    CHECK(tools.empty());
    CHECK(has_warning(diags));
  }
}

TEST_CASE("CamBam: ( T3 : 3.0 ), its comment, and the older ( T0  3.175 )") {
  std::vector<Diagnostic> diags;
  const auto tools = read_tools("( Made using CamBam - http://www.cambam.co.uk )\n"
                                "( front_Box 7/14/2020 5:44:34 PM )\n( Post processor: Default )\n"
                                "( T2 : 2.0 )\nG21 G90 G64 G40\nG0 Z10.0\n( T2 : 2.0 )\nT2 M6\n"
                                "( Contour2 )\nG17\nM3 S3000\n( T0 : 50.8 surfacing bit )\n"
                                "T0 M6\n( T5  3.175 )\nT5 M6\n",
                                diags);
  REQUIRE(tools.size() == 3);
  CHECK(tools.at(2).diameter_mm == 2);
  CHECK(tools.at(0).diameter_mm == doctest::Approx(50.8));
  CHECK(tools.at(0).description == "SURFACING BIT");
  CHECK(tools.at(5).diameter_mm == doctest::Approx(3.175));
  CHECK_FALSE(has_warning(diags)); // free text that names no shape is a note for CamBam

  SUBCASE("inch, and an engraving tool of no size") {
    std::vector<Diagnostic> d2;
    const auto inch = read_tools("( T1 : 0.25 )\n( T0 : 0.0 )\nG20 G90 G64 G40\nT1 M6\n", d2);
    REQUIRE(inch.size() == 1);
    CHECK(inch.at(1).diameter_mm == doctest::Approx(6.35));
    CHECK(has_warning(d2)); // T0 has no diameter: said, and ignored
  }
}

TEST_CASE("Vectric: the tool list and the name after the tool change") {
  std::vector<Diagnostic> diags;
  // Vectric writes the tool's own parentheses as braces inside comments.
  const auto tools =
      read_tools("( Profile 1 )\n( File created: Saturday November 21 2020 - 02:18 PM)\n"
                 "( for Mach2/3 from Vectric )\n( Material Size)\n"
                 "( X= 76.000, Y= 5.500, Z= 1.000)\n(Toolpaths used in this file:)\n"
                 "(Profile 1)\n(Tools used in this file: )\n"
                 "(5 = End Mill {0.2500 inch} UpDown)\n"
                 "(2 = Ball Nose {1/8\"})\n(3 = V-Bit {60 deg 1/2\"})\n"
                 "N100G00G20G17G90G40G49G80\nN120T5M06\n"
                 "N130 (Tool: End Mill {0.2500 inch} UpDown)\nN140G00G43Z2.0000H5\n",
                 diags);
  REQUIRE(tools.size() == 3);
  CHECK(tools.at(5).diameter_mm == doctest::Approx(6.35));
  CHECK(tools.at(5).shape == ToolShape::FlatEndMill);
  CHECK(tools.at(2).diameter_mm == doctest::Approx(3.175));
  CHECK(tools.at(2).shape == ToolShape::BallEndMill);
  CHECK(tools.at(3).shape == ToolShape::Chamfer);
  CHECK(tools.at(3).tip_angle_deg == 60);
  CHECK(tools.at(3).diameter_mm == doctest::Approx(12.7));
  CHECK(diags.empty());

  SUBCASE("metric list, \"T\" prefix") {
    std::vector<Diagnostic> d2;
    const auto mm = read_tools("(1 = End Mill {6 mm})\n(T2 = End Mill {0.5 inches})\nG21\n", d2);
    REQUIRE(mm.size() == 2);
    CHECK(mm.at(1).diameter_mm == 6);
    CHECK(mm.at(2).diameter_mm == doctest::Approx(12.7));
  }
}

TEST_CASE("shop style: (T1 = .5 ENDMILL) and a name on the tool change line") {
  std::vector<Diagnostic> diags;
  const auto tools = read_tools("(T1 = .5 ENDMILL)\n(T2 = 3/8 BALL)\nG20 G90\n"
                                "T3 M6 (1/4 FLAT ENDMILL)\nG0 Z1\nT4 M6\n(2D CONTOUR1)\n",
                                diags);
  REQUIRE(tools.size() == 3); // "2D CONTOUR1" after T4 names no tool
  CHECK(tools.at(1).diameter_mm == doctest::Approx(12.7));
  CHECK(tools.at(2).diameter_mm == doctest::Approx(9.525));
  CHECK(tools.at(2).shape == ToolShape::BallEndMill);
  CHECK(tools.at(3).diameter_mm == doctest::Approx(6.35));
  CHECK_FALSE(has_warning(diags));
}

TEST_CASE("a number and a keyed diameter: NX, SolidCAM and SolidWorks CAM tool lists") {
  std::vector<Diagnostic> diags;
  const auto tools = read_tools("(T1 D10. R0.5 MILL_D10R0.5)\n(TOOL 3 DIA 12.0 CORNER RAD 1.)\n"
                                "(TOOL #4: 6MM BALL)\n(T06 DIAMETER: 8 DRILL 118 DEG)\nG21\n",
                                diags);
  REQUIRE(tools.size() == 4);
  CHECK(tools.at(1).diameter_mm == 10);
  CHECK(tools.at(1).shape == ToolShape::BullNose);
  CHECK(tools.at(1).corner_radius_mm == 0.5);
  CHECK(tools.at(3).diameter_mm == 12);
  CHECK(tools.at(3).corner_radius_mm == 1);
  CHECK(tools.at(4).shape == ToolShape::BallEndMill);
  CHECK(tools.at(4).diameter_mm == 6);
  CHECK(tools.at(6).shape == ToolShape::Drill);
  CHECK(tools.at(6).diameter_mm == 8);
  CHECK_FALSE(has_warning(diags));

  SUBCASE("inch: (T02 - 1/2 FLAT END MILL)") {
    std::vector<Diagnostic> d2;
    const auto inch = read_tools("(T02 - 1/2 FLAT END MILL)\nG20\n", d2);
    REQUIRE(inch.count(2));
    CHECK(inch.at(2).diameter_mm == doctest::Approx(12.7));
  }
  SUBCASE("comments that only look like tools are not read") {
    std::vector<Diagnostic> d2;
    const auto none = read_tools("(T1 H1 D1 ROUGH)\n(TOLERANCE=0.01)\n(T1 ROUGHING 3 PASSES)\n"
                                 "(TOOL CHANGE)\n(DEPTH = 3MM)\nG21\n",
                                 d2);
    CHECK(none.empty());
  }
}

TEST_CASE("a tool list's description is kept over a different one at the tool change") {
  std::vector<Diagnostic> diags;
  const auto tools = read_tools(
      "(T1 D=6. CR=0. - ZMIN=-5. - FLAT END MILL)\nG21\nT1 M6 (8MM BALL END MILL)\n", diags);
  REQUIRE(tools.size() == 1);
  CHECK(tools.at(1).diameter_mm == 6);
  CHECK(tools.at(1).shape == ToolShape::FlatEndMill);
  REQUIRE(diags.size() == 1);
  CHECK(diags[0].severity == Severity::Note);
}

TEST_CASE("CAMotics TPL: the tool's name just before its tool change") {
  std::vector<Diagnostic> diags;
  const auto tools = read_tools("G90 G21\nT1 M6 (Reset tool)\n(Pockets)\n"
                                "(Tool: 1/4 in Carbide End Mill)\nT1 M6\nG0 Z2\nG1 Z-1 F300\n"
                                "G0 Z2\n\n(Profiles)\n(Tool: 1/8 in Carbide End Mill)\nT2 M6\n",
                                diags);
  REQUIRE(tools.size() == 2);
  CHECK(tools.at(1).diameter_mm == doctest::Approx(6.35));
  CHECK(tools.at(2).diameter_mm == doctest::Approx(3.175));
  CHECK(diags.empty());
}

TEST_CASE("pcb2gcode: the cutter named in the message after its tool change") {
  std::vector<Diagnostic> diags;
  const auto inch = read_tools("( pcb2gcode 3.0.1 )\nG94\nG20\nG90\nG00 Z1.00000\nT1\nM5\n"
                               "G04 P1.00000\n(MSG, Change tool bit to cutter diameter 0.05906in)\n"
                               "M6\nM0\nM3\n",
                               diags);
  REQUIRE(inch.count(1));
  CHECK(inch.at(1).diameter_mm == doctest::Approx(0.05906 * 25.4));
  CHECK(inch.at(1).shape == ToolShape::FlatEndMill);
  const auto mm =
      read_tools("G21\nT3\nM5\nG04 P1\n(MSG, Change tool bit to mill diameter 0.15000mm)\n"
                 "M0\n",
                 diags);
  REQUIRE(mm.count(3));
  CHECK(mm.at(3).diameter_mm == doctest::Approx(0.15));
  CHECK_FALSE(has_warning(diags));
}

TEST_CASE("a program that selects no tool: the one its header names (Eagle stepcraft.ulp)") {
  std::vector<Diagnostic> diags;
  const auto tools = read_tools(
      "(RS-274 Compatible G-code generated for UCCNC controller and Stepcraft 2 Mill)\n"
      "(Created by in EagleCAD with the stepcraft.ulp 0.2.)\n(Use a 1/32inch Bit)\n\nG90 G94 G49\n"
      "G21\nG00 Z5\nG01 Z-0.1 F300\n(Use a 1/64inch Bit)\n",
      diags);
  REQUIRE(tools.size() == 1);
  REQUIRE(tools.count(0));
  CHECK(tools.at(0).diameter_mm == doctest::Approx(25.4 / 32));
  CHECK_FALSE(has_warning(diags));
}

TEST_CASE("BlenderCAM / Fabex: (Tool: D = 3.0 mm  type END flutes 2)") {
  std::vector<Diagnostic> diags;
  // Its grbl post selects no tool: the program cuts with the one the comment describes.
  const auto end_mill = read_tools("(Created with grbl post processor 2024/01/11 09:36)\nG21\n"
                                   "(G-code generated with BlenderCAM and NC library)\nG17G90\n"
                                   "(Tool: D = 3.0 mm  type END flutes 2)\nS12000M03\nG00 Z2.0\n",
                                   diags);
  REQUIRE(end_mill.count(0));
  CHECK(end_mill.at(0).shape == ToolShape::FlatEndMill);
  CHECK(end_mill.at(0).diameter_mm == doctest::Approx(3.0));
  CHECK(end_mill.at(0).flutes == 2);
  CHECK(diags.empty());
  // An imperial scene writes inches with two apostrophes; a post with tool changes numbers it.
  const auto ball =
      read_tools("G20\nT2 M06\n(Tool: D = 0.125''  type BALL flutes 4)\nG0 Z0.5\n", diags);
  REQUIRE(ball.count(2));
  CHECK(ball.at(2).shape == ToolShape::BallEndMill);
  CHECK(ball.at(2).diameter_mm == doctest::Approx(3.175));
  CHECK(ball.at(2).corner_radius_mm == doctest::Approx(1.5875));
  // Cone cutters: the nearest shape, with a note that says so.
  diags.clear();
  const auto cone = read_tools("G21\n(Tool: D = 6.0 mm  type CYLCONE flutes 2)\nG0 Z5\n", diags);
  REQUIRE(cone.count(0));
  CHECK(cone.at(0).shape == ToolShape::Chamfer);
  REQUIRE(diags.size() == 1);
  CHECK(diags[0].severity == Severity::Note);
  CHECK(diags[0].message.find("CYLCONE") != std::string::npos);
}

TEST_CASE("a spot drill's or countersink's bare leading number is its point angle, not its size") {
  std::vector<Diagnostic> diags;
  const auto tools =
      read_tools("%\nO78242\n(T2 .375 DRILL)\n(T8 90 SPOT DRILL)\n"
                 "(T9 82 COUNTERSINK)\n(T10 12 SPOT DRILL)\n(T11 82 COUNTERSINK 16MM)\n"
                 "G21\n%\n",
                 diags);
  CHECK(tools.at(2).diameter_mm == 0.375);
  CHECK(tools.count(8) == 0); // its size is not written: not a 90 mm tool
  CHECK(tools.count(9) == 0);
  CHECK(tools.at(10).diameter_mm == 12); // 12 is no point angle: a 12 mm spot drill
  CHECK(tools.at(10).tip_angle_deg == 90);
  CHECK(tools.at(11).diameter_mm == 16);
  CHECK(tools.at(11).tip_angle_deg == 82);
}
