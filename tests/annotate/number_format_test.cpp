// The compact formats of annotation fields.
#include <doctest/doctest.h>

#include "number_format.hpp"

using namespace ncjoule::annotation;

TEST_CASE("significant digits without exponents or trailing zeros") {
  CHECK(format_significant(34.5, 3, 3) == "34.5");
  CHECK(format_significant(1.2345, 3, 3) == "1.23");
  CHECK(format_significant(0.012345, 3, 3) == "0.012"); // at most max_decimals
  CHECK(format_significant(0.012345, 3, 4) == "0.0123");
  CHECK(format_significant(1234.6, 3, 3) == "1235");
  CHECK(format_significant(2.0, 3, 3) == "2");
  CHECK(format_significant(0.0, 3, 3) == "0");
  CHECK(format_significant(-0.0001, 3, 3) == "0");
  CHECK(format_significant(0.000000806, 4, 12) == "0.000000806");
  CHECK(format_significant(-12.5, 3, 3) == "-12.5");
}

TEST_CASE("durations") {
  CHECK(format_duration(0.0123) == "0.012s"); // milliseconds at most
  CHECK(format_duration(0.0004) == "0s");
  CHECK(format_duration(1.234) == "1.23s");
  CHECK(format_duration(12.34) == "12.3s");
  CHECK(format_duration(59.96) == "1m00s");
  CHECK(format_duration(83) == "1m23s");
  CHECK(format_duration(3723.4) == "1h02m03s");
}

TEST_CASE("SI prefixes") {
  CHECK(format_si(450, "J") == "450J");
  CHECK(format_si(1234, "J") == "1.23kJ");
  CHECK(format_si(999.7, "J") == "1kJ");
  CHECK(format_si(4.5e6, "J") == "4.5MJ");
  CHECK(format_si(0.5, "W") == "0.5W");
}

TEST_CASE("user text becomes one safe token") {
  CHECK(safe_token("2D Pocket1", 24) == "2D_Pocket1");
  CHECK(safe_token("  Face (rough) – 50% #1 ", 24) == "Face_rough_50_1");
  CHECK(safe_token("a=b", 24) == "a_b");
  CHECK(safe_token("Very long operation name indeed", 10) == "Very_long");
}
