// The lowest tool bottom over a straight step (SweptStep::envelope_at) against a brute-force
// walk along the step: the closed forms must find the true minimum, never a point above it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "fixture.hpp"
#include "swept_step.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

// The least tool bottom in the column through (x, y) over `samples` tip positions of the step
// from `a` to `b`, with the tool's own envelope: an upper bound of the true minimum, within the
// profile's slope times the spacing of the samples.
double walked_minimum(const Tool& tool, const Point3& a, const Point3& b, double x, double y,
                      int samples) {
  double lowest = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= samples; ++k) {
    const double t = double(k) / samples;
    const double tx = a.x() + t * (b.x() - a.x()), ty = a.y() + t * (b.y() - a.y());
    const double r = std::sqrt((x - tx) * (x - tx) + (y - ty) * (y - ty));
    if (r > tool.radius()) continue;
    lowest = std::min(lowest, a.z() + t * (b.z() - a.z()) + tool.envelope_height(r));
  }
  return lowest;
}

// Checks SweptStep::envelope_at against the walk on 40 random ramps of `tool`, down and up,
// from nearly level to steeper than any flank, at 25 columns each around the step. Counts the
// columns checked, and those whose minimum lies inside the step, not at an end (what a closed
// form or a search has to find).
struct WalkCount {
  int columns = 0, interior = 0;
};
WalkCount check_ramps_against_walk(const Tool& tool, std::mt19937& random) {
  std::uniform_real_distribution<double> unit(0, 1);
  WalkCount count;
  const double d = tool.diameter_mm;
  for (int step = 0; step < 40; ++step) {
    const double length = 0.2 + 9.8 * unit(random), heading = 6.283 * unit(random);
    const double rise = (unit(random) - 0.5) * length * (step % 4 == 0 ? 4.0 : 0.6);
    const Point3 a(1, 2, -1),
        b(1 + length * std::cos(heading), 2 + length * std::sin(heading), -1 + rise);
    const detail::SweptStep swept(tool, a, b);
    for (int c = 0; c < 25; ++c) {
      const double t = -0.5 + 2 * unit(random), off = (unit(random) - 0.5) * 1.1 * d;
      const double x = a.x() + t * (b.x() - a.x()) - off * std::sin(heading);
      const double y = a.y() + t * (b.y() - a.y()) + off * std::cos(heading);
      const double exact = swept.envelope_at(x, y);
      const double walked = walked_minimum(tool, a, b, x, y, 20000);
      if (!std::isfinite(walked)) continue;
      CAPTURE(step);
      CAPTURE(x);
      CAPTURE(y);
      REQUIRE(std::isfinite(exact));
      CHECK(exact <= walked + 1e-12);
      CHECK(walked - exact < 5e-3);
      ++count.columns;
      const double ends =
          std::min(walked_minimum(tool, a, a, x, y, 1), walked_minimum(tool, b, b, x, y, 1));
      if (exact < ends - 1e-6) ++count.interior;
    }
  }
  return count;
}

// Every tool's ramps against the walk: the columns checked, and those whose minimum lies inside a
// step rather than at its ends, summed over the tools.
WalkCount check_tools_against_walk(const std::vector<Tool>& tools, unsigned seed) {
  std::mt19937 random(seed);
  WalkCount total;
  for (const Tool& tool : tools) {
    CAPTURE(tool.diameter_mm);
    CAPTURE(tool.tip_angle_deg);
    CAPTURE(tool.tip_diameter_mm);
    CAPTURE(tool.corner_radius_mm);
    const WalkCount count = check_ramps_against_walk(tool, random);
    total.columns += count.columns, total.interior += count.interior;
  }
  return total;
}

} // namespace

TEST_CASE("a V-bit's lowest bottom along ramps is the true minimum, tip flat or pointed") {
  std::vector<Tool> vbits;
  for (const double tip : {0.0, 0.8})
    for (const double angle : {30.0, 60.0, 90.0, 120.0}) {
      Tool vbit = flat_end_mill(1, 6);
      vbit.shape = ToolShape::Chamfer;
      vbit.tip_angle_deg = angle;
      vbit.tip_diameter_mm = tip;
      vbits.push_back(vbit);
    }
  const WalkCount total = check_tools_against_walk(vbits, 43);
  CHECK(total.columns > 2000);
  CHECK(total.interior > 200);
}

TEST_CASE("a bull nose's lowest bottom along ramps is the true minimum") {
  std::vector<Tool> bulls;
  for (const double corner : {0.25, 1.0, 2.9, 3.0})
    for (const double diameter : {6.0, 10.0}) {
      Tool bull = flat_end_mill(1, diameter);
      bull.shape = ToolShape::BullNose;
      bull.corner_radius_mm = corner;
      bulls.push_back(bull);
    }
  const WalkCount total = check_tools_against_walk(bulls, 44);
  CHECK(total.columns > 2000);
  CHECK(total.interior > 200);
}
