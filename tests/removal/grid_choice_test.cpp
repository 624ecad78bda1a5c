// The automatic grid (accuracy_grid_spacing, automatic_grid_spacing): chosen from the tools and
// what they cut, to a stated volume error, and never from the memory there is.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "fixture.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

constexpr double kPi = std::numbers::pi;

StockExtent extent_of(const ProgramBuilder& p) {
  StockExtent extent;
  for (const CanonCommand& c : p.commands())
    extent.add(c);
  return extent;
}

RemovalResult run(const ProgramBuilder& p, const std::map<int, Tool>& tools, const Box3& stock,
                  std::size_t memory_budget = 0) {
  RemovalOptions o;
  o.memory_budget_bytes = memory_budget;
  const StockExtent extent = extent_of(p);
  const double grid = automatic_grid_spacing(extent, tools, o.work_columns);
  StockSpec spec;
  spec.kind = StockSpec::Kind::Box;
  spec.box = stock;
  return simulate_removal(
      p.commands(), constant_speed_timeline(p.commands(), recommended_sample_step(tools, grid)),
      tools, spec, o);
}

} // namespace

TEST_CASE("one tool: a 100th of its diameter, the spacing of a 0.1% edge error") {
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 6)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(600).rapid(0, 0, 5).feed(0, 0, -2).feed(80, 0, -2).rapid(80, 0, 5);
  CHECK(accuracy_grid_spacing(extent_of(p), tools) == doctest::Approx(6.0 / 100));
  // A short program is not coarsened for work.
  CHECK(automatic_grid_spacing(extent_of(p), tools) == doctest::Approx(6.0 / 100));
}

TEST_CASE(
    "a face mill doing most of the cutting makes the grid coarser, the small tool bounds it") {
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 20)}, {2, flat_end_mill(2, 6)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(1000).rapid(0, 0, 5).feed(0, 0, -1);
  for (int pass = 0; pass < 10; ++pass)
    p.feed(pass % 2 ? 0 : 300, 16.0 * pass, -1).feed(pass % 2 ? 0 : 300, 16.0 * (pass + 1), -1);
  p.rapid(0, 0, 5).tool(2).rapid(10, 10, 5).feed(10, 10, -3).feed(30, 10, -3).rapid(30, 10, 5);
  const StockExtent extent = extent_of(p);
  const double grid = accuracy_grid_spacing(extent, tools);
  // Weighted by swept area, the face mill's edges decide: coarser than d/100 of the end mill...
  CHECK(grid > 6.0 / 100);
  // ...but the end mill's slot still spans eight columns.
  CHECK(grid <= 6.0 / 8 + 1e-12);
  // Weights by hand: L1 * 20 and L2 * 6; error per spacing 0.1 * (L1 + L2) / (L1*20 + L2*6).
  const double l1 = extent.cutting_length(1), l2 = extent.cutting_length(2);
  const double want = 0.001 / 0.1 * (l1 * 20 + l2 * 6) / (l1 + l2);
  REQUIRE(want < 6.0 / 8);
  CHECK(grid == doctest::Approx(want));
  // A 50 mm face mill and a 3 mm end mill on the same paths would ask for more than an eighth
  // of the end mill.
  const std::map<int, Tool> face{{1, flat_end_mill(1, 50)}, {2, flat_end_mill(2, 3)}};
  REQUIRE(0.001 / 0.1 * (l1 * 50 + l2 * 3) / (l1 + l2) > 3.0 / 8);
  CHECK(accuracy_grid_spacing(extent, face) == doctest::Approx(3.0 / 8));
}

TEST_CASE("a face mill's pass through the air over the stock does not make the grid coarser") {
  // A 100 mm face mill crosses the part at Z0, then a 12 mm end mill cuts a slot 5 mm deep (as a
  // posted program that faces a stock already flat at its top, Z0).
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 100)}, {2, flat_end_mill(2, 12)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(400).rapid(-60, 40, 5).feed(-60, 40, 0).feed(160, 40, 0).rapid(160, 40, 5);
  p.tool(2).rapid(0, 0, 5).feed(0, 0, -5).feed(100, 0, -5).rapid(100, 0, 5);
  const StockExtent extent = extent_of(p);
  REQUIRE(extent.cutting_length(1) == doctest::Approx(225)); // 220 across and the 5 mm plunge
  // Over a stock whose top is Z0 the face mill's pass cuts nothing: its plunge alone is weighed.
  CHECK(extent.cutting_length(1, 0) == doctest::Approx(5));
  CHECK(extent.cutting_length(2, 0) == doctest::Approx(extent.cutting_length(2)));
  const double l2 = extent.cutting_length(2);
  CHECK(accuracy_grid_spacing(extent, tools, 0) ==
        doctest::Approx(0.001 / 0.1 * (5 * 100 + l2 * 12) / (5 + l2)));
  // With its top half a millimetre higher the pass cuts a layer, and its 220 mm count.
  CHECK(extent.cutting_length(1, 0.5) == doctest::Approx(225));
  CHECK(accuracy_grid_spacing(extent, tools, 0.5) ==
        doctest::Approx(0.001 / 0.1 * (225 * 100 + l2 * 12) / (225 + l2)));
  CHECK(accuracy_grid_spacing(extent, tools, 0.5) > 1.5 * accuracy_grid_spacing(extent, tools, 0));
  // Without a top every cutting move counts, as before the stock is known.
  CHECK(accuracy_grid_spacing(extent, tools) == accuracy_grid_spacing(extent, tools, 0.5));
}

TEST_CASE("the grid does not follow the memory budget, and the removed volume stays within 0.2%") {
  const double R = 3, depth = 4, L = 50;
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 2 * R)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(300).rapid(0, 0, 5).feed(0, 0, -depth).feed(L, 0, -depth).rapid(L, 0, 5);
  // 150 mm square: 9M columns at d/120, so the accuracy grid (d/100, 6.25M columns: capped at 4M)
  // is used, the same under either budget.
  const Box3 stock{-50, -75, -10, 100, 75, 0};
  const RemovalResult small = run(p, tools, stock, std::size_t(256) << 20);
  const RemovalResult large = run(p, tools, stock, std::size_t(64) << 30);
  CHECK(small.grid.dx >= 2 * R / 100 - 1e-9);
  CHECK(small.grid.dx <= 2 * R / 60);
  CHECK(large.grid.dx == small.grid.dx);
  CHECK(large.memory_bytes == small.memory_bytes);
  const double want = kPi * R * R * depth + 2 * R * L * depth;
  CHECK(std::abs(small.removed_mm3 - want) / want < 2e-3);
}

TEST_CASE("a small job keeps the finest grid: a thin pass's MRR is exact") {
  // A finishing pass 0.5 mm wide along a 6 mm tool's side: at d/100 (0.06 mm) a column's width
  // is an eighth of the pass; the stock is small, so the grid is d/120.
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 6)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(600).rapid(-5, 0, 5).rapid(-5, 0, -2).feed(85, 0, -2).rapid(85, 0, 5);
  const Box3 stock{0, 2.5, -2, 80, 10, 0};
  const RemovalResult r = run(p, tools, stock);
  CHECK(r.grid.dx <= 6.0 / 120 + 1e-9);
  CHECK(r.removed_mm3 == doctest::Approx(80 * 0.5 * 2).epsilon(1e-3));
  StockExtent extent = extent_of(p);
  CHECK(automatic_grid_spacing(extent, tools, 1.5e8, 80 * 7.5) == doctest::Approx(6.0 / 120));
  CHECK(automatic_grid_spacing(extent, tools, 1.5e8, 1000 * 1000) == doctest::Approx(6.0 / 100));
}

TEST_CASE("a stock too large for the column cap is coarsened, with a note") {
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 3)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(600).rapid(0, 0, 5).feed(0, 0, -1).feed(10, 0, -1).rapid(10, 0, 5);
  const Box3 stock{-500, -500, -10, 500, 500, 0}; // a metre square: 0.05 mm is 400M columns
  const RemovalResult r = run(p, tools, stock);
  CHECK(double(r.grid.nx) * double(r.grid.ny) <= 4e6);
  bool noted = false;
  for (const Diagnostic& d : r.diagnostics)
    noted |= d.severity == Severity::Note && d.message.find("coarsened") != std::string::npos;
  CHECK(noted);
}
