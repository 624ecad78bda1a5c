// Removal in batches (RemovalEngine::remove_steps): the tiles of the grid run in parallel, each
// applying the batch's steps in order; the volumes must be those of removing the steps one by
// one, bit for bit, whatever the number of threads.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include <tbb/global_control.h>

#include "fixture.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

// Many short random moves over the stock at a few depths, with several tools: steps overlap
// each other and cross tile borders.
std::vector<RemovalStep> random_steps(const std::vector<Tool>& tools, std::size_t count) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> xy(0, 60), dz(-2.5, 0.5), step(-3, 3);
  std::vector<RemovalStep> steps;
  Point3 at{30, 30, 1};
  for (std::size_t k = 0; k < count; ++k) {
    Point3 to{std::clamp(at.x() + step(rng), -5.0, 65.0),
              std::clamp(at.y() + step(rng), -5.0, 65.0), dz(rng)};
    if (k % 97 == 0) to = {xy(rng), xy(rng), 1}; // a jump across the stock
    steps.push_back({&tools[k / 500 % tools.size()], at, to});
    at = to;
  }
  return steps;
}

std::vector<double> one_by_one(const StockShape& stock, const GridFrame& grid,
                               const std::vector<RemovalStep>& steps) {
  auto engine = make_removal_engine(EngineKind::Dexel, stock, grid);
  std::vector<double> v;
  for (const RemovalStep& s : steps)
    v.push_back(engine->remove_step(*s.tool, s.from, s.to));
  return v;
}

std::vector<double> batched(const StockShape& stock, const GridFrame& grid,
                            const std::vector<RemovalStep>& steps, std::size_t batch,
                            double* left = nullptr) {
  auto engine = make_removal_engine(EngineKind::Dexel, stock, grid);
  std::vector<double> all, part;
  for (std::size_t k = 0; k < steps.size(); k += batch) {
    const std::vector<RemovalStep> slice(steps.begin() + std::ptrdiff_t(k),
                                         steps.begin() +
                                             std::ptrdiff_t(std::min(k + batch, steps.size())));
    engine->remove_steps(slice, part);
    all.insert(all.end(), part.begin(), part.end());
  }
  if (left) *left = engine->material_volume_mm3();
  return all;
}

} // namespace

TEST_CASE("batched removal equals removal step by step, bit for bit, for any thread count") {
  std::vector<Tool> tools{flat_end_mill(1, 6), ball_end_mill(2, 4), drill(3, 3, 118)};
  const std::vector<RemovalStep> steps = random_steps(tools, 3000);
  const Box3 box{0, 0, -3, 60, 60, 0};
  const auto stock = make_box_stock(box, "test box");
  const GridFrame grid = make_grid(box, 0.15); // 400 x 400 columns, 13 x 13 tiles
  const std::vector<double> reference = one_by_one(*stock, grid, steps);
  double total = 0;
  for (double v : reference)
    total += v;
  CHECK(total > 1000); // the program removes a good deal

  for (int threads : {1, 2, 4}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    for (std::size_t batch : {std::size_t(1), std::size_t(64), std::size_t(5000)}) {
      CAPTURE(threads);
      CAPTURE(batch);
      double left = 0;
      const std::vector<double> v = batched(*stock, grid, steps, batch, &left);
      REQUIRE(v.size() == reference.size());
      bool identical = true;
      for (std::size_t k = 0; k < v.size(); ++k)
        identical = identical && v[k] == reference[k]; // exact, not approximate
      CHECK(identical);
      CHECK(left == doctest::Approx(60 * 60 * 3 - total).epsilon(1e-9));
    }
  }
}

TEST_CASE("a raster in one row of tiles is split among the cores, with the same volumes") {
  // A ball mill's raster along X, 0.2 mm apart in Y, stepping down as it goes: each batch's
  // steps lie in one or two rows of tiles, which remove_steps splits into runs of tiles.
  const Tool ball = ball_end_mill(1, 3);
  std::vector<RemovalStep> steps;
  for (int pass = 0; pass < 12; ++pass) {
    const double y = 10 + 0.2 * pass, z = -0.3 - 0.05 * pass;
    for (int k = 0; k < 200; ++k) {
      const double x0 = pass % 2 ? 58 - 0.28 * k : 2 + 0.28 * k;
      const double x1 = pass % 2 ? x0 - 0.28 : x0 + 0.28;
      steps.push_back({&ball, {x0, y, z + 0.001 * k}, {x1, y, z + 0.001 * (k + 1)}});
    }
  }
  const Box3 box{0, 0, -3, 60, 30, 0};
  const auto stock = make_box_stock(box, "test box");
  // 400 x 200 columns, 13 tiles along a row; each step spans 22 columns, one or two tiles.
  const GridFrame grid = make_grid(box, 0.15);
  const std::vector<double> reference = one_by_one(*stock, grid, steps);
  for (int threads : {1, 2, 4})
    for (std::size_t batch : {std::size_t(200), std::size_t(2400)}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      CAPTURE(threads);
      CAPTURE(batch);
      const std::vector<double> v = batched(*stock, grid, steps, batch);
      REQUIRE(v.size() == reference.size());
      bool identical = true;
      for (std::size_t k = 0; k < v.size(); ++k)
        identical = identical && v[k] == reference[k];
      CHECK(identical);
    }
}

TEST_CASE("a batch of a tool far wider than the grid runs in chunks, with the same volumes") {
  // A 40 mm cutter on a 0.06 mm grid: each step's footprint spans about 21 x 21 tiles, so the
  // 2,000 steps of one batch touch about 880,000 (step, tile) bins, more than one chunk of
  // remove_steps holds. Every 100th step cuts, each a little deeper and further along X, so that
  // cuts on both sides of a chunk's end overlap; the others pass over the stock (their tiles are
  // skipped, which keeps the test fast).
  const Tool wide = flat_end_mill(1, 40);
  std::vector<RemovalStep> steps;
  for (int k = 0; k < 2000; ++k) {
    const double x = 20 + 0.01 * k;
    const double z = k % 100 == 0 ? -0.1 * (1 + k / 100) : 1;
    steps.push_back({&wide, {x, 30, z}, {x + 1, 30.5, z}});
  }
  const Box3 box{0, 0, -3, 60, 60, 0};
  const auto stock = make_box_stock(box, "test box");
  const GridFrame grid = make_grid(box, 0.06); // 1000 x 1000 columns, 32 x 32 tiles
  const std::vector<double> reference = one_by_one(*stock, grid, steps);
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    CAPTURE(threads);
    const std::vector<double> v = batched(*stock, grid, steps, steps.size());
    REQUIRE(v.size() == reference.size());
    std::size_t cutting = 0, identical = 0;
    for (std::size_t k = 0; k < v.size(); ++k) {
      cutting += reference[k] > 0;
      identical += v[k] == reference[k]; // exact, not approximate
    }
    CHECK(cutting == 20); // every cut removes material
    CHECK(identical == v.size());
  }
}

TEST_CASE("pecks and plunges (vertical steps on one axis) give the volumes of step by step") {
  // The batch applies a run of vertical steps on one axis column by column (the tool's offset in
  // each column worked out once): its volumes must still be those of the steps one by one. Pecks
  // of 0.05 mm steps down and back up at a few holes, a drill, a flat mill with a
  // shank wider than its cutter (the shank reaches the stock on the deep holes) and a ball mill,
  // with a sideways move between holes so runs end and start again within tiles.
  Tool shanked = flat_end_mill(2, 3);
  shanked.cutting_length_mm = 1.5;
  shanked.shank_diameter_mm = 6;
  const std::vector<Tool> tools{drill(1, 5, 118), shanked, ball_end_mill(3, 4)};
  std::vector<RemovalStep> steps;
  int hole = 0;
  for (double x : {10.0, 10.8, 25.0, 40.3}) {
    for (double y : {12.0, 30.7}) {
      const Tool& tool = tools[std::size_t(hole++) % tools.size()];
      Point3 at{x, y, 1};
      for (double bottom : {-1.0, -2.2, -3.5}) { // three pecks, each back to Z1
        for (double z = at.z() - 0.05; z > bottom - 1e-9; z -= 0.05) {
          steps.push_back({&tool, at, {x, y, z}});
          at = {x, y, z};
        }
        steps.push_back({&tool, at, {x, y, 1}});
        at = {x, y, 1};
      }
      steps.push_back({&tool, at, {x + 0.7, y + 0.4, -0.5}}); // a sideways cut after the hole
    }
  }
  const Box3 box{0, 0, -3, 60, 60, 0};
  const auto stock = make_box_stock(box, "test box");
  const GridFrame grid = make_grid(box, 0.1); // 600 x 600 columns: holes cross tile borders
  const std::vector<double> reference = one_by_one(*stock, grid, steps);
  double total = 0;
  std::size_t cutting = 0;
  for (double v : reference) {
    total += v;
    cutting += v > 0;
  }
  CHECK(total > 150);   // eight holes of 3-5 mm through most of 3 mm, and the shank's rings
  CHECK(cutting > 300); // most steps down cut
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    for (std::size_t batch : {std::size_t(7), std::size_t(100000)}) {
      CAPTURE(threads);
      CAPTURE(batch);
      double left = 0;
      const std::vector<double> v = batched(*stock, grid, steps, batch, &left);
      REQUIRE(v.size() == reference.size());
      std::size_t identical = 0;
      for (std::size_t k = 0; k < v.size(); ++k)
        identical += v[k] == reference[k]; // exact, not approximate
      CHECK(identical == v.size());
      CHECK(left == doctest::Approx(60 * 60 * 3 - total).epsilon(1e-9));
    }
  }
}

TEST_CASE("rows of a tile with no material above the tool are skipped, with the same volumes") {
  // A slot 8 mm wide cleared along X at Z-1, then a long zigzag of short steps at Z-1 that
  // wanders over the slot and a little past its sides: most of its tiles still hold material
  // beside the slot, but most of their rows under the zigzag are clear, and the batch skips
  // those rows without working out the step's span there. Step by step (remove_step) visits
  // every row: the volumes must be the same bit for bit, and the batch must visit fewer columns.
  const Tool flat = flat_end_mill(1, 6);
  std::vector<RemovalStep> steps;
  for (double y : {27.0, 30.0, 33.0})
    steps.push_back({&flat, {2, y, -1}, {58, y, -1}});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> dx(-1, 1), dy(-0.8, 0.8);
  Point3 at{30, 30, -1};
  for (int k = 0; k < 4000; ++k) {
    const Point3 to{std::clamp(at.x() + dx(rng), 4.0, 56.0),
                    std::clamp(at.y() + dy(rng), 24.0, 36.0), -1};
    steps.push_back({&flat, at, to});
    at = to;
  }
  const Box3 box{0, 0, -3, 60, 60, 0};
  const auto stock = make_box_stock(box, "test box");
  const GridFrame grid = make_grid(box, 0.15); // 400 x 400 columns: tiles 4.8 mm square
  auto step_engine = make_removal_engine(EngineKind::Dexel, *stock, grid);
  std::vector<double> reference;
  for (const RemovalStep& s : steps)
    reference.push_back(step_engine->remove_step(*s.tool, s.from, s.to));
  std::size_t cutting = 0;
  for (double v : reference)
    cutting += v > 0;
  CHECK(cutting > 100);  // the zigzag's steps past the slot's sides cut
  CHECK(cutting < 3000); // most run in the cleared slot
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    CAPTURE(threads);
    auto engine = make_removal_engine(EngineKind::Dexel, *stock, grid);
    std::vector<double> v;
    engine->remove_steps(steps, v);
    REQUIRE(v.size() == reference.size());
    std::size_t identical = 0;
    for (std::size_t k = 0; k < v.size(); ++k)
      identical += v[k] == reference[k]; // exact, not approximate
    CHECK(identical == v.size());
    CHECK(engine->material_volume_mm3() == step_engine->material_volume_mm3());
    CHECK(engine->stats().columns_visited * 2 < step_engine->stats().columns_visited);
  }
}
