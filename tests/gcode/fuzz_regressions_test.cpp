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
  CHECK(errors(p) == 1); // the parameter number out of range
  const auto m = move_commands(p);
  REQUIRE(m.size() == 2);
  CHECK(m[0].end.y == 1e300);
  CHECK(m[1].end.x == 2.0);
}

TEST_CASE("a spline with coordinates that overflow to infinity is flattened without UB") {
  const Toolpath p = run("G21 G0 X0 Y0\n#1=[10**308]\nG5 X#1 Y#1 I#1 J-#1 P-#1 Q#1 F100\nM2\n");
  CHECK(of_kind(p, CanonKind::Feed).size() >= 1);
}
