// The voxel engine, the reference in the manner of the Anziani thesis: the stock is a 3-D grid
// of voxels, one byte each (material or not), and for every step of the toolpath every voxel in
// the bounding box of the tool's swept volume has its centre tested; a voxel whose centre lies
// inside the tool is removed. Nothing is skipped for being air already or far from the tool's
// outline: the method is meant to be obviously right, not fast.
//
// "Inside the tool" is inside the tool swept along the whole step (SweptStep::contains), so thin
// steps are not missed, and it is worked out from the tool's cross-section at the voxel's
// height. That shares nothing with the dexel engine's per-column envelope, which makes the two
// engines a check on each other. The tool's side reaches above the stock (its holder is not
// modelled), so a step's box runs from its lowest tip to the top of the stock.
#include <algorithm>
#include <cmath>
#include <functional>
#include <mutex>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "engines.hpp"
#include "swept_step.hpp"
#include "tile_sum.hpp"

namespace ncjoule::detail {
namespace {

struct Count {
  std::uint64_t removed = 0, tested = 0;
};

class VoxelEngine final : public RemovalEngine {
public:
  VoxelEngine(const StockShape& stock, const GridFrame& grid) : grid_(grid) {
    const std::vector<double> bounds = voxel_layer_bounds(grid_);
    nz_ = int(bounds.size()) - 1;
    centre_.resize(std::size_t(nz_));
    height_.resize(std::size_t(nz_));
    for (int k = 0; k < nz_; ++k) {
      centre_[k] = (bounds[k] + bounds[k + 1]) / 2;
      height_[k] = bounds[k + 1] - bounds[k];
    }
    voxels_.assign(grid_.columns() * std::size_t(nz_), 0);

    std::vector<std::uint32_t> first;
    std::vector<ZInterval> intervals;
    stock.fill_columns(grid_, first, intervals);
    for (std::size_t c = 0; c < grid_.columns(); ++c)
      for (std::uint32_t k = first[c]; k < first[c + 1]; ++k) {
        // Voxels whose centre lies in [lo, hi) are material.
        const auto a = std::lower_bound(centre_.begin(), centre_.end(), intervals[k].lo);
        const auto b = std::lower_bound(centre_.begin(), centre_.end(), intervals[k].hi);
        for (auto v = a; v < b; ++v)
          voxels_[c * std::size_t(nz_) + std::size_t(v - centre_.begin())] = 1;
      }
  }

  EngineKind kind() const override { return EngineKind::Voxel; }
  const GridFrame& grid() const override { return grid_; }
  const EngineStats& stats() const override { return stats_; }
  std::size_t memory_bytes() const override {
    return voxels_.capacity() + (centre_.capacity() + height_.capacity()) * sizeof(double);
  }

  bool material_at(const Point3& p) const override {
    const int i = detail::clamped_index(std::floor((p.x() - grid_.x0) / grid_.dx));
    const int j = detail::clamped_index(std::floor((p.y() - grid_.y0) / grid_.dy));
    if (i < 0 || j < 0 || i >= grid_.nx || j >= grid_.ny) return false;
    const std::size_t c = std::size_t(j) * std::size_t(grid_.nx) + std::size_t(i);
    double z = grid_.z0;
    for (int k = 0; k < nz_; ++k) {
      if (p.z() >= z && p.z() < z + height_[k])
        return voxels_[c * std::size_t(nz_) + std::size_t(k)];
      z += height_[k];
    }
    return false;
  }

  double material_volume_mm3() const override {
    double layers = 0; // sum of the heights of the material voxels
    for (std::size_t c = 0; c < grid_.columns(); ++c)
      for (int k = 0; k < nz_; ++k)
        if (voxels_[c * std::size_t(nz_) + std::size_t(k)]) layers += height_[k];
    return layers * grid_.dx * grid_.dy;
  }

  double remove_step(const Tool& tool, const Point3& from, const Point3& to) override {
    const SweptStep step(tool, from, to);
    // The bounding box of the swept tool, as voxel index ranges (voxels whose centre is in it).
    const int i0 = std::max(0, int(std::ceil((step.footprint_xmin() - grid_.x0) / grid_.dx - 0.5)));
    const int i1 = std::min(grid_.nx - 1,
                            int(std::floor((step.footprint_xmax() - grid_.x0) / grid_.dx - 0.5)));
    const int j0 = std::max(0, int(std::ceil((step.footprint_ymin() - grid_.y0) / grid_.dy - 0.5)));
    const int j1 = std::min(grid_.ny - 1,
                            int(std::floor((step.footprint_ymax() - grid_.y0) / grid_.dy - 0.5)));
    const int k0 = int(std::lower_bound(centre_.begin(), centre_.end(), step.lowest_tip_z()) -
                       centre_.begin());
    ++stats_.steps;
    if (i0 > i1 || j0 > j1 || k0 >= nz_) return 0;
    stats_.columns_visited += std::uint64_t(i1 - i0 + 1) * std::uint64_t(j1 - j0 + 1);

    // Rows in parallel. Each row's counts are integers, so the sum (and the volume, added up
    // per layer below) is the same whatever the split. Removed voxels are counted per layer
    // because layers may differ in height.
    std::vector<std::uint64_t> removed_per_layer(std::size_t(nz_), 0);
    const std::uint64_t tested = tbb::parallel_reduce(
        tbb::blocked_range<int>(j0, j1 + 1), std::uint64_t(0),
        [&](const tbb::blocked_range<int>& rows, std::uint64_t tested) {
          std::vector<std::uint64_t> removed(std::size_t(nz_), 0);
          for (int j = rows.begin(); j != rows.end(); ++j) {
            const double y = grid_.column_y(j);
            for (int i = i0; i <= i1; ++i) {
              const double x = grid_.column_x(i);
              std::uint8_t* column =
                  voxels_.data() + (std::size_t(j) * grid_.nx + std::size_t(i)) * nz_;
              for (int k = k0; k < nz_; ++k) {
                ++tested;
                if (step.contains(x, y, centre_[k]) && column[k]) {
                  column[k] = 0;
                  ++removed[k];
                }
              }
            }
          }
          std::lock_guard lock(merge_mutex_);
          for (int k = k0; k < nz_; ++k)
            removed_per_layer[k] += removed[k];
          return tested;
        },
        std::plus<>());
    stats_.cells_tested += tested;
    double layers = 0;
    for (int k = k0; k < nz_; ++k)
      layers += double(removed_per_layer[k]) * height_[k];
    return layers * grid_.dx * grid_.dy;
  }

private:
  GridFrame grid_;
  int nz_ = 1;
  std::vector<double> centre_;       // Z of each layer's voxel centres, ascending
  std::vector<double> height_;       // each layer's thickness
  std::vector<std::uint8_t> voxels_; // 1 = material; column c holds layers [c * nz_, (c+1) * nz_)
  std::mutex merge_mutex_;
  EngineStats stats_;
};

} // namespace

std::unique_ptr<RemovalEngine> make_voxel_engine(const StockShape& stock, const GridFrame& grid) {
  return std::make_unique<VoxelEngine>(stock, grid);
}

} // namespace ncjoule::detail
