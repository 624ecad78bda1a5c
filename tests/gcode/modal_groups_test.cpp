// Each modal group of the interpreter, one test case per group. Expected lines are those LinuxCNC's
// `rs274 -g` prints for the same programs.
#include <doctest/doctest.h>

#include "program_runner.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("motion group: G0/G1 stay in effect for following axis words") {
  const Toolpath p = run("G21\nG0 X1 Y2 Z3\nX4\nG1 X5 F100\nY6\nM2\n");
  CHECK(errors(p) == 0);
  const std::vector<std::string> expected = {
      "STRAIGHT_TRAVERSE(1.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)",
      "STRAIGHT_TRAVERSE(4.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)",
      "STRAIGHT_FEED(5.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)",
      "STRAIGHT_FEED(5.0000, 6.0000, 3.0000, 0.0000, 0.0000, 0.0000)"};
  CHECK(moves(p) == expected);
  // Every command knows the source line it came from (0-based).
  const auto m = move_commands(p);
  CHECK(m[1].line == 2);
  CHECK(m[3].line == 4);
  CHECK(m[3].start.y == doctest::Approx(2.0));
}

TEST_CASE("motion group: G80 cancels, then axis words alone are an error") {
  const Toolpath p = run("G21\nG0 X1\nG80\nX2\nM2\n");
  CHECK(moves(p).size() == 1);
  REQUIRE(errors(p) == 1);
  CHECK(with_severity(p, Severity::Error)[0].line == 4);
}

TEST_CASE("motion group, Fanuc family: canned cycles are group 09, G80 leaves G0/G1 in force") {
  for (const char* dialect : {"fanuc", "haas", "mach3", "siemens"}) {
    CAPTURE(dialect);
    const Toolpath p = run("G21\nG1 X1 F100\nG81 X5 Z-1 R1\nG80\nX2\nG0 X3\nG81 X4 Z-1 R1\n"
                           "G80\nY9\nM30\n",
                           dialect);
    CHECK(errors(p) == 0);
    auto on_line = [&](int line) {
      std::vector<CanonCommand> out;
      for (const CanonCommand& c : move_commands(p))
        if (c.line == line) out.push_back(c);
      return out;
    };
    // After the first G80 the G1 before the cycle moves X2; after the second, the G0.
    const auto x2 = on_line(4), y9 = on_line(8);
    REQUIRE(x2.size() == 1);
    CHECK(x2[0].kind == CanonKind::Feed);
    CHECK(x2[0].end.x == doctest::Approx(2));
    REQUIRE(y9.size() == 1);
    CHECK(y9[0].kind == CanonKind::Traverse);
    CHECK(y9[0].end.y == doctest::Approx(9));
  }
}

TEST_CASE("motion group: the safety line G00 G17 G21 G40 G49 G80 G90 runs whole") {
  // rs274 runs it: G80 beside G0 gives way to G0. Every other code of the line takes effect.
  for (const char* dialect : {"linuxcnc", "fanuc", "haas"}) {
    CAPTURE(dialect);
    const Toolpath p = run("G20\nG91\nG00 G17 G21 G40 G49 G80 G90\nX1 Y2\nM30\n", dialect);
    CHECK(errors(p) == 0);
    CHECK(warnings(p) == 0);
    // As in rs274, G0 alone is a move to where the tool is; then X1 Y2.
    const auto m = move_commands(p);
    REQUIRE(m.size() == 2);
    CHECK(m[1].kind == CanonKind::Traverse);
    CHECK(m[1].end.x == doctest::Approx(1)); // G21 and G90 took effect: 1 mm, absolute
    CHECK(!m[1].state.inch);
  }
}

TEST_CASE("G91 G28 G53 Z0: a warning, and the return home the post meant") {
  const Toolpath p = run("G21 G0 Z5\nG91 G28 G53 Z0\nM30\n", "fanuc");
  CHECK(errors(p) == 0);
  const auto w = with_severity(p, Severity::Warning);
  REQUIRE(w.size() == 1);
  CHECK(w[0].message.find("G53") != std::string::npos);
  const auto m = move_commands(p);
  REQUIRE(m.size() == 3); // G0 Z5, the intermediate point (no move under G91 Z0), then home
  CHECK(m.back().end.z == doctest::Approx(0));
}

TEST_CASE("two codes of one modal group: Fanuc takes the last, LinuxCNC refuses the block") {
  const Toolpath fanuc = run("G21\nG0 G1 X1 F100\nM30\n", "fanuc");
  CHECK(errors(fanuc) == 0);
  REQUIRE(warnings(fanuc) == 1);
  const auto m = move_commands(fanuc);
  REQUIRE(m.size() == 1);
  CHECK(m[0].kind == CanonKind::Feed);
}

TEST_CASE("with no dialect named or recognised, what only LinuxCNC refuses is a warning") {
  // No dialect given, nothing in the text names one: the default (linuxcnc) relaxes.
  const Toolpath p = run("G21\nG1 X1 F100\nG81 X5 Z-1 R1\nG80\nX2\nG0 G1 X3\nM30\n", "");
  CHECK(p.result.dialect_origin == DialectOrigin::Default);
  CHECK(errors(p) == 0);
  CHECK(warnings(p) == 2);
  const auto m = move_commands(p);
  REQUIRE(m.size() >= 2);
  CHECK(m[m.size() - 2].end.x == doctest::Approx(2));
  CHECK(m[m.size() - 2].kind == CanonKind::Feed);
  CHECK(m.back().end.x == doctest::Approx(3));
  CHECK(m.back().kind == CanonKind::Feed);
  // Named, LinuxCNC's refusal stands.
  const Toolpath strict = run("G21\nG1 X1 F100\nG80\nX2\nM30\n", "linuxcnc");
  CHECK(errors(strict) == 1);
}

TEST_CASE("two codes of one modal group on a line are an error and the block is skipped") {
  const Toolpath p = run("G21\nG0 G1 X1 F100\nG17 G18\nG90 G91 X3\nG20 G21\nX7\nM2\n");
  const auto e = with_severity(p, Severity::Error);
  REQUIRE(e.size() == 4);
  CHECK(e[0].line == 2);
  CHECK(e[0].column == 4); // the second code of the group
  CHECK(e[0].message.find("G0 and G1") != std::string::npos);
  CHECK(e[1].line == 3);
  CHECK(e[2].line == 4);
  CHECK(e[3].line == 5);
  // No move came from the rejected blocks; the program went on.
  const std::vector<std::string> expected = {
      "STRAIGHT_TRAVERSE(7.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)"};
  CHECK(moves(p) == expected);
}

TEST_CASE("plane group: G17 G18 G19 select the arc plane") {
  const Toolpath p = run("G21 G0 X0 Y0 Z0\nG18\nG19\nG17\nM2\n");
  const auto planes = of_kind(p, CanonKind::PlaneSelect);
  REQUIRE(planes.size() == 3);
  CHECK(format_canon(planes[0]) == "SELECT_PLANE(CANON_PLANE_XZ)");
  CHECK(format_canon(planes[1]) == "SELECT_PLANE(CANON_PLANE_YZ)");
  CHECK(format_canon(planes[2]) == "SELECT_PLANE(CANON_PLANE_XY)");
}

TEST_CASE("distance group: G91 adds to the current point, G90 goes back to absolute") {
  const Toolpath p = run("G21 G0 X1 Y1 Z1\nG91 X2 Y-3\nZ-1\nG90 X0\nM2\n");
  const std::vector<std::string> expected = {
      "STRAIGHT_TRAVERSE(1.0000, 1.0000, 1.0000, 0.0000, 0.0000, 0.0000)",
      "STRAIGHT_TRAVERSE(3.0000, -2.0000, 1.0000, 0.0000, 0.0000, 0.0000)",
      "STRAIGHT_TRAVERSE(3.0000, -2.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
      "STRAIGHT_TRAVERSE(0.0000, -2.0000, 0.0000, 0.0000, 0.0000, 0.0000)"};
  CHECK(moves(p) == expected);
}

TEST_CASE("arc distance group: G91.1 centres are relative, G90.1 absolute") {
  const Toolpath p =
      run("G21 G0 X10 Y0 Z0\nG2 X0 Y10 I-10 J0 F100\nG90.1 G3 X10 Y0 I0 J0\nG91.1\nM2\n");
  CHECK(errors(p) == 0);
  const std::vector<std::string> expected = {
      "STRAIGHT_TRAVERSE(10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
      "ARC_FEED(0.0000, 10.0000, 0.0000, 0.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)",
      "ARC_FEED(10.0000, 0.0000, 0.0000, 0.0000, 1, 0.0000, 0.0000, 0.0000, 0.0000)"};
  CHECK(moves(p) == expected);
}

TEST_CASE("feed mode group: G93 inverse time, G94 per minute, G95 per revolution") {
  const Toolpath p = run("G21 G0 X0 Y0 Z0\nG93\nG1 X5 F2\nG94 F100\nX10\nS1000 M3\nG95 F0.1\n"
                         "X20\nG94\nM2\n");
  CHECK(errors(p) == 0);
  const auto rates = of_kind(p, CanonKind::SetFeedRate);
  REQUIRE(rates.size() == 3);
  // G93 F2 over 5 mm: the move must take 1/2 min, so 10 mm/min (rs274 prints the same).
  CHECK(format_canon(rates[0]) == "SET_FEED_RATE(10.0000)");
  CHECK(format_canon(rates[1]) == "SET_FEED_RATE(100.0000)");
  CHECK(format_canon(rates[2]) == "SET_FEED_RATE(0.1000)");
  const auto feeds = of_kind(p, CanonKind::Feed);
  REQUIRE(feeds.size() == 3);
  CHECK(feeds[0].state.feed_mode == FeedMode::InverseTime);
  CHECK(feeds[1].state.feed_mode == FeedMode::UnitsPerMinute);
  CHECK(feeds[1].state.feed == doctest::Approx(100.0));
  CHECK(feeds[2].state.feed_mode == FeedMode::UnitsPerRevolution);
  CHECK(feeds[2].state.feed == doctest::Approx(0.1));
}

TEST_CASE("feed mode group: G93 feed moves need their own F") {
  const Toolpath p = run("G21 G0 X0 Y0 Z0\nG93 G1 X5 F2\nX6\nM2\n");
  const auto e = with_severity(p, Severity::Error);
  REQUIRE(e.size() == 1);
  CHECK(e[0].line == 3);
}

TEST_CASE("units group: G20 reads inches, commands hold mm and print in inches") {
  const Toolpath p = run("G20 G0 X1 Y2 Z0.5\nG1 X1.5 F10\nG21 G0 X10\nM2\n");
  const auto m = move_commands(p);
  REQUIRE(m.size() == 3);
  CHECK(m[0].end.x == doctest::Approx(25.4));
  CHECK(m[0].end.y == doctest::Approx(50.8));
  CHECK(m[0].end.z == doctest::Approx(12.7));
  CHECK(m[0].state.inch);
  CHECK(m[1].state.feed == doctest::Approx(254.0)); // 10 in/min in mm/min
  CHECK(format_canon(m[1]) == "STRAIGHT_FEED(1.5000, 2.0000, 0.5000, 0.0000, 0.0000, 0.0000)");
  CHECK(format_canon(of_kind(p, CanonKind::SetFeedRate)[0]) == "SET_FEED_RATE(10.0000)");
  // Back in mm: the position carried over is printed in mm.
  CHECK(format_canon(m[2]) ==
        "STRAIGHT_TRAVERSE(10.0000, 50.8000, 12.7000, 0.0000, 0.0000, 0.0000)");
  const auto units = of_kind(p, CanonKind::LengthUnits);
  REQUIRE(units.size() == 2);
  CHECK(format_canon(units[0]) == "USE_LENGTH_UNITS(CANON_UNITS_INCHES)");
  CHECK(format_canon(units[1]) == "USE_LENGTH_UNITS(CANON_UNITS_MM)");
}

TEST_CASE("cutter compensation group: G41/G42 with no radius known run as programmed") {
  const Toolpath p = run("G21 G0 X0 Y0\nG1 F100\nG41 D1 X5\nG40 X6\nG42 X7\nM2\n");
  CHECK(errors(p) == 0);
  CHECK(warnings(p) == 0);
  CHECK(p.result.comp_radius_unknown == std::set<int>{1});
  const auto m = moves(p);
  REQUIRE(m.size() == 4);
  CHECK(m[1] == "STRAIGHT_FEED(5.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
}

TEST_CASE("tool length group: G43 H from the tool table, G43 with the current tool, G49") {
  ToolTable tools;
  tools[1] = ToolEntry{1, 10.0, 6.0};
  tools[2] = ToolEntry{2, 25.4, 3.0};
  const Toolpath p =
      run("G21\nT1 M6\nG43 H1\nG0 X1 Y2 Z3\nG43 H2\nG49\nG43\nG43.1 Z-2\nG43 H7\nM2\n", "linuxcnc",
          tools);
  const auto offsets = of_kind(p, CanonKind::ToolLengthOffset);
  REQUIRE(offsets.size() == 6);
  CHECK(offsets[0].value == doctest::Approx(10.0));
  CHECK(format_canon(offsets[0]) == "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 10.0000, 0.0000 0.0000 "
                                    "0.0000, 0.0000 0.0000 0.0000)");
  CHECK(offsets[1].value == doctest::Approx(25.4));
  CHECK(offsets[2].value == 0.0);
  CHECK(offsets[3].value == doctest::Approx(10.0)); // G43 alone: the tool in the spindle
  CHECK(offsets[4].value == doctest::Approx(-2.0)); // G43.1 dynamic offset
  CHECK(offsets[5].value == 0.0);                   // tool 7 is not in the table
  const auto w = with_severity(p, Severity::Warning);
  REQUIRE(w.size() == 1);
  CHECK(w[0].line == 9);
  // The program's Z is not moved by the offset (rs274 prints Z3).
  CHECK(moves(p)[0] == "STRAIGHT_TRAVERSE(1.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)");
}

TEST_CASE("coordinate system group: G54-G59.3 with G10 L2 offsets") {
  const Toolpath p = run("G21 G0 X1 Y2 Z3\nG10 L2 P2 X10 Y20 Z-5\nG55\nG0 X0 Y0\nG59.3\n"
                         "G10 L2 P9 X1\nG0 X0\nG54\nG0 X0\nM2\n");
  CHECK(errors(p) == 0);
  const auto offsets = of_kind(p, CanonKind::WorkOffset);
  REQUIRE(offsets.size() == 4);
  CHECK(format_canon(offsets[0]) ==
        "SET_G5X_OFFSET(2, 10.0000, 20.0000, -5.0000, 0.0000, 0.0000, 0.0000)");
  CHECK(offsets[1].value == 9.0);
  CHECK(format_canon(offsets[2]) ==
        "SET_G5X_OFFSET(9, 1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  CHECK(offsets[3].value == 1.0);
  const std::vector<std::string> expected = {
      "STRAIGHT_TRAVERSE(1.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)",
      // (1, 2, 3) in G54 is (-9, -18, 8) in G55.
      "STRAIGHT_TRAVERSE(0.0000, 0.0000, 8.0000, 0.0000, 0.0000, 0.0000)",
      "STRAIGHT_TRAVERSE(0.0000, 20.0000, 3.0000, 0.0000, 0.0000, 0.0000)",
      "STRAIGHT_TRAVERSE(0.0000, 20.0000, 3.0000, 0.0000, 0.0000, 0.0000)"};
  CHECK(moves(p) == expected);
}

TEST_CASE("G92 shifts the program's coordinates, G92.1 cancels") {
  const Toolpath p = run("G21 G0 X10 Y20 Z0\nG92 X0 Y0\nG0 X1\nG92.1\nG0 Y0\nM2\n");
  const auto g92 = of_kind(p, CanonKind::AxisOffset);
  REQUIRE(g92.size() == 2);
  CHECK(format_canon(g92[0]) == "SET_G92_OFFSET(10.0000, 20.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  CHECK(format_canon(g92[1]) == "SET_G92_OFFSET(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  const auto m = moves(p);
  REQUIRE(m.size() == 3);
  CHECK(m[1] == "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  CHECK(m[2] == "STRAIGHT_TRAVERSE(11.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
}

TEST_CASE("path control group: G61, G61.1, G64 P (in program units)") {
  const Toolpath p = run("G21\nG61\nG61.1\nG64 P0.05\nG64\nG20 G64 P0.002\nM2\n");
  const auto modes = of_kind(p, CanonKind::PathControl);
  REQUIRE(modes.size() == 5);
  CHECK(format_canon(modes[0]) == "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)");
  CHECK(format_canon(modes[1]) == "SET_MOTION_CONTROL_MODE(CANON_EXACT_STOP)");
  CHECK(format_canon(modes[2]) == "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.050000)");
  CHECK(modes[2].state.path_tolerance == doctest::Approx(0.05));
  CHECK(modes[3].state.path_tolerance == 0.0);
  CHECK(modes[4].state.path_tolerance == doctest::Approx(0.0508)); // 0.002 in, in mm
  CHECK(format_canon(modes[4]) == "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.002000)");
}

TEST_CASE("spindle, coolant and tool commands carry the machine state") {
  const Toolpath p = run("G21\nT3 M6\nS2000 M3\nM8\nG0 X1\nM4\nM7\nM9\nM5\nM30\n");
  const std::vector<std::string> expected = {"SELECT_TOOL(3)",
                                             "CHANGE_TOOL(3)",
                                             "SET_SPINDLE_SPEED(0, 2000.0000)",
                                             "START_SPINDLE_CLOCKWISE(0)",
                                             "FLOOD_ON()",
                                             "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, "
                                             "0.0000, 0.0000)",
                                             "START_SPINDLE_COUNTERCLOCKWISE(0)",
                                             "MIST_ON()",
                                             "MIST_OFF()",
                                             "FLOOD_OFF()",
                                             "STOP_SPINDLE_TURNING(0)",
                                             "PROGRAM_END()"};
  const auto lines = canon(p);
  CHECK(std::vector<std::string>(lines.end() - expected.size(), lines.end()) == expected);
  const auto m = move_commands(p);
  REQUIRE(m.size() == 1);
  CHECK(m[0].state.tool == 3);
  CHECK(m[0].state.spindle == SpindleDir::Clockwise);
  CHECK(m[0].state.spindle_rpm == 2000.0);
  CHECK(m[0].state.flood);
  CHECK_FALSE(m[0].state.mist);
  CHECK(p.result.completed);
}
