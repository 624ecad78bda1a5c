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

std::optional<bool> RemovalEngine::material_above(const Point3&, const Point3&, double,
                                                  double) const {
  return std::nullopt;
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

namespace {

// The coarsest grid the automatic choice goes to: a twentieth of the largest diameter (a face
// mill's passes), but no more than an eighth of the smallest, so that the smallest tool's cuts
// still span several columns (their MRR per block stays readable), and at most 2 mm.
double coarsest_grid_spacing(const std::map<int, Tool>& tools) {
  double smallest = 0, largest = 0;
  for (const auto& [number, tool] : tools)
    if (tool.diameter_mm > 0) {
      smallest = smallest > 0 ? std::min(smallest, tool.diameter_mm) : tool.diameter_mm;
      largest = std::max(largest, tool.diameter_mm);
    }
  return std::max(default_grid_spacing(tools), std::min({largest / 20.0, smallest / 8.0, 2.0}));
}

// The volume a cut gains or loses along its edges on the grid is about this share of the
// spacing over the tool's diameter: 0.06 on single cuts (docs/removal.md's table: 0.1-0.5% at
// d/20, 0.02-0.1% at d/60), 0.1 on the worst real program measured (the FreeCAD sample job, a
// pocket and contours: 0.17% at d/60, docs/removal.md).
constexpr double kEdgeErrorPerSpacing = 0.1;
// What the automatic grid aims at: removed volume within 0.1% (and the MRR of blocks that cut
// more than a sliver with it).
constexpr double kVolumeErrorTarget = 0.001;
// Below this many columns (about 32 MiB of stock model) the finest grid costs little.
constexpr double kSmallJobColumns = 1e6;

} // namespace

double accuracy_grid_spacing(const StockExtent& extent, const std::map<int, Tool>& tools,
                             double top_z) {
  // Each tool's cuts, weighted by the share of the removal they make (the area they sweep: their
  // length in the stock times the diameter): the spacing that keeps the sum of their edge errors
  // within the target. A face mill's pass over the air above the stock has no edge to lose.
  double weight = 0, per_diameter = 0, smallest = 0;
  for (const auto& [number, tool] : tools) {
    if (!(tool.diameter_mm > 0)) continue;
    const double d = tool.diameter_mm;
    smallest = smallest > 0 ? std::min(smallest, d) : d;
    const double w = extent.cutting_length(number, top_z) * d;
    weight += w;
    per_diameter += w / d;
  }
  if (smallest == 0) return 0.1;
  const double fine = default_grid_spacing(tools);
  if (!(weight > 0)) return std::clamp(smallest / 60.0, fine, coarsest_grid_spacing(tools));
  const double spacing = kVolumeErrorTarget / kEdgeErrorPerSpacing / (per_diameter / weight);
  return std::clamp(spacing, fine, coarsest_grid_spacing(tools));
}

double automatic_grid_spacing(const StockExtent& extent, const std::map<int, Tool>& tools,
                              double work_columns, double stock_area_mm2, double top_z) {
  const double accurate = accuracy_grid_spacing(extent, tools, top_z);
  // Coarser than a twentieth of the diameter, single cuts lose more than half a percent of their
  // volume (docs/removal.md).
  const double coarse = std::max(accurate, coarsest_grid_spacing(tools));
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
  // A small job keeps the finest grid: it costs little there, and a thin pass (a finishing
  // pass half a millimetre wide) has its MRR off by up to a column's width over its own width.
  const double fine = default_grid_spacing(tools);
  if (stock_area_mm2 > 0 && fine < accurate && stock_area_mm2 / (fine * fine) <= kSmallJobColumns &&
      work(fine) <= work_columns / 4)
    return fine;
  double dx = accurate;
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
