// MTConnect time stamps: the forms agents and adapters write, and what is not one.
#include <doctest/doctest.h>

#include "ncjoule/logs.hpp"

using namespace ncjoule;

TEST_CASE("log times: ISO 8601 stamps in UTC, with fractions and offsets") {
  // 2017-02-07T19:38:27Z: 17204 days after 1970-01-01, 19:38:27 into the day.
  const double day = 17204.0 * 86400;
  CHECK(parse_log_time("2017-02-07T19:38:27Z").value() == doctest::Approx(day + 70707));
  CHECK(parse_log_time("2017-02-07T19:38:27.6093750Z").value() ==
        doctest::Approx(day + 70707.609375).epsilon(1e-12));
  CHECK(parse_log_time("2017-02-07T19:38:27.5").value() == doctest::Approx(day + 70707.5));
  // An offset: 20:38:27+01:00 is 19:38:27 UTC.
  CHECK(parse_log_time("2017-02-07T20:38:27+01:00").value() == doctest::Approx(day + 70707));
  CHECK(parse_log_time("1970-01-01T00:00:00Z").value() == 0);
  CHECK(format_log_time(day + 70707.6) == "2017-02-07 19:38:27 UTC");
}

TEST_CASE("log times: what is not a time stamp is refused") {
  CHECK_FALSE(parse_log_time(""));
  CHECK_FALSE(parse_log_time("Block_Number"));
  CHECK_FALSE(parse_log_time("2017-13-07T19:38:27Z"));
  CHECK_FALSE(parse_log_time("2017-02-07T19:38:27.Z"));
  CHECK_FALSE(parse_log_time("2017-02-07T19:38:27Zjunk"));
  CHECK_FALSE(parse_log_time("2017-02-07"));
}
