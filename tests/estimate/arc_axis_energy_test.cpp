// The axis terms of arcs: each axis draws its line for the distance it travels along the arc,
// whether or not material removal sampled the move (without it, a move has only its two ends,
// and a full circle's chord is zero).
#include <doctest/doctest.h>

#include <string>

#include "estimate_checks.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"

using namespace ncjoule;
using namespace estimate_test;

namespace {

constexpr std::size_t kAxisX = std::size_t(PowerComponent::AxisX);
constexpr std::size_t kAxisY = std::size_t(PowerComponent::AxisY);
constexpr std::size_t kAxisZ = std::size_t(PowerComponent::AxisZ);

// The source line (0-based) of the arc in each program below.
constexpr int kArcLine = 5;

const LineSummary& line_of(const Estimate& e, int line) {
  for (const LineSummary& l : e.lines)
    if (l.line == line) return l;
  FAIL("no line " << line);
  return e.lines.front();
}

Estimate run(const std::string& arc, bool removal) {
  const std::string program = "G21 G90 G17\n(T1 D=6. CR=0. - FLAT END MILL)\nT1 M6\nS5000 M3\n"
                              "G0 X0 Y0 Z5\n" +
                              arc + "\nM5\nM30\n";
  EstimateOptions options;
  options.simulate_removal = removal;
  options.stock = parse_stock_spec("box:-50,-50,-30,50,50,-20"); // far below: nothing is cut
  return estimate_program(make_source("arc.ngc", program),
                          load_profile(std::string(NCJOULE_SOURCE_DIR) +
                                       "/samples/machines/haas-vf0-pavanaskar2014.toml"),
                          options);
}

} // namespace

TEST_CASE("a full circle moves X and Y four radii each: their move lines, removal or not") {
  const std::string circle = "G2 X0 Y0 I20 J0 F600"; // centre (20, 0), radius 20
  const Estimate bare = run(circle, false), sampled = run(circle, true);
  const LineSummary &a = line_of(bare, kArcLine), &b = line_of(sampled, kArcLine);
  REQUIRE(a.time_s == doctest::Approx(b.time_s));
  const PavanaskarConstants& p = bare.power.pavanaskar;
  // KA for the whole move, KB times the travel (the integral of each axis's speed): 80 mm each.
  CHECK(a.components_j[kAxisX] ==
        doctest::Approx(p.move_ka_w[0] * a.time_s + p.move_kb_w_per_mm_s[0] * 80).epsilon(1e-5));
  CHECK(a.components_j[kAxisY] ==
        doctest::Approx(p.move_ka_w[1] * a.time_s + p.move_kb_w_per_mm_s[1] * 80).epsilon(1e-5));
  CHECK(a.components_j[kAxisZ] == 0);
  // Removal samples the arc finely: the same energy, to its sampling.
  CHECK(b.components_j[kAxisX] == doctest::Approx(a.components_j[kAxisX]).epsilon(0.005));
  CHECK(b.components_j[kAxisY] == doctest::Approx(a.components_j[kAxisY]).epsilon(0.005));
}

TEST_CASE("a helical half turn: the in-plane axes by their quarter turns, Z by the rise") {
  // From (0, 0, 5) about (10, 0), counter-clockwise half a turn to (20, 0, 2): X travels 20 mm,
  // Y out 10 and back 10 (20 mm), Z 3 mm.
  const std::string helix = "G3 X20 Y0 Z2 I10 J0 F600";
  const Estimate bare = run(helix, false), sampled = run(helix, true);
  const LineSummary &a = line_of(bare, kArcLine), &b = line_of(sampled, kArcLine);
  const PavanaskarConstants& p = bare.power.pavanaskar;
  for (auto [component, axis, travel] :
       {std::tuple{kAxisX, 0, 20.0}, std::tuple{kAxisY, 1, 20.0}, std::tuple{kAxisZ, 2, 3.0}}) {
    CAPTURE(axis);
    CHECK(a.components_j[component] ==
          doctest::Approx(p.move_ka_w[axis] * a.time_s + p.move_kb_w_per_mm_s[axis] * travel)
              .epsilon(1e-5));
    CHECK(b.components_j[component] == doctest::Approx(a.components_j[component]).epsilon(0.005));
  }
}

namespace {

CanonCommand arc(Pose start, Pose end, double cx, double cy, int rotation) {
  CanonCommand c;
  c.kind = CanonKind::Arc;
  c.start = start;
  c.end = end;
  c.centre_first = cx;
  c.centre_second = cy;
  c.rotation = rotation;
  c.plane = Plane::XY;
  return c;
}

void check_travel(const CanonCommand& move, std::array<double, 3> expected) {
  const std::array<double, 3> t = axis_travel(move);
  for (int i = 0; i < 3; ++i) {
    CAPTURE(i);
    CHECK(t[i] == doctest::Approx(expected[i]).epsilon(1e-9));
  }
}

} // namespace

TEST_CASE("axis_travel: quarter turns, full turns, turns of a helix, both directions") {
  // A quarter from (10, 0) to (0, 10) about the origin, counter-clockwise: 10 mm each.
  check_travel(arc({10, 0, 0}, {0, 10, 0}, 0, 0, 1), {10, 10, 0});
  // The same ends clockwise: three quarters through (0, -10) and (-10, 0), 30 mm each.
  check_travel(arc({10, 0, 0}, {0, 10, 0}, 0, 0, -1), {30, 30, 0});
  // A full circle of radius 20, and two more turns (P3).
  check_travel(arc({0, 0, 0}, {0, 0, 0}, 20, 0, -1), {80, 80, 0});
  check_travel(arc({0, 0, 0}, {0, 0, 0}, 20, 0, -3), {240, 240, 0});
  // 100 turns of a helix, radius 10, 10 mm down: past the exact quarter-by-quarter count.
  check_travel(arc({10, 0, 0}, {10, 0, -10}, 0, 0, 100), {4000, 4000, 10});
  // A line: its displacement.
  CanonCommand line;
  line.kind = CanonKind::Feed;
  line.start = {1, 2, 3};
  line.end = {-2, 6, 3};
  check_travel(line, {3, 4, 0});
}
