// The column grid shared by the engines, and the engine factory.
#include <algorithm>
#include <cmath>
#include <limits>

#include "engines.hpp"
#include "ncjoule/removal.hpp"

namespace ncjoule {

GridFrame make_grid(const Box3& bounds, double spacing_mm) {
  GridFrame g;
  g.x0 = bounds.xmin, g.y0 = bounds.ymin;
  g.z0 = bounds.zmin, g.z1 = bounds.zmax;
  const double w = bounds.xmax - bounds.xmin, h = bounds.ymax - bounds.ymin;
  // Cells tile the bounds exactly, so a box stock's volume and its edges are exact; the small
  // tolerance keeps 155 / 0.1 at 1550 cells despite rounding.
  g.nx = std::max(1, int(std::ceil(w / spacing_mm - 1e-9)));
  g.ny = std::max(1, int(std::ceil(h / spacing_mm - 1e-9)));
  g.dx = w > 0 ? w / g.nx : spacing_mm;
  g.dy = h > 0 ? h / g.ny : spacing_mm;
  return g;
}

void RemovalEngine::remove_steps(const std::vector<RemovalStep>& steps,
                                 std::vector<double>& volumes, std::vector<double>* cut_tops) {
  volumes.resize(steps.size());
  if (cut_tops) cut_tops->assign(steps.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < steps.size(); ++k)
    volumes[k] = remove_step(*steps[k].tool, steps[k].from, steps[k].to);
}

std::string_view engine_name(EngineKind kind) {
  return kind == EngineKind::Voxel ? "voxel" : "dexel";
}

std::unique_ptr<RemovalEngine> make_removal_engine(EngineKind kind, const StockShape& stock,
                                                   const GridFrame& grid) {
  if (kind == EngineKind::Voxel) return detail::make_voxel_engine(stock, grid);
  return detail::make_dexel_engine(stock, grid);
}

double default_grid_spacing(const std::map<int, Tool>& tools) {
  double smallest = 0;
  for (const auto& [number, tool] : tools)
    if (tool.diameter_mm > 0 && (smallest == 0 || tool.diameter_mm < smallest))
      smallest = tool.diameter_mm;
  if (smallest == 0) return 0.1;
  return std::clamp(smallest / 120.0, 0.01, 1.0);
}

double automatic_grid_spacing(const StockExtent& extent, const std::map<int, Tool>& tools,
                              double work_columns) {
  const double fine = default_grid_spacing(tools);
  double smallest = 0;
  for (const auto& [number, tool] : tools)
    if (tool.diameter_mm > 0 && (smallest == 0 || tool.diameter_mm < smallest))
      smallest = tool.diameter_mm;
  // Coarser than a twentieth of the diameter, single cuts lose more than half a percent of their
  // volume (docs/removal.md).
  const double coarse = smallest > 0 ? std::clamp(smallest / 20.0, fine, 2.0) : fine;
  // Columns visited: per step of length s, a band 2r wide and 2r + s long, over dx^2 each.
  auto work = [&](double dx) {
    const double s = recommended_sample_step(tools, dx);
    double w = 0;
    for (const auto& [number, tool] : tools) {
      const double r = tool.reach_radius();
      w += extent.cutting_length(number) / s * (2 * r) * (2 * r + s) / (dx * dx);
    }
    return w;
  };
  double dx = fine;
  while (dx < coarse && work(dx) > work_columns)
    dx = std::min(coarse, dx * 1.25);
  return dx;
}

double recommended_sample_step(const std::map<int, Tool>& tools, double grid_mm) {
  double radius = 0;
  for (const auto& [number, tool] : tools)
    if (tool.diameter_mm > 0 && (radius == 0 || tool.radius() < radius)) radius = tool.radius();
  const double grid = grid_mm > 0 ? grid_mm : default_grid_spacing(tools);
  // A whole number of grid pitches: a step along a grid axis then crosses the same number of
  // columns every time, and the MRR of a steady cut is steady from step to step.
  const double wanted = std::min(std::max(grid, radius / 4), std::max(grid, 1.0));
  return grid * std::max(1.0, std::round(wanted / grid));
}

} // namespace ncjoule
