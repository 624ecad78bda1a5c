// The voxel engine, the reference in the manner of the Anziani thesis: the stock is a 3-D grid
// of voxels, and a voxel is removed when its centre lies inside the tool. Here "the tool" is the
// tool swept along the whole step, so thin steps are not missed, but each voxel is still tested
// on its own, from the tool's cross-section at the voxel's height. That test shares nothing with
// the dexel engine's per-column envelope, which makes the two engines a check on each other.
//
// Voxels are bits, 64 to a word along Z; empty words are skipped without testing.
#include <algorithm>
#include <bit>
#include <cmath>

#include "engines.hpp"
#include "swept_step.hpp"
#include "tile_sum.hpp"

namespace ncjoule::detail {
namespace {

// A voxel column costs far more than a dexel column: hand tiles to other threads early.
constexpr std::size_t kParallelMinColumns = 2'000;

class VoxelEngine final : public RemovalEngine {
public:
  VoxelEngine(const StockShape& stock, const GridFrame& grid) : grid_(grid) {
    const double height = grid_.z1 - grid_.z0;
    const double target = std::min(grid_.dx, grid_.dy);
    nz_ = std::max(1, int(std::ceil(height / target - 1e-9)));
    dz_ = height / nz_;
    words_ = (std::size_t(nz_) + 63) / 64;
    bits_.assign(grid_.columns() * words_, 0);

    std::vector<std::uint32_t> first;
    std::vector<ZInterval> intervals;
    stock.fill_columns(grid_, first, intervals);
    for (std::size_t c = 0; c < grid_.columns(); ++c) {
      for (std::uint32_t k = first[c]; k < first[c + 1]; ++k) {
        // Voxels whose centre lies in [lo, hi).
        const int a = std::max(0, int(std::ceil((intervals[k].lo - grid_.z0) / dz_ - 0.5)));
        const int b = std::min(nz_, int(std::ceil((intervals[k].hi - grid_.z0) / dz_ - 0.5)));
        for (int v = a; v < b; ++v)
          bits_[c * words_ + v / 64] |= std::uint64_t(1) << (v % 64);
      }
    }
  }

  EngineKind kind() const override { return EngineKind::Voxel; }
  const GridFrame& grid() const override { return grid_; }
  const EngineStats& stats() const override { return stats_; }
  std::size_t memory_bytes() const override { return bits_.capacity() * sizeof(std::uint64_t); }

  double material_volume_mm3() const override {
    std::uint64_t n = 0;
    for (std::uint64_t w : bits_)
      n += std::uint64_t(std::popcount(w));
    return double(n) * voxel_volume();
  }

  double remove_step(const Tool& tool, const Point3& from, const Point3& to) override {
    const SweptStep step(tool, from, to);
    // Voxels whose centre is below the lowest tip cannot be inside the tool.
    const int k0 = std::max(0, int(std::ceil((step.lowest_tip_z() - grid_.z0) / dz_ - 0.5)));
    const TileResult r = for_each_footprint_column(
        grid_, step, kParallelMinColumns,
        [&](std::size_t c, int, int, double x, double y, TileResult& acc) {
          std::uint64_t* column = bits_.data() + c * words_;
          std::uint64_t removed = 0;
          for (std::size_t w = std::size_t(k0) / 64; w < words_; ++w) {
            std::uint64_t word = column[w];
            if (w == std::size_t(k0) / 64) word &= ~std::uint64_t(0) << (k0 % 64);
            while (word) {
              const int bit = std::countr_zero(word);
              word &= word - 1;
              const int v = int(w * 64) + bit;
              ++acc.cells_tested;
              if (step.contains(x, y, grid_.z0 + (v + 0.5) * dz_)) {
                column[w] &= ~(std::uint64_t(1) << bit);
                ++removed;
              }
            }
          }
          acc.volume_mm3 += double(removed);
        });
    ++stats_.steps;
    stats_.columns_visited += r.columns_visited;
    stats_.cells_tested += r.cells_tested;
    return r.volume_mm3 * voxel_volume();
  }

private:
  double voxel_volume() const { return grid_.dx * grid_.dy * dz_; }

  GridFrame grid_;
  int nz_ = 1;
  double dz_ = 1;
  std::size_t words_ = 1;
  std::vector<std::uint64_t> bits_; // column-major: words_ words per column, bit v = layer v
  EngineStats stats_;
};

} // namespace

std::unique_ptr<RemovalEngine> make_voxel_engine(const StockShape& stock, const GridFrame& grid) {
  return std::make_unique<VoxelEngine>(stock, grid);
}

} // namespace ncjoule::detail
