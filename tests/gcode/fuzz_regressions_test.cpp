// Inputs the fuzzers found, or their kind: huge numbers where an integer is expected must give a
// diagnostic, never undefined behaviour.
#include <doctest/doctest.h>

#include "program_runner.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("a G code too large for an integer is an error, not a cast overflow") {
  const Toolpath p =
      run("G44444444444444444444444444444444444444444444444444419 (Units)\nG0 X1\nM2\n");
  const auto e = with_severity(p, Severity::Error);
  REQUIRE(e.size() == 1);
  CHECK(e[0].line == 1);
  CHECK(e[0].column == 1);
  CHECK(moves(p).size() == 1);
  CHECK(errors(run("M[10**9]\nM2\n")) == 1);
}

TEST_CASE("huge parameter indices, ROUND and repeat counts stay defined") {
  const Toolpath p =
      run("G21\nG0 X#[10**300]\nG0 Y[ROUND[10**300]]\n#1=[10**300]\no1 repeat [#1*-1]\n"
          "G0 Z1\no1 endrepeat\nG0 X2\nM2\n");
  // The parameter number out of range, and Y1e300 beyond any control's range.
  CHECK(errors(p) == 2);
  const auto m = move_commands(p);
  REQUIRE(m.size() == 1);
  CHECK(m[0].end.x == 2.0);
}

TEST_CASE("a spline with coordinates that overflow to infinity is refused without UB") {
  // Every word is out of range: the block is an error; the flattening never sees them.
  const Toolpath p = run("G21 G0 X0 Y0\n#1=[10**308]\nG5 X#1 Y#1 I#1 J-#1 P-#1 Q#1 F100\nM2\n");
  CHECK(errors(p) >= 1);
  CHECK(of_kind(p, CanonKind::Feed).empty());
  // Within range, a spline across the whole range still flattens into a bounded number of moves.
  const Toolpath q = run("G21 G0 X-99999 Y0\nG5 X99999 Y0 I99999 J99999 P-99999 Q99999 F100\nM2\n");
  CHECK(errors(q) == 0);
  CHECK(of_kind(q, CanonKind::Feed).size() >= 1);
}
