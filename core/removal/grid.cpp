// The column grid shared by the engines, and the engine factory.
#include <algorithm>
#include <cmath>

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

double recommended_sample_step(const std::map<int, Tool>& tools, double grid_mm) {
  double step = grid_mm > 0 ? grid_mm : default_grid_spacing(tools);
  for (const auto& [number, tool] : tools)
    if (tool.diameter_mm > 0) step = std::min(step, tool.radius() / 4);
  return step;
}

} // namespace ncjoule
