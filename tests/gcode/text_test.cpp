// The shared text helpers: trimming, ASCII case and whole-text numbers.
#include <doctest/doctest.h>

#include "ncjoule/text.hpp"

using namespace ncjoule;

TEST_CASE("trim takes blanks and line ends off both ends only") {
  CHECK(trim("  a b\t\r\n") == "a b");
  CHECK(trim(" \t\r\n").empty());
  CHECK(trim("x") == "x");
}

TEST_CASE("case changes touch ASCII letters only") {
  CHECK(to_upper("g1 x\xe9") == "G1 X\xe9"); // a Latin-1 byte stays as it is
  CHECK(to_lower("Box:1,2") == "box:1,2");
}

TEST_CASE("a number is the whole text, finite") {
  CHECK(parse_number(" 6 ") == 6.0);
  CHECK(parse_number("+1e3") == 1000.0);
  CHECK(parse_number(".5") == 0.5);
  CHECK(parse_number("6.") == 6.0);
  CHECK(parse_number("-0.25") == -0.25);
  for (const char* bad : {"", " ", "6mm", "nan", "inf", "1e999", "--1", "+"}) {
    CAPTURE(bad);
    CHECK_FALSE(parse_number(bad));
  }
}
