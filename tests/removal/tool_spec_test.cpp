// Tools written on the command line: N:TYPE:DIAMETER[:EXTRA...].
#include <doctest/doctest.h>

#include "ncjoule/removal.hpp"

using namespace ncjoule;

TEST_CASE("tool specs: each type and its extra values") {
  auto flat = parse_tool_spec("1:flat:6");
  REQUIRE(flat);
  CHECK(flat->number == 1);
  CHECK(flat->shape == ToolShape::FlatEndMill);
  CHECK(flat->diameter_mm == 6);
  auto ball = parse_tool_spec("2:BALL:6");
  REQUIRE(ball);
  CHECK(ball->shape == ToolShape::BallEndMill);
  CHECK(ball->corner_radius_mm == 3);
  CHECK(ball->envelope_height(3) == doctest::Approx(3)); // a hemisphere
  auto bull = parse_tool_spec("3:bullnose:10:1.5");
  REQUIRE(bull);
  CHECK(bull->shape == ToolShape::BullNose);
  CHECK(bull->corner_radius_mm == 1.5);
  auto drill = parse_tool_spec("4:drill:6.8:118");
  REQUIRE(drill);
  CHECK(drill->shape == ToolShape::Drill);
  CHECK(drill->tip_angle_deg == 118);
  CHECK(parse_tool_spec("4:drill:6.8")->tip_angle_deg == 118);
  auto vbit = parse_tool_spec("5:chamfer:12:60:0.5");
  REQUIRE(vbit);
  CHECK(vbit->tip_angle_deg == 60);
  CHECK(vbit->tip_diameter_mm == 0.5);
  CHECK(parse_tool_spec("5:chamfer:12")->tip_angle_deg == 90);
}

TEST_CASE("tool specs: mistakes are refused with a reason") {
  for (const char* bad :
       {"1:flat", "x:flat:6", "1.5:flat:6", "1:square:6", "1:flat:six", "1:flat:0", "1:flat:6:2",
        "3:bullnose:10", "3:bullnose:10:6", "4:drill:6:200", "-1:flat:6"}) {
    std::vector<Diagnostic> problems;
    CAPTURE(bad);
    CHECK_FALSE(parse_tool_spec(bad, &problems));
    REQUIRE(problems.size() == 1);
    CHECK(problems[0].severity == Severity::Error);
    CHECK_FALSE(problems[0].message.empty());
  }
  // The error points at the field it is about.
  std::vector<Diagnostic> problems;
  parse_tool_spec("1:square:6", &problems, {"job.toml", 7, 12});
  REQUIRE(problems.size() == 1);
  CHECK(problems[0].message.find("square") != std::string::npos);
  CHECK(problems[0].line == 7);
  CHECK(problems[0].column == 12 + 2);
  problems.clear();
  parse_tool_spec("1:flat:0", &problems, {"job.toml", 7, 12});
  REQUIRE(problems.size() == 1);
  CHECK(problems[0].column == 12 + 7); // the diameter
  CHECK(tool_shape_from_name("Chamfer") == ToolShape::Chamfer);
  CHECK_FALSE(tool_shape_from_name("vee"));
}

TEST_CASE("tool specs: lengths may carry their unit, angles may not") {
  auto quarter = parse_tool_spec("1:flat:0.25in");
  REQUIRE(quarter);
  CHECK(quarter->diameter_mm == doctest::Approx(6.35));
  auto bull = parse_tool_spec("3:bullnose:0.5\":0.03in");
  REQUIRE(bull);
  CHECK(bull->diameter_mm == doctest::Approx(12.7));
  CHECK(bull->corner_radius_mm == doctest::Approx(0.762));
  auto vbit = parse_tool_spec("5:chamfer:12mm:60:0.02in");
  REQUIRE(vbit);
  CHECK(vbit->tip_angle_deg == 60);
  CHECK(vbit->tip_diameter_mm == doctest::Approx(0.508));
  std::vector<Diagnostic> problems;
  CHECK_FALSE(parse_tool_spec("4:drill:6.8:118in", &problems));
  REQUIRE(problems.size() == 1);
  CHECK(problems[0].message.find("118in") != std::string::npos);
}
