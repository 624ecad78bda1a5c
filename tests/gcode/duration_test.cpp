// Durations in words and on a clock: rounding at the unit boundaries, and no overflow.
#include <cmath>
#include <doctest/doctest.h>
#include <limits>

#include "ncjoule/duration.hpp"

using namespace ncjoule;

TEST_CASE("durations in words and on a clock") {
  CHECK(duration_words(12.34) == "12.3 s");
  CHECK(duration_words(125) == "2 min 05.0 s");
  CHECK(duration_words(3723) == "1 h 02 min 03.0 s");
  CHECK(duration_words(59.96) == "1 min 00.0 s"); // rounded before it is split
  CHECK(duration_clock(125) == "2:05");
  CHECK(duration_clock(3599.6) == "1:00:00");
  CHECK(duration_clock(3723) == "1:02:03");
}

TEST_CASE("durations never overflow and never go negative") {
  CHECK(duration_words(6e28) == "16700000000000000000000000 h"); // no exponent
  CHECK(duration_clock(6e28) == "16700000000000000000000000 h");
  CHECK(duration_words(1e12) == "277777777 h 46 min 40.0 s");
  CHECK(duration_words(-5) == "0.0 s");
  CHECK(duration_words(std::numeric_limits<double>::quiet_NaN()) == "0.0 s");
  CHECK(duration_words(std::numeric_limits<double>::infinity()) == "0.0 s");
  const ClockParts p = split_duration(7199.99, 1);
  CHECK(p.hours == 2);
  CHECK(p.minutes == 0);
  CHECK(p.seconds == 0);
}

TEST_CASE("durations past double precision split into hours alone, never an out-of-range int") {
  // Found by the pipeline fuzz target: a Z move of 2e29 mm at a feed rate gave a rest of
  // -4.6e9 s after the hours, cast to int.
  for (const double seconds : {1.6e25, 3.3e29, 1e300, 9.007199254740993e15 * 3600}) {
    CAPTURE(seconds);
    const ClockParts p = split_duration(seconds, 0.1);
    CHECK(p.minutes >= 0);
    CHECK(p.minutes <= 59);
    CHECK(p.seconds >= 0);
    CHECK(p.seconds < 60);
    CHECK(p.hours == doctest::Approx(seconds / 3600));
  }
}

TEST_CASE("whole numbers are written out in full, never with an exponent") {
  CHECK(whole_number_text(0, 3) == "0");
  CHECK(whole_number_text(-0.2, 3) == "0");
  CHECK(whole_number_text(1234567, 3) == "1234567"); // exact where a double is
  CHECK(whole_number_text(-98765.4, 3) == "-98765");
  CHECK(whole_number_text(1.666e25, 3) == "16700000000000000000000000");
  CHECK(whole_number_text(9.996e20, 3) == "1000000000000000000000"); // rounding carries
  CHECK(whole_number_text(-2.5e17, 2) == "-250000000000000000");
  const std::string most = whole_number_text(std::numeric_limits<double>::max(), 3);
  CHECK(most.size() == 309);
  CHECK(most.rfind("180", 0) == 0);
  CHECK(whole_number_text(std::numeric_limits<double>::infinity(), 3) == "0");
  CHECK(huge_hours(3e12) == "3000000000000");
}
