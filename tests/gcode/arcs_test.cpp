// Arcs and helices: R form both ways round, full circles, every plane, P turns, and the radius
// check. Expected lines are what `rs274 -g` prints for the same programs.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "program_runner.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("R-form arcs: positive R takes the short way, negative R the long way") {
  const Toolpath p = run("G21 G17\nG0 X0 Y0 Z0\nG2 X10 Y0 R5 F100\nG3 X0 Y0 R-5\nG2 X10 Y0 R-6\n"
                         "G2 X0 Y0 R6\nM2\n");
  CHECK(errors(p) == 0);
  const auto m = move_commands(p);
  REQUIRE(m.size() == 5);
  // rs274 prints the centre's Y as -0.0000 too.
  CHECK(format_canon(m[1]) ==
        "ARC_FEED(10.0000, 0.0000, 5.0000, -0.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)");
  CHECK(format_canon(m[2]) ==
        "ARC_FEED(0.0000, 0.0000, 5.0000, 0.0000, 1, 0.0000, 0.0000, 0.0000, 0.0000)");
  // R6 over a 10 mm chord: centre 3.3166 off the chord's middle, on the side that makes the
  // arc longer than a half circle for R-6 and shorter for R6.
  CHECK(format_canon(m[3]) ==
        "ARC_FEED(10.0000, 0.0000, 5.0000, 3.3166, -1, 0.0000, 0.0000, 0.0000, 0.0000)");
  CHECK(format_canon(m[4]) ==
        "ARC_FEED(0.0000, 0.0000, 5.0000, 3.3166, -1, 0.0000, 0.0000, 0.0000, 0.0000)");
  CHECK(std::abs(arc_geometry(m[3]).sweep) > std::numbers::pi);
  CHECK(std::abs(arc_geometry(m[4]).sweep) < std::numbers::pi);
  CHECK(arc_geometry(m[4]).radius == doctest::Approx(6.0));
}

TEST_CASE("R-form arc too small to reach its end point: a warning, taken as a half circle") {
  const Toolpath p = run("G21 G0 X0 Y0\nG2 X10 Y0 R4 F100\nM2\n");
  CHECK(errors(p) == 0);
  const auto w = with_severity(p, Severity::Warning);
  REQUIRE(w.size() == 1);
  CHECK(w[0].line == 2);
  CHECK(w[0].column == 11); // the R word
  const auto arcs = of_kind(p, CanonKind::Arc);
  REQUIRE(arcs.size() == 1);
  CHECK(arcs[0].centre_first == doctest::Approx(5));
  CHECK(arcs[0].centre_second == doctest::Approx(0).epsilon(1e-9));
}

TEST_CASE("full circles with IJK, and P extra turns with a helix") {
  const Toolpath p = run("G21\nG0 X0 Y0 Z0\nG2 X0 Y0 I5 J0 F100\nG3 I-5 Z-2 P3\nM2\n");
  CHECK(errors(p) == 0);
  const auto arcs = of_kind(p, CanonKind::Arc);
  REQUIRE(arcs.size() == 2);
  CHECK(format_canon(arcs[0]) ==
        "ARC_FEED(0.0000, 0.0000, 5.0000, 0.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)");
  CHECK(format_canon(arcs[1]) ==
        "ARC_FEED(0.0000, 0.0000, -5.0000, 0.0000, 3, -2.0000, 0.0000, 0.0000, 0.0000)");
  const ArcGeometry full = arc_geometry(arcs[0]);
  CHECK(full.sweep == doctest::Approx(-2 * std::numbers::pi));
  CHECK(full.length == doctest::Approx(10 * std::numbers::pi));
  const ArcGeometry helix = arc_geometry(arcs[1]);
  CHECK(helix.sweep == doctest::Approx(6 * std::numbers::pi));
  CHECK(helix.axial == doctest::Approx(-2.0));
  CHECK(helix.length == doctest::Approx(std::hypot(30 * std::numbers::pi, 2.0)));
}

TEST_CASE("helices in every plane: G18 (ZX), G19 (YZ), G17 (XY)") {
  const Toolpath p = run("G21\nG0 X0 Y0 Z0\nG18 G2 X10 Z0 Y-3 I5 K0 F100\n"
                         "G19 G3 Y7 Z0 X2 J5 K0 P2\nG17 G3 X0 Y7 Z-1 I-1 J0\nM2\n");
  CHECK(errors(p) == 0);
  const auto arcs = of_kind(p, CanonKind::Arc);
  REQUIRE(arcs.size() == 3);
  // rs274 prints the plane's first and second axis: Z X for G18, Y Z for G19.
  CHECK(arcs[0].plane == Plane::XZ);
  CHECK(format_canon(arcs[0]) ==
        "ARC_FEED(0.0000, 10.0000, 0.0000, 5.0000, -1, -3.0000, 0.0000, 0.0000, 0.0000)");
  CHECK(arc_geometry(arcs[0]).axial == doctest::Approx(-3.0));
  CHECK(arcs[1].plane == Plane::YZ);
  CHECK(format_canon(arcs[1]) ==
        "ARC_FEED(7.0000, 0.0000, 2.0000, 0.0000, 2, 2.0000, 0.0000, 0.0000, 0.0000)");
  CHECK(arc_geometry(arcs[1]).sweep == doctest::Approx(3 * std::numbers::pi));
  CHECK(arcs[2].plane == Plane::XY);
  CHECK(format_canon(arcs[2]) ==
        "ARC_FEED(0.0000, 7.0000, 1.0000, 7.0000, 1, -1.0000, 0.0000, 0.0000, 0.0000)");
  // The helix ends where it should: point_on_move at 1 is the end point.
  const Pose end = point_on_move(arcs[1], 1.0);
  CHECK(end.x == doctest::Approx(2.0));
  CHECK(end.y == doctest::Approx(7.0));
  CHECK(end.z == doctest::Approx(0.0));
  const Pose half = point_on_move(arcs[1], 0.5);
  CHECK(half.x == doctest::Approx(6.0)); // halfway along the helix axis, from X10 to X2
}

TEST_CASE("end radius off the start radius: silent within rs274ngc's tolerance, else a spiral") {
  // rs274 (LinuxCNC 2.9) refuses an arc when |r1 - r2| exceeds 2*sqrt(2)*0.01 mm (0.0283 mm;
  // 2*sqrt(2)*0.001 in in inch programs) and 0.1% of the radius, or 100 times that absolute
  // limit. Measured with rs274: a quarter arc of radius 1 mm is refused from r2 = 1.02829 mm.
  CHECK(warnings(run("G21 G0 X0 Y0\nG3 X1 Y-1.0282 I1 J0 F100\nM2\n")) == 0);
  CHECK(warnings(run("G21 G0 X0 Y0\nG3 X1 Y-1.0284 I1 J0 F100\nM2\n")) == 1);
  // Inch: 0.0028 in passes, 0.0029 in does not.
  CHECK(warnings(run("G20 G0 X0 Y0\nG3 X1 Y-1.0028 I1 J0 F10\nM2\n")) == 0);
  CHECK(warnings(run("G20 G0 X0 Y0\nG3 X1 Y-1.0029 I1 J0 F10\nM2\n")) == 1);
  // The relative limit: 0.05 mm off a 100 mm radius is within 0.1%.
  CHECK(warnings(run("G21 G0 X0 Y0\nG3 X100 Y-100.05 I100 J0 F100\nM2\n")) == 0);
  // Inch posts rounding to 4 decimals: 0.00008 in (0.002 mm) off, no word at all.
  CHECK(warnings(run("G20 G0 X0.1234 Y0\nG2 X0.6234 Y0.00008 I0.25 J0 F10\nM2\n")) == 0);

  // Far off: a warning naming both radii, never an error, and the arc is timed as a spiral.
  const Toolpath p = run("G21 G0 X0 Y0 Z0\nG2 X10 Y0 I4 J0 F100\nM2\n");
  CHECK(errors(p) == 0);
  const auto w = with_severity(p, Severity::Warning);
  REQUIRE(w.size() == 1);
  CHECK(w[0].line == 2);
  CHECK(w[0].message.find("r1=4.0000 r2=6.0000") != std::string::npos);
  const auto arcs = of_kind(p, CanonKind::Arc);
  REQUIRE(arcs.size() == 1);
  CHECK(arcs[0].end.x == doctest::Approx(10));
}

TEST_CASE("I/J written from the centre to the start: detected, warned about once, followed") {
  // A post that writes I/J as (start - centre): every arc fits only that way.
  const Toolpath p = run("G21 G0 X0 Y0\nG2 X10 Y0 I-5 J0 F100\nG2 X20 Y0 I-5 J0\n"
                         "G3 X30 Y0 I-5 J0\nM2\n");
  CHECK(errors(p) == 0);
  const auto w = with_severity(p, Severity::Warning);
  REQUIRE(w.size() == 1);
  CHECK(w[0].line == 2);
  CHECK(w[0].message.find("centre to the start") != std::string::npos);
  const auto arcs = of_kind(p, CanonKind::Arc);
  REQUIRE(arcs.size() == 3);
  CHECK(arcs[0].centre_first == doctest::Approx(5));
  CHECK(arcs[1].centre_first == doctest::Approx(15));
  CHECK(arcs[2].centre_first == doctest::Approx(25));
  // Read the standard way, the same arcs fit: no switch, no warning.
  CHECK(warnings(run("G21 G0 X0 Y0\nG2 X10 Y0 I5 J0 F100\nG2 X20 Y0 I5 J0\nM2\n")) == 0);
}

TEST_CASE("arc P must be a positive integer, an arc needs offsets or R") {
  const Toolpath p = run("G21 G0 X0 Y0\nG2 X0 Y0 I5 P0 F100\nG2 X0 Y0 I5 P1.5\nG2 X1 Y1\nM2\n");
  CHECK(errors(p) == 3);
  CHECK(of_kind(p, CanonKind::Arc).empty());
}

TEST_CASE("arcs in inch programs: mm inside, inches when printed") {
  const Toolpath p = run("G20\nG0 X1 Y1 Z0.1\nG2 X3 Y1 I1 J0 F10\nG91 G3 X-1 Y1 R1\nM2\n");
  CHECK(errors(p) == 0);
  const auto arcs = of_kind(p, CanonKind::Arc);
  REQUIRE(arcs.size() == 2);
  CHECK(arcs[0].centre_first == doctest::Approx(50.8));
  CHECK(arcs[0].end.x == doctest::Approx(76.2));
  CHECK(arc_geometry(arcs[0]).radius == doctest::Approx(25.4));
  CHECK(format_canon(arcs[0]) ==
        "ARC_FEED(3.0000, 1.0000, 2.0000, 1.0000, -1, 0.1000, 0.0000, 0.0000, 0.0000)");
  // Incremental R arc: end (2, 2); a quarter circle about (2, 1).
  CHECK(format_canon(arcs[1]) ==
        "ARC_FEED(2.0000, 2.0000, 2.0000, 1.0000, 1, 0.1000, 0.0000, 0.0000, 0.0000)");
}

TEST_CASE("G93 arcs get the feed that makes them last 1/F minutes") {
  const Toolpath p = run("G21 G0 X0 Y0 Z0\nG93 G2 X10 Y0 R5 F2\nM2\n");
  const auto rates = of_kind(p, CanonKind::SetFeedRate);
  REQUIRE(rates.size() == 1);
  CHECK(rates[0].value == doctest::Approx(5 * std::numbers::pi * 2)); // length * F
}

TEST_CASE(
    "a full circle of zero radius: no motion with a warning under Mach3, refused by LinuxCNC") {
  // Eagle's stepcraft.ulp writes one for every hole smaller than its bit.
  const std::string text = "G21 G90\nG0 X1 Y1 Z0\nG1 Z-0.15 F30\nG3 X1 Y1 I0.000 F360\nG0 Z1\nM2\n";
  const Toolpath mach3 = run(text, "mach3");
  CHECK(errors(mach3) == 0);
  CHECK(moves(mach3).size() == 3); // the arc is not among them
  bool warned = false;
  for (const Diagnostic& d : mach3.result.diagnostics)
    warned = warned || (d.severity == Severity::Warning && d.line == 4 &&
                        d.message.find("zero radius") != std::string::npos);
  CHECK(warned);
  CHECK(errors(run(text, "linuxcnc")) == 1);
  // A zero-radius arc that goes somewhere is an error everywhere.
  CHECK(errors(run("G21 G90\nG0 X1 Y1 Z0\nG3 X2 Y1 I0 J0 F100\nM2\n", "mach3")) >= 1);
}

TEST_CASE("arc_bounds holds every point of the arc, in every plane, helices and spirals too") {
  // The stock's extent skips walking along an arc its box already holds: the box must hold
  // every point point_on_move gives, and be no more than a hair larger than the circle.
  const Toolpath p = run("G21\nG0 X0 Y0 Z0\nG17 G3 X0 Y0 I5 J0 Z-2 P3 F100\n"
                         "G18 G2 X10 Z0 I5 K0 Y4\nG19 G3 Y4 Z6 J0 K3 X-1\n"
                         "G17 G2 X20 Y1 I5.2 J0.5\nG17 G3 X40000 Y80000 I20000 J40000\nM2\n");
  std::size_t arcs = 0;
  for (const CanonCommand& c : move_commands(p)) {
    if (c.kind != CanonKind::Arc) continue;
    ++arcs;
    Pose low, high;
    arc_bounds(c, low, high);
    // No wider than the circle and the axis's travel (a spiral's end radius is at most its
    // start radius and the chord).
    const double chord = std::hypot(c.end.x - c.start.x, c.end.y - c.start.y, c.end.z - c.start.z);
    const double r = arc_geometry(c).radius + chord + 1e-6;
    CHECK(high.x - low.x <= 2 * r + std::abs(c.end.x - c.start.x));
    CHECK(high.y - low.y <= 2 * r + std::abs(c.end.y - c.start.y));
    CHECK(high.z - low.z <= 2 * r + std::abs(c.end.z - c.start.z));
    for (int k = 0; k <= 4096; ++k) {
      const Pose q = point_on_move(c, k / 4096.0);
      CHECK((low.x <= q.x && q.x <= high.x && low.y <= q.y && q.y <= high.y && low.z <= q.z &&
             q.z <= high.z));
    }
  }
  CHECK(errors(p) == 0);
  CHECK(arcs == 5);
}
