// The voxel engine's Z layers: even layers, except that the Z levels a program cuts flat floors
// at are layer boundaries. A voxel is removed when its centre is inside the tool, so a floor
// through the middle of a layer leaves or removes half a layer over the whole floor; on a
// boundary it is exact, and the voxel and dexel engines then differ only where surfaces are
// curved or sloped.
#include <algorithm>
#include <cmath>

#include "ncjoule/removal.hpp"

namespace ncjoule {
namespace {

// Levels closer than this to a boundary already there are the same level.
constexpr double kSameLevelMm = 1e-6;

} // namespace

std::vector<double> voxel_layer_bounds(const GridFrame& grid) {
  const double target = std::min(grid.dx, grid.dy);
  const double height = grid.z1 - grid.z0;
  const int uniform = std::max(1, int(std::ceil(height / target - 1e-9)));

  std::vector<double> fixed{grid.z0, grid.z1};
  for (double z : grid.z_levels)
    if (z > grid.z0 + kSameLevelMm && z < grid.z1 - kSameLevelMm) fixed.push_back(z);
  std::sort(fixed.begin(), fixed.end());
  fixed.erase(std::unique(fixed.begin(), fixed.end(),
                          [](double a, double b) { return b - a < kSameLevelMm; }),
              fixed.end());
  // A program with very many levels (3-D surfacing) would multiply the layers: keep even
  // layers then.
  if (fixed.size() > std::size_t(uniform) + 2) fixed = {grid.z0, grid.z1};

  std::vector<double> bounds{fixed.front()};
  for (std::size_t k = 0; k + 1 < fixed.size(); ++k) {
    const double gap = fixed[k + 1] - fixed[k];
    const int n = std::max(1, int(std::ceil(gap / target - 1e-9)));
    for (int m = 1; m < n; ++m)
      bounds.push_back(fixed[k] + gap * m / n);
    bounds.push_back(fixed[k + 1]);
  }
  return bounds;
}

} // namespace ncjoule
