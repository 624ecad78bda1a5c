// Canned cycles expanded into their moves, checked line by line against what `rs274 -g` prints
// for the same programs.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdio>

#include "program_runner.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("G83 pecks back to R after every peck, G98 retracts to the start height") {
  const Toolpath p = run("G21\nG0 X0 Y0 Z5\nG98 G83 X1 Y2 Z-4 R1 Q1.5 F100\nM2\n");
  CHECK(errors(p) == 0);
  const std::vector<std::string> expected = {
      T(0, 0, 5),      T(1, 2, 5),      T(1, 2, 1),  F(1, 2, -0.5),   T(1, 2, 1),
      T(1, 2, -0.246), F(1, 2, -2),     T(1, 2, 1),  T(1, 2, -1.746), F(1, 2, -3.5),
      T(1, 2, 1),      T(1, 2, -3.246), F(1, 2, -4), T(1, 2, 5)};
  CHECK(moves(p) == expected);
  // The peck moves belong to the cycle's block.
  for (const CanonCommand& c : move_commands(p))
    if (c.start.x == 1.0) CHECK(c.line == 2);
}

TEST_CASE("G73 only backs off to break the chip, G99 retracts to R") {
  const Toolpath p = run("G21\nG0 X0 Y0 Z5\nG99 G73 X1 Y2 Z-4 R1 Q1.5 F100\nM2\n");
  const std::vector<std::string> expected = {
      T(0, 0, 5),      T(1, 2, 5),    T(1, 2, 1),      F(1, 2, -0.5), T(1, 2, -0.246), F(1, 2, -2),
      T(1, 2, -1.746), F(1, 2, -3.5), T(1, 2, -3.246), F(1, 2, -4),   T(1, 2, 1)};
  CHECK(moves(p) == expected);
}

TEST_CASE("peck distances per family: Haas setting 22, a machine's own parameters") {
  // Haas: G83 rapids back down to 0.050 in (setting 22 as shipped) above the last peck, and G73
  // backs off as much; the program is metric, the setting is not.
  const Toolpath g83 = run("G21\nG0 X0 Y0 Z5\nG98 G83 X1 Y2 Z-4 R1 Q1.5 F100\nG80\nM30\n", "haas");
  CHECK(errors(g83) == 0);
  const std::vector<std::string> p = moves(g83);
  const std::vector<std::string> expected83 = {F(1, 2, -0.5), T(1, 2, 1), T(1, 2, 0.77),
                                               F(1, 2, -2),   T(1, 2, 1), T(1, 2, -0.73),
                                               F(1, 2, -3.5), T(1, 2, 1), T(1, 2, -2.23)};
  REQUIRE(p.size() >= 3 + expected83.size());
  CHECK(std::vector<std::string>(p.begin() + 3, p.begin() + 3 + long(expected83.size())) ==
        expected83);
  const Toolpath g73 = run("G21\nG0 X0 Y0 Z5\nG99 G73 X1 Y2 Z-4 R1 Q1.5 F100\nG80\nM30\n", "haas");
  const std::vector<std::string> expected73 = {
      T(0, 0, 5),     T(1, 2, 5),    T(1, 2, 1),     F(1, 2, -0.5), T(1, 2, 0.77), F(1, 2, -2),
      T(1, 2, -0.73), F(1, 2, -3.5), T(1, 2, -2.23), F(1, 2, -4),   T(1, 2, 1)};
  CHECK(moves(g73) == expected73);
  // A machine's own parameter (a profile's [setup]) wins over its family's.
  InterpreterOptions options;
  options.dialect = find_dialect("fanuc");
  options.chip_break_retract_mm = 1.0;
  const Toolpath own = interpret(
      make_source("t.nc", "G21\nG0 X0 Y0 Z5\nG99 G73 X1 Y2 Z-4 R1 Q1.5 F100\nG80\nM30\n"), options);
  CHECK(moves(own)[4] == T(1, 2, 0.5));
}

TEST_CASE("G81 with L repeats under G91 steps from hole to hole") {
  const Toolpath p = run("G21\nG0 X0 Y0 Z5\nG91 G98 G81 X10 Y0 Z-4 R-2 L3 F100\nG90 G80\nM2\n");
  CHECK(errors(p) == 0);
  const std::vector<std::string> expected = {
      T(0, 0, 5),   T(10, 0, 5), T(10, 0, 3), F(10, 0, -1), T(10, 0, 5),  T(20, 0, 5), T(20, 0, 3),
      F(20, 0, -1), T(20, 0, 5), T(30, 0, 5), T(30, 0, 3),  F(30, 0, -1), T(30, 0, 5)};
  CHECK(moves(p) == expected);
}

TEST_CASE("G82: sticky R, Z and P, G98 in a series goes back to the series' start height") {
  const Toolpath p = run("G21\nG0 X0 Y0 Z5\nG99 G82 X1 Y2 Z-4 R1 P0.5 F100\nX3\nG98 Y4 Z-6\nM2\n");
  CHECK(errors(p) == 0);
  const std::vector<std::string> expected = {
      T(0, 0, 5), T(1, 2, 5), T(1, 2, 1), F(1, 2, -4), D(0.5), T(1, 2, 1),
      // X3: R, Z and P carried over; approached at R where G99 left the tool.
      T(3, 2, 1), F(3, 2, -4), D(0.5), T(3, 2, 1),
      // G98: approached at and retracted to Z5, where the series began.
      T(3, 4, 5), T(3, 4, 1), F(3, 4, -6), D(0.5), T(3, 4, 5)};
  CHECK(moves(p) == expected);
}

TEST_CASE("a series goes on across cycle codes and ends with a non-cycle motion") {
  // G81 then G82 is one series: G98 still goes back to Z5.
  const Toolpath same = run("G21\nG0 X0 Y0 Z5\nG99 G81 X1 Z-1 R1 F100\nG98 G82 X2 Z-1 R1 P1\nM2\n");
  const std::vector<std::string> expected_same = {T(0, 0, 5), T(1, 0, 5), T(1, 0, 1), F(1, 0, -1),
                                                  T(1, 0, 1), T(2, 0, 5), T(2, 0, 1), F(2, 0, -1),
                                                  D(1),       T(2, 0, 5)};
  CHECK(moves(same) == expected_same);
  // G0 in between starts a new series at Z3.
  const Toolpath fresh =
      run("G21\nG0 X0 Y0 Z5\nG99 G81 X1 Z-1 R1 F100\nG0 Z3\nG98 G81 X2 Z-1 R1\nM2\n");
  const std::vector<std::string> expected_fresh = {T(0, 0, 5),  T(1, 0, 5), T(1, 0, 1), F(1, 0, -1),
                                                   T(1, 0, 1),  T(1, 0, 3), T(2, 0, 3), T(2, 0, 1),
                                                   F(2, 0, -1), T(2, 0, 3)};
  CHECK(moves(fresh) == expected_fresh);
}

TEST_CASE("G91 G99 repeats: R is measured from the series' start height every time") {
  const Toolpath p =
      run("G21\nG0 X0 Y0 Z5\nG91 G99 G81 X10 Z-4 R-2 F100\nX10\nG98 X10\nG90 G80\nM2\n");
  const std::vector<std::string> expected = {T(0, 0, 5),  T(10, 0, 5), T(10, 0, 3),  F(10, 0, -1),
                                             T(10, 0, 3), T(20, 0, 3), F(20, 0, -1), T(20, 0, 3),
                                             T(30, 0, 5), T(30, 0, 3), F(30, 0, -1), T(30, 0, 5)};
  CHECK(moves(p) == expected);
}

TEST_CASE("G85 feeds out, G89 dwells and feeds out, G86 stops the spindle to retract") {
  const Toolpath p = run("G21\nM3 S1000\nG0 X0 Y0 Z5\nG98 G85 X1 Y2 Z-4 R1 F100\n"
                         "G99 G89 X3 Z-3 R2 P0.25\nG98 G86 X2 Y0 Z-3 R1 P1\nM2\n");
  CHECK(errors(p) == 0);
  const std::vector<std::string> expected = {T(0, 0, 5),  T(1, 2, 5),  T(1, 2, 1), F(1, 2, -4),
                                             F(1, 2, 1),  T(1, 2, 5),  T(3, 2, 5), T(3, 2, 2),
                                             F(3, 2, -3), D(0.25),     F(3, 2, 2), T(2, 0, 5),
                                             T(2, 0, 1),  F(2, 0, -3), D(1),       T(2, 0, 5)};
  CHECK(moves(p) == expected);
  // G86: STOP_SPINDLE_TURNING before the retract, START_SPINDLE_CLOCKWISE after.
  const auto lines = canon(p);
  const auto at = std::find(lines.begin(), lines.end(), D(1));
  REQUIRE(at + 3 < lines.end());
  CHECK(*(at + 1) == "STOP_SPINDLE_TURNING(0)");
  CHECK(*(at + 2) == T(2, 0, 5));
  CHECK(*(at + 3) == "START_SPINDLE_CLOCKWISE(0)");
  const auto retract = move_commands(p).back();
  CHECK(retract.state.spindle == SpindleDir::Off);
}

TEST_CASE("canned cycles in inches and in the XZ plane") {
  const Toolpath inch = run("G20\nG0 X0 Y0 Z0.5\nG98 G83 X1 Y2 Z-0.4 R0.1 Q0.15 F10\nM2\n");
  const auto m = moves(inch);
  REQUIRE(m.size() == 14);
  CHECK(m[3] == F(1, 2, -0.05));
  CHECK(m[5] == T(1, 2, -0.04)); // 0.010 in above the last peck
  CHECK(m.back() == T(1, 2, 0.5));
  // G18: the drilling axis is Y, the hole is at (Z, X).
  const Toolpath zx = run("G21 G18\nG0 X0 Y5 Z0\nG98 G81 X1 Z2 Y-4 R1 F100\nM2\n");
  const std::vector<std::string> expected = {T(0, 5, 0), T(1, 5, 2), T(1, 1, 2), F(1, -4, 2),
                                             T(1, 5, 2)};
  CHECK(moves(zx) == expected);
}

TEST_CASE("canned cycle errors: R below Z, peck without Q: a missing R only warns") {
  // A post that drops R (FreeCAD's comparams): the cycle starts where the tool is.
  const Toolpath nor = run("G21 G0 Z5\nG81 X1 Z-1 F100\nM2\n");
  CHECK(errors(nor) == 0);
  CHECK(with_severity(nor, Severity::Warning).size() == 1);
  REQUIRE(of_kind(nor, CanonKind::Feed).size() == 1);
  CHECK(of_kind(nor, CanonKind::Feed)[0].start.z == doctest::Approx(5));
  CHECK(errors(run("G21 G0 Z5\nG81 X1 Z2 R1 F100\nM2\n")) == 1);
  const Toolpath noq = run("G21 G0 Z5\nG83 X1 Z-1 R1 F100\nM2\n");
  CHECK(errors(noq) == 0); // a warning: the hole is drilled in one go
  CHECK(with_severity(noq, Severity::Warning).size() == 1);
  CHECK(moves(noq).back() == T(1, 0, 1)); // drilled in one go
}

TEST_CASE("a peck cycle whose Q is no step at its R height is refused, not run forever") {
  // Found by fuzzing: R1.1e117 with Q4 never got deeper (R - Q == R in floating point).
  const Toolpath p = run("G21 G90\nG0 X0 Y0 Z5\nG83 X15 Y15 Z-15 R" + std::string(118, '1') +
                             ". Q4 F90\nG80\nM2\n",
                         "fanuc");
  CHECK(errors(p) == 1);
  CHECK(p.commands.size() < 100);
  // As many pecks as a cycle may repeat, and one more.
  CHECK(errors(run("G21 G90\nG0 X0 Y0 Z5\nG83 X1 Y1 Z-1000 R2 Q0.001 F90\nG80\nM2\n")) == 1);
  CHECK(errors(run("G21 G90\nG0 X0 Y0 Z5\nG83 X1 Y1 Z-15 R2 Q4 F90\nG80\nM2\n")) == 0);
}
