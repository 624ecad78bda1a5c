// Expressions, functions and parameters. Every expected value is what `rs274 -g` gives for the
// same expression.
#include <doctest/doctest.h>

#include <charconv>
#include <cmath>
#include <random>
#include <string>

#include "expression.hpp"
#include "program_runner.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {
// Runs "G0 X[expr]" after `setup` and returns X in mm (NaN when the move is missing).
double x_of(const std::string& expr, const std::string& setup = "") {
  const Toolpath p = run("G21\n" + setup + "G0 X" + expr + "\nM2\n");
  const auto m = move_commands(p);
  return m.empty() ? std::nan("") : m.back().end.x;
}
} // namespace

TEST_CASE("operator precedence: ** before * / MOD before + - before comparisons before logic") {
  CHECK(x_of("[1+2*3]") == 7.0);
  CHECK(x_of("[2**3**2]") == 64.0); // left to right
  CHECK(x_of("[-2**2]") == 4.0);    // unary minus binds tighter than **
  CHECK(x_of("[10/4]") == 2.5);
  CHECK(x_of("[1+2 GT 2 AND 0 OR 1]") == 1.0);
  CHECK(x_of("[7 XOR 0]") == 1.0);
  CHECK(x_of("[[1+2]*3]") == 9.0);
}

TEST_CASE("functions: two-argument ATAN in degrees, rounding, roots and trigonometry") {
  CHECK(x_of("[ATAN[1]/[-1]]") == doctest::Approx(135.0));
  CHECK(x_of("[ROUND[-2.5]]") == -3.0);
  CHECK(x_of("[ROUND[2.4]]") == 2.0);
  CHECK(x_of("[FIX[-2.5]]") == -3.0);
  CHECK(x_of("[FUP[-2.5]]") == -2.0);
  CHECK(x_of("[SQRT[16]+ABS[-1]]") == 5.0);
  CHECK(x_of("[SIN[30]*COS[60]]") == doctest::Approx(0.25));
  CHECK(x_of("[EXP[0]+LN[1]]") == 1.0);
  CHECK(x_of("[ACOS[0]]") == doctest::Approx(90.0));
  CHECK(x_of("[TAN[45]]") == doctest::Approx(1.0));
  CHECK(x_of("abs[-3]") == 3.0); // a function may stand as a word's value
}

TEST_CASE("MOD takes the sign of nothing: results are never negative") {
  CHECK(x_of("[-7 MOD 3]") == 2.0);
  CHECK(x_of("[7 MOD -3]") == 1.0);
  CHECK(x_of("[7.5 MOD 2]") == 1.5);
}

TEST_CASE("EQ and NE compare with rs274's tolerance of 0.0001") {
  CHECK(x_of("[1 EQ 1.00001]") == 1.0);
  CHECK(x_of("[1 EQ 1.001]") == 0.0);
  CHECK(x_of("[1 NE 1.00001]") == 0.0);
  CHECK(x_of("[2 GE 2]") == 1.0);
  CHECK(x_of("[2 LT 2]") == 0.0);
}

TEST_CASE("named and numbered parameters, EXISTS, indirect parameters") {
  CHECK(x_of("#1", "#1=5\n") == 5.0);
  CHECK(x_of("#<depth>", "#<Depth>=3\n") == 3.0); // names are case-insensitive
  CHECK(x_of("#<_global>", "#<_global>=4\n") == 4.0);
  CHECK(x_of("[EXISTS[#<depth>]+EXISTS[#<nope>]*10]", "#<depth>=3\n") == 1.0);
  CHECK(x_of("#[1+1]", "#2=6\n") == 6.0);
  CHECK(x_of("##3", "#3=4\n#4=9\n") == 9.0);
}

TEST_CASE("assignments take effect after the line, all reading the old values") {
  // rs274: X5 (the old #1), then #2 = old #1 + 1 = 1.
  const Toolpath p = run("G21\n#1=5\n#1=10 #2=[#1+1] G0 X#1\nG0 Y#2 Z#1\nM2\n");
  CHECK(errors(p) == 0);
  const auto m = move_commands(p);
  REQUIRE(m.size() == 2);
  CHECK(m[0].end.x == 5.0);
  CHECK(m[1].end.y == 6.0);
  CHECK(m[1].end.z == 10.0);
}

TEST_CASE("expression errors name the column and skip the block") {
  const Toolpath p = run("G21\nG0 X[1/0]\nG0 Y#<unset>\nG0 X[SQRT[-1]]\nG0 X[1+]\nG0 Z1\nM2\n");
  const auto e = with_severity(p, Severity::Error);
  REQUIRE(e.size() == 4);
  CHECK(e[0].line == 2);
  CHECK(e[0].column == 4);
  CHECK(e[0].message.find("division by zero") != std::string::npos);
  CHECK(e[1].message.find("unset") != std::string::npos);
  CHECK(e[3].line == 5);
  CHECK(moves(p).size() == 1);
}

TEST_CASE("system parameters: #<_x> and friends in program units") {
  CHECK(x_of("[#<_y>*2]", "G20 G0 Y1.5\n") == doctest::Approx(3.0 * 25.4));
  CHECK(x_of("#<_metric>") == 1.0);
  CHECK(x_of("#5220") == 1.0); // G54 is the active system
}

TEST_CASE("a value that overflows is an error where it arises, never infinity or NaN") {
  // An infinite dwell was dropped, an infinite coordinate made a move of no time.
  for (const char* block :
       {"G4 P[10**308*10]", "G0 X[10**400]", "G0 X[EXP[1000]]", "G0 X[0-10**308-10**308]",
        "G0 X[1/[10**-320]]", "#1=[10**308*10]", "G0 X[10**308*10 GT 0]"}) {
    CAPTURE(block);
    const Toolpath p = run(std::string("G21\n") + block + "\nM2\n");
    const auto e = with_severity(p, Severity::Error);
    REQUIRE(e.size() == 1);
    CHECK(e[0].line == 2);
    CHECK(e[0].column > 0);
    CHECK(e[0].message.find("not a finite number") != std::string::npos);
    CHECK(moves(p).empty());
  }
  // A number too long for a double, written out.
  const Toolpath p = run("G21\nG0 X" + std::string(400, '9') + "\nM2\n");
  REQUIRE(errors(p) == 1);
  CHECK(p.result.diagnostics[0].message.find("out of range") != std::string::npos);
}

TEST_CASE("signs and parameter references chain in any order") {
  CHECK(x_of("[--1]") == 1.0);
  CHECK(x_of("[-+-+-2]") == -2.0);
  CHECK(x_of("-#1", "#1=5\n") == -5.0);
  CHECK(x_of("#-#1", "#1=-2\n#2=7\n") == 7.0);
  CHECK(x_of("[-#-#1]", "#1=-2\n#2=7\n") == -7.0);
  CHECK(x_of("[2**-1]") == 0.5);
  CHECK(x_of("[-2**2]") == 4.0);
  CHECK(x_of("[1 - -1 * 3]") == 4.0);
}

TEST_CASE("brackets nest up to the limit, and a level more is an error with its column") {
  const int n = detail::kMaxExpressionNesting;
  const std::string deepest = std::string(n, '[') + "1" + std::string(n, ']');
  CHECK(x_of(deepest) == 1.0);
  const Toolpath p = run("G21\nG0 X[" + deepest + "]\nM2\n");
  const auto e = with_severity(p, Severity::Error);
  REQUIRE(e.size() == 1);
  CHECK(e[0].line == 2);
  CHECK(e[0].column == 4);
  CHECK(e[0].message.find("nested more than 128 brackets deep") != std::string::npos);
}

TEST_CASE("plain numbers read to the same double from_chars gives, in every form a word takes") {
  // Short decimals take a fast path: each must equal the correctly rounded value.
  std::mt19937_64 random(43);
  int checked = 0;
  for (int i = 0; i < 100000; ++i) {
    const int whole_digits = int(random() % 10), fraction_digits = int(random() % 25);
    std::string text;
    for (int k = 0; k < whole_digits; ++k)
      text += char('0' + random() % 10);
    if (fraction_digits > 0 || whole_digits == 0) text += '.';
    for (int k = 0; k < fraction_digits; ++k)
      text += char('0' + random() % 10);
    if (text == ".") continue;
    const std::string whole = text.front() == '.' ? "0" + text : text;
    double expected = 0, got = -1;
    std::from_chars(whole.data(), whole.data() + whole.size(), expected);
    REQUIRE(detail::parse_plain_number(text, got));
    if (got != expected) FAIL_CHECK(text);
    const std::string negative = "-" + text;
    REQUIRE(detail::parse_plain_number(negative, got));
    if (got != -expected || !std::signbit(got)) FAIL_CHECK(negative);
    ++checked;
  }
  CHECK(checked > 90000);
  double v = 0;
  CHECK(detail::parse_plain_number("9007199254740993", v)); // past 2^53: from_chars reads it
  CHECK(v == 9007199254740992.0);
  CHECK(detail::parse_plain_number("-0", v));
  CHECK(std::signbit(v));
  for (const char* bad : {"", ".", "-", "+", "1.2.3", "1e5", "12a", "-.", " 1"})
    CHECK_FALSE(detail::parse_plain_number(bad, v));
}
