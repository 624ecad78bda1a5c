// format_canon prints exactly what printf("%.4f") would, in program units, like `rs274 -g`.
#include <doctest/doctest.h>

#include <cstdio>
#include <string>

#include "ncjoule/gcode.hpp"

using namespace ncjoule;

TEST_CASE("moves print with printf's %.4f rounding, negative zero included") {
  CanonCommand c;
  c.kind = CanonKind::Feed;
  c.end = Pose{0.00005, -0.00004, 1234.56785, 1.23456789, -0.5, 359.99995};
  char expected[256];
  std::snprintf(expected, sizeof expected, "STRAIGHT_FEED(%.4f, %.4f, %.4f, %.4f, %.4f, %.4f)",
                c.end.x, c.end.y, c.end.z, c.end.a, c.end.b, c.end.c);
  CHECK(format_canon(c) == expected);
  CHECK(format_canon(c).find("-0.0000") != std::string::npos);
}

TEST_CASE("inch programs print in inches, arcs print the plane's axes and the turns") {
  CanonCommand c;
  c.kind = CanonKind::Arc;
  c.state.inch = true;
  c.plane = Plane::XZ;
  c.end = Pose{25.4, 50.8, 76.2, 0, 0, 0};
  c.centre_first = 12.7;
  c.centre_second = -25.4;
  c.rotation = -3;
  CHECK(format_canon(c) ==
        "ARC_FEED(3.0000, 1.0000, 0.5000, -1.0000, -3, 2.0000, 0.0000, 0.0000, 0.0000)");
}

TEST_CASE("huge values print whole instead of overrunning a buffer") {
  CanonCommand c;
  c.kind = CanonKind::Traverse;
  c.end.x = 1e300;
  const std::string line = format_canon(c);
  CHECK(line.size() > 300);
  CHECK(line.rfind("STRAIGHT_TRAVERSE(1000000000000000052504760255204420248704468581108159154",
                   0) == 0);
  CHECK(line.substr(line.size() - 46) == ".0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  c.kind = CanonKind::Dwell;
  c.value = 1e300;
  CHECK(format_canon(c).size() > 300);
}
