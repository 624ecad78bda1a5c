// The voxel reference engine: thesis-style testing of every voxel in a step's bounding box, and
// layers whose boundaries sit on the program's flat floors.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "fixture.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("voxel layers: even layers with boundaries on the given Z levels") {
  GridFrame g = make_grid({0, 0, -10, 10, 10, 0}, 0.3);
  const std::vector<double> even = voxel_layer_bounds(g);
  REQUIRE(even.size() >= 2);
  CHECK(even.front() == -10);
  CHECK(even.back() == 0);
  for (std::size_t k = 0; k + 1 < even.size(); ++k)
    CHECK(even[k + 1] - even[k] <= 0.3 + 1e-12);

  g.z_levels = {-1.05, -3.333, -20, 5, 0}; // outside and on the stock's faces are left out
  const std::vector<double> aligned = voxel_layer_bounds(g);
  for (double level : {-1.05, -3.333}) {
    bool found = false;
    for (double b : aligned)
      found = found || std::abs(b - level) < 1e-12;
    CHECK_MESSAGE(found, "level ", level, " is a boundary");
  }
  for (std::size_t k = 0; k + 1 < aligned.size(); ++k) {
    CHECK(aligned[k + 1] > aligned[k]);
    CHECK(aligned[k + 1] - aligned[k] <= 0.3 + 1e-12);
  }
  // A level per layer or more (3-D surfacing) would multiply the layers: even layers then.
  for (int k = 0; k < 200; ++k)
    g.z_levels.push_back(-0.01 - 0.049 * k);
  CHECK(voxel_layer_bounds(g).size() == even.size());
}

TEST_CASE("voxel engine tests every voxel in the step's bounding box") {
  const Box3 box{0, 0, -5, 40, 20, 0};
  const auto stock = make_box_stock(box, "box");
  const GridFrame grid = make_grid(box, 0.5); // 80 x 40 columns, 10 layers
  auto engine = make_removal_engine(EngineKind::Voxel, *stock, grid);
  CHECK(engine->material_volume_mm3() == doctest::Approx(40 * 20 * 5));
  const Tool tool = flat_end_mill(1, 6);
  // From x = 10 to 20 at y = 10, tip at z = -2: the box is x 7..23, y 7..13 (32 x 12 column
  // centres) and z -2..0 (the 4 layers whose centres are above the tip).
  const double v = engine->remove_step(tool, {10, 10, -2}, {20, 10, -2});
  CHECK(engine->stats().columns_visited == 32 * 12);
  CHECK(engine->stats().cells_tested == 32 * 12 * 4);
  // Removed: a 10 x 6 band with half discs at both ends, 2 deep; at 0.5 mm the discs are
  // rough, so within a few percent.
  const double exact = (10 * 6 + std::numbers::pi * 9) * 2;
  CHECK(v == doctest::Approx(exact).epsilon(0.05));
  // Already cut: the same step tests the same voxels again and removes nothing.
  CHECK(engine->remove_step(tool, {10, 10, -2}, {20, 10, -2}) == 0);
  CHECK(engine->stats().cells_tested == 2 * 32 * 12 * 4);
  // Above the stock: an empty box, nothing tested.
  CHECK(engine->remove_step(tool, {0, 0, 1}, {40, 20, 1}) == 0);
  CHECK(engine->stats().cells_tested == 2 * 32 * 12 * 4);
}

TEST_CASE("voxel floors are exact when their levels are layer boundaries") {
  // A slot 1.3 mm deep in layers of 0.5 mm: without the level the floor falls in the middle of
  // a layer; with it, the voxel engine matches the dexel engine.
  const Box3 box{0, 0, -5, 40, 20, 0};
  const auto stock = make_box_stock(box, "box");
  GridFrame grid = make_grid(box, 0.5);
  const Tool tool = flat_end_mill(1, 6);
  auto dexel = make_removal_engine(EngineKind::Dexel, *stock, grid);
  const double d = dexel->remove_step(tool, {10, 10, -1.3}, {30, 10, -1.3});
  auto coarse = make_removal_engine(EngineKind::Voxel, *stock, grid);
  const double v_even = coarse->remove_step(tool, {10, 10, -1.3}, {30, 10, -1.3});
  grid.z_levels = {-1.3};
  auto aligned = make_removal_engine(EngineKind::Voxel, *stock, grid);
  const double v_aligned = aligned->remove_step(tool, {10, 10, -1.3}, {30, 10, -1.3});
  report("slot 1.3 deep: voxel even layers vs dexel", std::abs(v_even - d) / d);
  report("slot 1.3 deep: voxel aligned layers vs dexel", std::abs(v_aligned - d) / d);
  CHECK(std::abs(v_even - d) / d > 0.05);    // 1.5 of 1.3 mm: the even layers are off
  CHECK(std::abs(v_aligned - d) / d < 1e-9); // same columns, same depth
}
