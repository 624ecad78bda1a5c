// Cutter radius compensation (G41/G42): the geometry against hand-made cases, where the radius
// comes from, what each dialect does with what compensation cannot make, and wear mode. The
// agreement with LinuxCNC's own rs274 is checked by rs274_agreement.py (rs274_comp/).
#include <doctest/doctest.h>

#include <cmath>

#include "cutter_comp.hpp"
#include "cutter_comp_mode.hpp"
#include "program_runner.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

Toolpath run_with(const std::string& text, const std::string& dialect, InterpreterOptions options) {
  const SourceFile source = make_source("test.ngc", text);
  if (!dialect.empty()) options.dialect = find_dialect(dialect);
  options.max_commands = 100000;
  return interpret(source, options);
}

ToolTable table_with_radius(int tool, double radius) {
  ToolTable tools;
  tools[tool] = ToolEntry{tool, 0.0, 2 * radius};
  return tools;
}

} // namespace

TEST_CASE("cutter comp: entry, convex corner arc and exit (G41, radius 2)") {
  const Toolpath p = run("G21 F100\nG0 X-10 Y0\nG41 D1\nG1 X0 Y0\nG1 Y-10\nG40\nG1 X20 Y-20\nM2\n",
                         "linuxcnc", table_with_radius(1, 2));
  CHECK(errors(p) == 0);
  CHECK(p.result.comp_radius_unknown.empty());
  const auto m = moves(p);
  REQUIRE(m.size() == 5);
  // Entry: a radius to the left of the end, across the move (+X): (0, 2).
  CHECK(m[1] == F(0, 2, 0));
  // The right turn to -Y is convex for G41: a clockwise arc about the corner, then the side.
  CHECK(m[2].rfind("ARC_FEED(2.0000, 0.0000, 0.0000, 0.0000, -1, 0.0000", 0) == 0);
  CHECK(m[3] == F(2, -10, 0));
  CHECK(m[4] == F(20, -20, 0)); // the exit move, from where the tool is
  const auto cmds = move_commands(p);
  CHECK(cmds[4].start.x == doctest::Approx(2));
  CHECK(cmds[4].start.y == doctest::Approx(-10));
}

TEST_CASE("cutter comp: a concave corner shortens the move before it (G42, radius 1)") {
  const Toolpath p = run("G21 F100\nG0 X-5 Y0\nG42 D2\nG1 X0 Y0\nG1 X10\nG1 Y-10\nG40 G1 X20 "
                         "Y-20\nM2\n",
                         "linuxcnc", table_with_radius(2, 1));
  CHECK(errors(p) == 0);
  const auto m = moves(p);
  REQUIRE(m.size() == 5);
  CHECK(m[1] == F(0, -1, 0));
  CHECK(m[2] == F(9, -1, 0)); // stops a radius before the next side
  CHECK(m[3] == F(9, -10, 0));
  CHECK(m[4] == F(20, -20, 0));
}

TEST_CASE("cutter comp: G41.1 D is a diameter, G10 L1 R a radius over the tool table") {
  const Toolpath a = run("G21 F100\nG0 X-10 Y0\nG41.1 D4\nG1 X0 Y0\nG40 G1 X-10\nM2\n");
  CHECK(moves(a)[1] == F(0, 2, 0));
  const Toolpath b = run("G21 F100\nG10 L1 P1 R3\nG0 X-10 Y0\nG41 D1\nG1 X0 Y0\nG40 G1 X-10\nM2\n",
                         "linuxcnc", table_with_radius(1, 1));
  CHECK(moves(b)[1] == F(0, 3, 0));
}

TEST_CASE("cutter comp: the radius of the tool described outside the table comes before it") {
  InterpreterOptions options;
  options.tools = table_with_radius(1, 1);
  options.comp_radius_mm[1] = 5;
  const Toolpath p =
      run_with("G21 F100\nG0 X-10 Y0\nG41 D1\nG1 X0 Y0\nG40 G1 X-10\nM2\n", "linuxcnc", options);
  CHECK(moves(p)[1] == F(0, 5, 0));
}

TEST_CASE("cutter comp: no radius known, moves as programmed and the tool is listed") {
  const Toolpath p = run("G21 G0 X0 Y0\nG1 F100\nG41 D1 X5\nG40 X6\nG42 X7\nM2\n");
  CHECK(errors(p) == 0);
  CHECK(warnings(p) == 0);
  CHECK(p.result.comp_radius_unknown == std::set<int>{1});
  const auto m = moves(p);
  REQUIRE(m.size() == 4);
  CHECK(m[1] == F(5, 0, 0));
}

TEST_CASE("cutter comp: wear mode runs the path as programmed (G41.2, a WEAR COMP comment)") {
  const Toolpath a = run("G21 F100\nG0 X-10 Y0\nG41.2 D1\nG1 X0 Y0\nG1 Y10\nG40\nM2\n", "linuxcnc",
                         table_with_radius(1, 2));
  CHECK(errors(a) == 0);
  CHECK(warnings(a) == 0);
  CHECK(moves(a)[1] == F(0, 0, 0));
  CHECK(moves(a)[2] == F(0, 10, 0));
  const Toolpath b = run("(T1 | FLAT END MILL - 4 | H1 | D1 | WEAR COMP | TOOL DIA. - 4.)\nG21 "
                         "F100\nG0 X-10 Y0\nG41 D1\nG1 X0 Y0\nG40\nM2\n",
                         "fanuc", table_with_radius(1, 2));
  CHECK(moves(b)[1] == F(0, 0, 0));
  CHECK(b.result.comp_radius_unknown.empty());
  InterpreterOptions options;
  options.tools = table_with_radius(1, 2);
  options.default_cutter_compensation = CutterCompMode::Wear;
  CHECK(moves(run_with("G21 F100\nG0 X-10 Y0\nG41 D1\nG1 X0 Y0\nM2\n", "fanuc", options))[1] ==
        F(0, 0, 0));
  // A CONTROL COMP comment holds over the machine's default.
  CHECK(moves(run_with("(T1 | D1 | CONTROL COMP)\nG21 F100\nG0 X-10 Y0\nG41 D1\nG1 X0 Y0\nM2\n",
                       "fanuc", options))[1] == F(0, 2, 0));
}

TEST_CASE("cutter comp: an entry move shorter than the radius, LinuxCNC refuses, others warn") {
  const std::string program = "G21 F100\nG0 X-1 Y0\nG41 D1\nG1 X0 Y0\nG1 Y10\nG40\nM2\n";
  const Toolpath strict = run(program, "linuxcnc", table_with_radius(1, 2));
  const auto e = with_severity(strict, Severity::Error);
  REQUIRE(e.size() == 1);
  CHECK(e[0].line == 4);
  CHECK(e[0].column == 1);
  CHECK(e[0].message.find("entry move") != std::string::npos);
  const Toolpath lenient = run(program, "fanuc", table_with_radius(1, 2));
  CHECK(errors(lenient) == 0);
  CHECK(warnings(lenient) == 1);
  CHECK(moves(lenient)[1] == F(0, 0, 0));
  CHECK(moves(lenient)[2] == F(0, 10, 0)); // as programmed until G40
}

TEST_CASE("cutter comp: a concave corner the tool cannot reach") {
  // A 1 mm step into a slot with a 2 mm radius: the move before would have to turn back.
  const std::string program =
      "G21 F100\nG0 X-10 Y-10\nG42 D1\nG1 X0 Y0\nG1 X10\nG1 Y1\nG1 X9\nG1 Y20\nG40\nM2\n";
  CHECK(errors(run(program, "linuxcnc", table_with_radius(1, 2))) == 1);
  const Toolpath lenient = run(program, "haas", table_with_radius(1, 2));
  CHECK(errors(lenient) == 0);
  CHECK(warnings(lenient) >= 1);
}

TEST_CASE("cutter comp: G28 and G53 with compensation on") {
  const std::string g28 = "G21 F100\nG0 X-10 Y0\nG41 D1\nG1 X0 Y0\nG28\nG40\nM2\n";
  CHECK(errors(run(g28, "linuxcnc", table_with_radius(1, 2))) == 1);
  const Toolpath lenient = run(g28, "fanuc", table_with_radius(1, 2));
  CHECK(errors(lenient) == 0);
  CHECK(warnings(lenient) == 1);
  const std::string g53 = "G21 F100\nG0 X-10 Y0\nG41 D1\nG1 X0 Y0\nG53 G0 Z0\nG40\nM2\n";
  CHECK(errors(run(g53, "linuxcnc", table_with_radius(1, 2))) == 1);
  CHECK(errors(run(g53, "fanuc", table_with_radius(1, 2))) == 0);
}

TEST_CASE("cutter comp: moves held in the queue come out before the program ends") {
  const Toolpath p = run("G21 F100\nG0 X-10 Y0\nG41 D1\nG1 X0 Y0\nG1 Y10\nM2\n", "linuxcnc",
                         table_with_radius(1, 2));
  const auto m = moves(p);
  REQUIRE(m.size() == 3);
  CHECK(m[2] == F(-2, 10, 0));
  CHECK(p.commands.back().kind == CanonKind::ProgramEnd);
}

TEST_CASE("cutter comp: the geometry helpers") {
  using namespace ncjoule::detail;
  const CompPoint e = straight_entry_end({0, 0}, {10, 0}, 1, CompSide::Right);
  CHECK(e.error.empty());
  CHECK(e.point.a == doctest::Approx(10));
  CHECK(e.point.b == doctest::Approx(-1));
  CHECK(!straight_entry_end({0, 0}, {1, 0}, 1, CompSide::Left).error.empty());
  CHECK(arc_sweep({1, 0}, {0, 0}, 1, {0, 1}) == doctest::Approx(std::acos(-1.0) / 2));
  CHECK(arc_sweep({1, 0}, {0, 0}, -1, {0, 1}) == doctest::Approx(-3 * std::acos(-1.0) / 2));
  Pose pose;
  set_plane_point(pose, Plane::XZ, {3, 4});
  CHECK(pose.z == 3);
  CHECK(pose.x == 4);
  CHECK(plane_point(pose, Plane::XZ).a == 3);
}

TEST_CASE("cutter comp: CAM comments that say how compensation was posted") {
  using namespace ncjoule::detail;
  CHECK(
      comp_mode_of_comment("T1 | FLAT END MILL | H1 | D1 | CONTROL COMP | TOOL DIA. - 6.")->mode ==
      CutterCompMode::Control);
  CHECK(comp_mode_of_comment("T2 | D2 | REVERSE WEAR COMP")->mode == CutterCompMode::Wear);
  CHECK(comp_mode_of_comment("CUTTER COMP WEAR TYPE")->mode == CutterCompMode::Wear);
  CHECK(!comp_mode_of_comment("COMPOUND ANGLE"));
}
