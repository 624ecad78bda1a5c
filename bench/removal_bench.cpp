// Removal engines side by side: the same program (a pocket cleared in zigzag passes at two
// depths, with a helical entry) on the same stock and grid, played by the dexel and the voxel
// engine. Prints steps per second, columns per second (dexel: columns under the step's
// footprint; voxel: columns of the step's bounding box), the speed ratio and the volumes (which
// must agree). The voxel engine is the thesis-style reference (every voxel of each step's
// bounding box tested), hence the coarse default grid.
//
// Usage: bench_removal [grid_mm=0.25] [stock_height_mm=20]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <vector>

#include "ncjoule/removal.hpp"

using namespace ncjoule;

namespace {

// Tip positions of the pocket program, no further apart than `step` mm.
std::vector<Point3> pocket_path(double step) {
  std::vector<Point3> corners;
  const double x0 = 16, x1 = 64, y0 = 16, y1 = 44, stepover = 6;
  for (double z : {-3.0, -6.0}) {
    // Helical entry: two turns of radius 4 down to z.
    const int turns_samples = 720;
    for (int k = 0; k <= turns_samples; ++k) {
      const double a = 4 * std::numbers::pi * k / turns_samples;
      corners.push_back(
          {40 + 4 * std::cos(a), 30 + 4 * std::sin(a), z + 3 - 3.0 * k / turns_samples});
    }
    bool forward = true;
    for (double y = y0; y <= y1 + 1e-9; y += stepover) {
      corners.push_back({forward ? x0 : x1, y, z});
      corners.push_back({forward ? x1 : x0, y, z});
      forward = !forward;
    }
    corners.push_back({corners.back().x(), corners.back().y(), 5}); // retract
  }
  std::vector<Point3> path{{40 + 4, 30, 5}};
  for (const Point3& c : corners) {
    const Point3 a = path.back();
    const int n = std::max(1, int(std::ceil((c - a).norm() / step)));
    for (int k = 1; k <= n; ++k)
      path.push_back(a + (double(k) / n) * (c - a));
  }
  return path;
}

struct Run {
  double seconds = 0, cpu_seconds = 0, volume = 0;
  EngineStats stats;
  std::size_t memory = 0;
};

Run play(EngineKind kind, const StockShape& stock, const GridFrame& grid, const Tool& tool,
         const std::vector<Point3>& path) {
  auto engine = make_removal_engine(kind, stock, grid);
  Run r;
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  for (std::size_t k = 0; k + 1 < path.size(); ++k)
    r.volume += engine->remove_step(tool, path[k], path[k + 1]);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.cpu_seconds = double(std::clock() - c0) / CLOCKS_PER_SEC; // all threads
  r.stats = engine->stats();
  r.memory = engine->memory_bytes();
  return r;
}

} // namespace

int main(int argc, char** argv) {
  const double grid_mm = argc > 1 ? std::atof(argv[1]) : 0.25;
  const double height = argc > 2 ? std::atof(argv[2]) : 20;
  Tool tool;
  tool.number = 1;
  tool.diameter_mm = 12;
  const Box3 box{0, 0, -height, 80, 60, 0};
  const auto stock = make_box_stock(box, "bench box");
  GridFrame grid = make_grid(box, grid_mm);
  grid.z_levels = {-3, -6}; // the pocket's floors, as simulate_removal would give them
  std::map<int, Tool> tools{{1, tool}};
  const std::vector<Point3> path = pocket_path(recommended_sample_step(tools, grid_mm));
  std::printf("program: 12 mm flat end mill, pocket 48 x 28 mm, two 3 mm levels, %zu steps\n",
              path.size() - 1);
  std::printf("stock: 80 x 60 x %.0f mm, grid %.3f mm (%d x %d columns, %zu voxel layers)\n",
              height, grid.dx, grid.nx, grid.ny, voxel_layer_bounds(grid).size() - 1);

  const Run dexel = play(EngineKind::Dexel, *stock, grid, tool, path);
  const Run voxel = play(EngineKind::Voxel, *stock, grid, tool, path);
  for (const auto& [name, r] : {std::pair{"dexel", dexel}, std::pair{"voxel", voxel}}) {
    std::printf("%-6s %8.3f s (cpu %8.3f s)  %10.0f steps/s  %12.0f columns/s  %12.0f cells "
                "tested/s  removed %.2f mm^3  memory %.1f MB\n",
                name, r.seconds, r.cpu_seconds, r.stats.steps / r.seconds,
                r.stats.columns_visited / r.seconds, r.stats.cells_tested / r.seconds, r.volume,
                r.memory / 1e6);
  }
  std::printf("dexel / voxel speed ratio: %.1f wall, %.1f cpu (target >= 50)\n",
              voxel.seconds / dexel.seconds, voxel.cpu_seconds / dexel.cpu_seconds);
  std::printf("volume difference voxel vs dexel: %.4f %%\n",
              100 * std::abs(voxel.volume - dexel.volume) / dexel.volume);
  return 0;
}
