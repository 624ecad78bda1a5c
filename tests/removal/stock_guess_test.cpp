// The guessed stock (guess_stock): each rule of docs/removal.md, "The guessed stock", on the
// smallest program that shows it.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "fixture.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

std::optional<StockGuess> guess(const ProgramBuilder& p, const std::map<int, Tool>& tools,
                                bool inch = false, const Box3* first = nullptr) {
  StockExtent extent;
  for (const CanonCommand& c : p.commands())
    extent.add(c);
  return guess_stock(extent.tool_cuts(tools), inch, first);
}

bool says(const StockGuess& g, const std::string& words) {
  for (const std::string& rule : g.rules)
    if (rule.find(words) != std::string::npos) return true;
  return false;
}

// A raster over X0..60 Y0..40 at `z`, passes 5 mm apart, entered by a plunge from 5 mm above.
void raster(ProgramBuilder& p, double z) {
  p.rapid(0, 0, z + 5).feed(0, 0, z);
  for (double y = 0; y <= 40; y += 10) {
    p.feed(60, y, z);
    if (y + 5 <= 40) p.feed(60, y + 5, z).feed(0, y + 5, z);
    if (y + 10 <= 40) p.feed(0, y + 10, z);
  }
  p.rapid(0, 40, z + 5);
}

} // namespace

TEST_CASE("guessed stock: cuts just under Z0 make Z0 the top, not the cut") {
  // An engraving 0.3 mm deep, every move at one level: the old box had no height and removed
  // nothing. Its top is Z0, its outline the groove's edge (a line, not an area: widened by the
  // tool's radius).
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 2)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(300).rapid(10, 10, 2).feed(10, 10, -0.3).feed(50, 10, -0.3);
  p.feed(50, 30, -0.3).rapid(50, 30, 2);
  const auto g = guess(p, tools);
  REQUIRE(g);
  CHECK(g->box.zmax == 0);
  CHECK(g->box.zmin == doctest::Approx(-0.3));
  CHECK(g->box.xmin == doctest::Approx(9));
  CHECK(g->box.xmax == doctest::Approx(51));
  CHECK(g->box.ymax == doctest::Approx(31));
  CHECK(says(*g, "top: Z0"));
  CHECK(says(*g, "lines rather than areas (T1)"));

  // The removal of it: the groove, 2 mm wide and 0.3 mm deep over 60 mm, with round ends.
  const Timeline tl = constant_speed_timeline(p.commands(), 0.05);
  const RemovalResult r = simulate_removal(p.commands(), tl, tools, StockSpec{});
  CHECK(r.removed_mm3 == doctest::Approx((60 * 2 + std::numbers::pi) * 0.3).epsilon(0.02));
}

TEST_CASE("guessed stock: a face below Z0 removes its layer, and the face mill does not set the "
          "outline") {
  // Fusion's TOP FACE at Z-0.5 with a 50 mm face mill running past the part on every side,
  // then a 10 mm end mill clears the area X0..60 Y0..40 2 mm deep. The face mill's passes
  // reach X-30..90: the stock is where the end mill works.
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 50)}, {2, flat_end_mill(2, 10)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(1000).rapid(-30, 0, 5).feed(-30, 0, -0.5).feed(90, 0, -0.5);
  p.feed(90, 40, -0.5).feed(-30, 40, -0.5).rapid(-30, 40, 5);
  p.tool(2).feed_rate(600);
  raster(p, -2);
  const auto g = guess(p, tools);
  REQUIRE(g);
  CHECK(g->box.zmax == 0);
  CHECK(g->box.zmin == doctest::Approx(-2));
  CHECK(g->box.xmin == doctest::Approx(0));
  CHECK(g->box.xmax == doctest::Approx(60));
  CHECK(g->box.ymax == doctest::Approx(40));
  CHECK(says(*g, "facing passes of T1"));
  // The face removes its 0.5 mm layer over the whole stock.
  const Timeline tl = constant_speed_timeline(p.commands(), 0.1);
  const RemovalResult r = simulate_removal(p.commands(), tl, tools, StockSpec{});
  double face = 0;
  for (std::size_t k = 0; k < p.commands().size() && p.commands()[k].state.tool == 1; ++k)
    face += r.commands[k].removed_mm3;
  CHECK(face == doctest::Approx(60 * 40 * 0.5).epsilon(0.01));
}

TEST_CASE("guessed stock: a face at Z0 has a facing step above it") {
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 50)}, {2, flat_end_mill(2, 10)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(1000).rapid(-30, 0, 5).feed(-30, 0, 0).feed(90, 0, 0);
  p.feed(90, 40, 0).feed(-30, 40, 0).rapid(-30, 40, 5);
  p.tool(2).feed_rate(600);
  raster(p, -2);
  auto g = guess(p, tools);
  REQUIRE(g);
  CHECK(g->box.zmax == doctest::Approx(0.5)); // the usual allowance, 0.5 mm
  CHECK(says(*g, "one facing step above the face of T1"));
  g = guess(p, tools, true);
  REQUIRE(g);
  CHECK(g->box.zmax == doctest::Approx(0.508)); // 0.02 in for an inch program
  // Two facing passes 0.3 mm apart: the step is theirs.
  ProgramBuilder two;
  two.tool(1).feed_rate(1000).rapid(-30, 0, 5).feed(-30, 0, 0.3).feed(90, 0, 0.3);
  two.feed(90, 40, 0.3).feed(-30, 40, 0.3).feed(-30, 40, 0).feed(90, 40, 0).feed(90, 0, 0);
  two.feed(-30, 0, 0).rapid(-30, 0, 5).tool(2).feed_rate(600);
  raster(two, -2);
  g = guess(two, tools);
  REQUIRE(g);
  CHECK(g->box.zmax == doctest::Approx(0.6));
}

TEST_CASE("guessed stock: a program that cuts above Z0 has its top at its highest level") {
  // Z0 on the table: a 20 mm block faced at Z19.5 and cleared down to Z15.
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 10)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(600);
  raster(p, 19.5);
  raster(p, 15);
  const auto g = guess(p, tools);
  REQUIRE(g);
  CHECK(g->box.zmax == doctest::Approx(19.5));
  CHECK(g->box.zmin == doctest::Approx(15));
  CHECK(says(*g, "the program cuts above Z0"));
}

TEST_CASE("guessed stock: an area's passes run to the stock's edge, a contour's edge is inside "
          "it") {
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 6)}};
  // A raster over X0..60 Y0..40: the path's extent is the stock's.
  ProgramBuilder area;
  area.tool(1).feed_rate(600);
  raster(area, -1);
  auto g = guess(area, tools);
  REQUIRE(g);
  CHECK(g->box.xmin == 0);
  CHECK(g->box.xmax == 60);
  CHECK(g->box.ymax == 40);
  // A profile around a 60 x 40 part, cut out of the stock: the tool's far edge is in it.
  ProgramBuilder contour;
  contour.tool(1).feed_rate(600).rapid(-3, -3, 5).feed(-3, -3, -4).feed(63, -3, -4);
  contour.feed(63, 43, -4).feed(-3, 43, -4).feed(-3, -3, -4).rapid(-3, -3, 5);
  g = guess(contour, tools);
  REQUIRE(g);
  CHECK(g->box.xmin == doctest::Approx(-6));
  CHECK(g->box.xmax == doctest::Approx(66));
  CHECK(g->box.ymax == doctest::Approx(46));
}

TEST_CASE("guessed stock: a lead-in from above Z0 does not widen the outline") {
  // A vertical lead-in arc (G18) from X80 Z10 down to X70 Z0, then the pass at Z-1 back to X0.
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 6)}};
  ProgramBuilder p;
  // Centre Z10 X70 (G18: Z, then X), a quarter turn.
  p.tool(1).feed_rate(600).rapid(80, 0, 10).arc_in(Plane::XZ, 70, 0, 0, 10, 70, +1);
  p.feed(70, 0, -1).feed(0, 0, -1).feed(0, 10, -1).feed(70, 10, -1).rapid(70, 10, 10);
  const auto g = guess(p, tools);
  REQUIRE(g);
  CHECK(g->box.zmax == 0);
  CHECK(g->box.xmax <= 70 + 3 + 1e-9);
}

TEST_CASE("guessed stock: a later setup is no larger than the first") {
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 50)}};
  // The second side: a 50 mm face mill faces X-40..100 Y-20..60 at Z-0.5 (passes that run far
  // past a part the first setup left 60 x 40 x 12).
  ProgramBuilder p;
  p.tool(1).feed_rate(1000).rapid(-40, -20, 5).feed(-40, -20, -0.5).feed(100, -20, -0.5);
  p.feed(100, 20, -0.5).feed(-40, 20, -0.5).feed(-40, 60, -0.5).feed(100, 60, -0.5);
  const Box3 first{0, 0, -12, 60, 40, 0};
  const auto alone = guess(p, tools);
  const auto bounded = guess(p, tools, false, &first);
  REQUIRE(alone);
  REQUIRE(bounded);
  CHECK(alone->box.xmax - alone->box.xmin == doctest::Approx(140));
  CHECK(bounded->box.xmax - bounded->box.xmin == doctest::Approx(60));
  CHECK(bounded->box.ymax - bounded->box.ymin == doctest::Approx(40));
  CHECK((bounded->box.xmin + bounded->box.xmax) / 2 == doctest::Approx(30)); // on its cuts
  CHECK(says(*bounded, "no larger than the first setup's stock"));
}

TEST_CASE("guessed stock: a drilling program's holes below Z0 make Z0 the top") {
  // Feed plunges from the R plane Z2 to Z-10: no travel across XY.
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 6)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(100).rapid(10, 10, 2).feed(10, 10, -10).rapid(10, 10, 2);
  p.rapid(30, 10, 2).feed(30, 10, -10).rapid(30, 10, 2);
  const auto g = guess(p, tools);
  REQUIRE(g);
  CHECK(g->box.zmax == 0);
  CHECK(g->box.zmin == -10);
}
