// Values beyond what industrial controls take are errors with their column, never a move of
// no time or a dropped dwell: lengths to 99,999.999 mm (9,999.9999 in), angles to 99,999.999
// degrees, dwells to 99,999.999 s, S to 1,000,000 rpm, F and other words to eight digits.
#include <doctest/doctest.h>

#include "program_runner.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

// The one error of a program, which must say `words`.
Diagnostic only_error(const Toolpath& p, const std::string& words) {
  const auto e = with_severity(p, Severity::Error);
  REQUIRE(e.size() == 1);
  CHECK(e[0].message.find(words) != std::string::npos);
  return e[0];
}

} // namespace

TEST_CASE("a word beyond its range is an error at its column, and its block does not run") {
  struct Case {
    std::string block;
    int column;
  };
  const Case cases[] = {
      {"G2 X1 Y0 R10000000000000 F100", 10}, // radius 1e13: an arc of no time
      {"G1 X100000000000000000000000000000 F100", 4},
      {"G1 X" + std::string(100, '6') + " F100", 4},
      {"G0 Y100000", 4},
      {"G0 Z-100000", 4},
      {"G2 X1 I100000 F100", 7},
      {"G0 A100000", 4},
      {"G1 X1 F100000000", 7},
      {"G1 X1 F0.00001", 7},
      {"S1000001 M3", 1},
      {"G4 P[10**10]", 4},
  };
  for (const Case& c : cases) {
    CAPTURE(c.block);
    const Toolpath p = run("G21 G90 G0 X0 Y0 Z0\n" + c.block + "\nG0 X5\nM2\n");
    const Diagnostic e = only_error(p, "out of range");
    CHECK(e.line == 2);
    CHECK(e.column == c.column);
    const auto m = move_commands(p);
    REQUIRE(m.size() == 2); // the block before and the block after
    CHECK(m[1].end.x == 5.0);
    CHECK(of_kind(p, CanonKind::Dwell).empty());
  }
}

TEST_CASE("values at the limits are taken") {
  const Toolpath p =
      run("G21 G90\nG0 X99999.999 Y-99999.999 Z0 A99999.999\nG1 X0 F99999999\nG1 X1 F0.0001\n"
          "G4 P99999.999\nS1000000 M3\nG20\nG0 X9999.9999\nM2\n");
  CHECK(errors(p) == 0);
  CHECK(move_commands(p).size() == 4);
  REQUIRE(of_kind(p, CanonKind::Dwell).size() == 1);
  CHECK(of_kind(p, CanonKind::Dwell)[0].value == 99999.999);
  // In inches the bound is 9,999.9999 in, whatever the units were before the block.
  CHECK(errors(run("G21 G90\nG20 G0 X10000\nM2\n")) == 1);
  CHECK(errors(run("G20 G90\nG21 G0 X99999\nM2\n")) == 0);
}

TEST_CASE("dwells are bounded in seconds, whatever unit P is in") {
  // LinuxCNC: P in seconds.
  const Toolpath p = run("G21\nG4 P100000\nM2\n");
  const Diagnostic e = only_error(p, "dwell out of range");
  CHECK(e.column == 4);
  CHECK(of_kind(p, CanonKind::Dwell).empty());
  // Fanuc: P in ms, eight digits are 99,999.999 s.
  const Toolpath f = run("O1000\nG4 P99999999\nM30\n", "fanuc");
  CHECK(errors(f) == 0);
  REQUIRE(of_kind(f, CanonKind::Dwell).size() == 1);
  CHECK(of_kind(f, CanonKind::Dwell)[0].value == doctest::Approx(99999.999));
  // A canned cycle's dwell and a Sinumerik cycle's: refused as they are made.
  only_error(run("G21 G90 G0 X0 Y0 Z5\nG82 X1 Y1 Z-1 R1 P1000000 F100\nG80\nM2\n"),
             "dwell out of range");
  only_error(run("G0 X0 Y0 Z20\nF100\nCYCLE82(10, -1, 1, , 5, 1000000)\nM30\n", "siemens"),
             "dwell out of range");
}

TEST_CASE("a position that incremental moves push out of range is refused: the machine stays") {
  const Toolpath p = run("G21 G91\nG0 X60000\nG0 X60000\nG0 X-10000\nM2\n");
  const Diagnostic e = only_error(p, "the move goes out of range");
  CHECK(e.line == 3);
  CHECK(e.column == 1);
  const auto m = move_commands(p);
  REQUIRE(m.size() == 2);
  CHECK(m[0].end.x == 60000.0);
  CHECK(m[1].start.x == 60000.0); // from where the machine is, not where it was told to go
  CHECK(m[1].end.x == 50000.0);
  // A Sinumerik frame shifted past the range.
  CHECK(errors(run("G0 X0 Y0\nTRANS X90000\nG0 X20000\nM30\n", "siemens")) == 1);
}
