// Tool profiles and reading tools from CAM comments.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "fixture.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("tool lower envelopes") {
  const Tool flat = flat_end_mill(1, 10);
  CHECK(flat.envelope_height(0) == 0);
  CHECK(flat.envelope_height(5) == 0);
  CHECK(std::isinf(flat.envelope_height(5.01)));

  const Tool ball = ball_end_mill(2, 10);
  CHECK(ball.envelope_height(0) == 0);
  CHECK(ball.envelope_height(3) == doctest::Approx(5 - 4)); // 3-4-5 triangle
  CHECK(ball.envelope_height(5) == doctest::Approx(5));

  Tool bull = flat_end_mill(3, 10);
  bull.shape = ToolShape::BullNose;
  bull.corner_radius_mm = 1;
  CHECK(bull.envelope_height(4) == 0);
  CHECK(bull.envelope_height(5) == doctest::Approx(1));
  CHECK(bull.envelope_height(4.6) == doctest::Approx(1 - 0.8));

  const Tool d = drill(4, 8, 118);
  CHECK(d.envelope_height(4) == doctest::Approx(4 / std::tan(59 * std::numbers::pi / 180)));

  Tool vbit = flat_end_mill(5, 10);
  vbit.shape = ToolShape::Chamfer;
  vbit.tip_angle_deg = 90;
  vbit.tip_diameter_mm = 1;
  CHECK(vbit.envelope_height(0.5) == 0);
  CHECK(vbit.envelope_height(3.5) == doctest::Approx(3));

  // A 3 mm cutter on a 6 mm shank: beyond the flutes the shank reaches down to 8 mm.
  Tool necked = flat_end_mill(6, 3);
  necked.cutting_length_mm = 8;
  necked.shank_diameter_mm = 6;
  CHECK(necked.reach_radius() == 3);
  CHECK(necked.envelope_height(2) == 8);
  CHECK(std::isinf(necked.envelope_height(3.1)));

  // The section radius inverts the envelope where the profile rises (flat parts excepted, where
  // the section is the whole flat).
  for (const Tool& t : {ball, bull, d, vbit})
    for (double r = 0.6; r < t.radius(); r += 0.17) {
      if (t.envelope_height(r) == 0)
        CHECK(t.section_radius(0) >= r);
      else
        CHECK(t.section_radius(t.envelope_height(r)) == doctest::Approx(r));
    }
}

TEST_CASE("Fusion 360 / HSM tool comments") {
  std::vector<Diagnostic> diags;
  const SourceFile f =
      make_source("fusion.nc", "%\nO1001\n"
                               "(T1 D=6. CR=0. - ZMIN=-5. - FLAT END MILL)\n"
                               "(T2 D=8. CR=4. - ZMIN=-3. - BALL END MILL)\n"
                               "(T3 D=10. CR=1. - ZMIN=-2. - BULLNOSE END MILL)\n"
                               "(T4 D=5. CR=0. TAPER=118deg - ZMIN=-12. - DRILL)\n"
                               "(T5 D=12. CR=0. TAPER=45deg - ZMIN=-1. - CHAMFER MILL)\n"
                               "G90 G94 G17\nG21\nT1 M6\n");
  const auto tools = parse_tool_comments(f, diags);
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
    const auto inch = parse_tool_comments(
        make_source("in.nc", "(T7 D=0.25 CR=0. - ZMIN=-0.2 - FLAT END MILL)\nG20\n"), d2);
    REQUIRE(inch.count(7));
    CHECK(inch.at(7).diameter_mm == doctest::Approx(6.35));
  }
  SUBCASE("unknown types and bad sizes are reported") {
    std::vector<Diagnostic> d2;
    const auto t = parse_tool_comments(
        make_source("odd.nc", "(T8 D=3. CR=0. - ZMIN=-1. - WIDGET)\n(T9 D=0. - FLAT END MILL)\n"),
        d2);
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
  const SourceFile f = make_source("freecad.nc", "(Exported by FreeCAD)\nG21\n"
                                                 "(begin operation: TC: 6mm Ball End)\n"
                                                 "(TC: 6mm Ball End)\nM6 T2\nG43 H2\n"
                                                 "(TC: 5mm Endmill)\nM6 T1\n"
                                                 "(TC: 60 Deg V-Bit 10mm)\nM6 T3\n");
  const auto tools = parse_tool_comments(f, diags);
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
  const SourceFile f =
      make_source("mcam.nc", "%\nO0000(PART)\n(TOOL - 1 DIA. OFF. - 1 LEN. - 1 DIA. - 6.)\n"
                             "(8. BALL ENDMILL TOOL - 2 DIA. OFF. - 2 LEN. - 2 DIA. - 8.)\n"
                             "( T3 | 10. SPOT DRILL | H3 | TOOL DIA. - 10. )\n"
                             "G21\n");
  const auto tools = parse_tool_comments(f, diags);
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
    const auto in = parse_tool_comments(
        make_source("mcam_in.nc", "(1/2 FLAT ENDMILL TOOL - 4 DIA. OFF. - 4 LEN. - 4 DIA. - .5)\n"
                                  "G20 G90\n"),
        d2);
    REQUIRE(in.count(4));
    CHECK(in.at(4).diameter_mm == doctest::Approx(12.7));
  }
}
