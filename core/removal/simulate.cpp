// Playing a timed program on the stock: the volume of every sampled step, per command and in
// total, the MRR through each command, and collisions of rapids with the stock.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ncjoule/removal.hpp"

namespace ncjoule {
namespace {

// A rapid removing less than this is grazing within rounding, not a collision.
constexpr double kCollisionMinMm3 = 1e-6;

bool is_move(CanonKind k) {
  return k == CanonKind::Traverse || k == CanonKind::Feed || k == CanonKind::Arc ||
         k == CanonKind::Probe;
}

std::string format_box(const Box3& b) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "box %.3f,%.3f,%.3f to %.3f,%.3f,%.3f mm", b.xmin, b.ymin, b.zmin,
                b.xmax, b.ymax, b.zmax);
  return buf;
}

std::string format_mm3(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

// The tools the program's moves use (for the default grid and sample step).
std::map<int, Tool> tools_in_use(const std::vector<CanonCommand>& commands,
                                 const std::map<int, Tool>& tools) {
  std::map<int, Tool> used;
  for (const CanonCommand& c : commands)
    if (is_move(c.kind))
      if (auto it = tools.find(c.state.tool); it != tools.end()) used.insert(*it);
  return used.empty() ? tools : used;
}

// The Z levels of the cutting moves' end points (flat floors, plunge bottoms), for the voxel
// engine's layer boundaries.
std::vector<double> cutting_levels(const std::vector<CanonCommand>& commands,
                                   const std::map<int, Tool>& tools) {
  std::vector<double> levels;
  for (const CanonCommand& c : commands)
    if ((c.kind == CanonKind::Feed || c.kind == CanonKind::Arc) && tools.count(c.state.tool)) {
      levels.push_back(c.start.z);
      levels.push_back(c.end.z);
    }
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  return levels;
}

// Sample points of a move; when the planner gave none, the move's own geometry at a fixed
// number of points, evenly spread in time.
std::vector<MotionSample> samples_of(const TimedCommand& tc, const CanonCommand& cmd,
                                     double max_step_mm) {
  if (tc.samples.size() >= 2) return tc.samples;
  const double length = move_length(cmd);
  const int n = std::max(1, int(std::ceil(length / max_step_mm - 1e-9)));
  std::vector<MotionSample> out(std::size_t(n) + 1);
  for (int k = 0; k <= n; ++k) {
    const double u = double(k) / n;
    out[k].u = u;
    out[k].t_s = tc.start_s + u * tc.duration_s;
    out[k].position = point_on_move(cmd, u);
  }
  return out;
}

} // namespace

RemovalResult simulate_removal(const std::vector<CanonCommand>& commands, const Timeline& timeline,
                               const std::map<int, Tool>& tools, const StockSpec& spec,
                               const RemovalOptions& options) {
  RemovalResult result;
  result.engine = options.engine;
  result.commands.resize(timeline.commands.size());
  auto diag = [&](Severity s, int line, std::string message) {
    result.diagnostics.push_back({s, options.source_path, line, 0, std::move(message)});
  };
  for (const auto& [number, tool] : tools)
    if (const std::string problem = tool_problem(tool); !problem.empty())
      diag(Severity::Error, 0, "tool T" + std::to_string(number) + " " + problem);

  // The stock.
  std::unique_ptr<StockShape> stock;
  switch (spec.kind) {
  case StockSpec::Kind::Box:
    stock = make_box_stock(spec.box, format_box(spec.box) + " (given)");
    break;
  case StockSpec::Kind::Stl: {
    std::string error;
    auto mesh = read_stl(spec.stl_path, error);
    if (!mesh) {
      diag(Severity::Error, 0, "stock: " + error + "; nothing is removed");
      result.stock_description = "none (" + spec.stl_path + " could not be read)";
      return result;
    }
    const std::string text = "STL " + spec.stl_path + " (" +
                             std::to_string(mesh->triangles.size()) + " triangles, bounds " +
                             format_box(mesh->bounds()) + ")";
    stock = make_mesh_stock(std::move(*mesh), text);
    break;
  }
  case StockSpec::Kind::Default: {
    const auto box = default_stock_box(commands, timeline, tools);
    if (!box || box->empty()) {
      const char* why = !box ? "the program has no cutting move with a known tool"
                             : "every cutting move is at one Z level";
      diag(Severity::Warning, 0,
           std::string("no stock given and ") + why +
               ": nothing is removed (give a stock box or STL)");
      result.stock_description = "none (no stock given, and " + std::string(why) + ")";
      return result;
    }
    stock = make_box_stock(*box, format_box(*box) +
                                     " (default: bounding box of the cutting moves, XY widened "
                                     "by the tool radius, Z from the lowest cut up to the "
                                     "highest level at which a cutting move travels in XY)");
    break;
  }
  }
  const Box3 bounds = stock->bounds();
  if (bounds.empty()) {
    diag(Severity::Error, 0, "stock has no volume: nothing is removed");
    result.stock_description = stock->description();
    return result;
  }

  // The grid.
  const std::map<int, Tool> used = tools_in_use(commands, tools);
  double spacing = options.grid_mm > 0 ? options.grid_mm : default_grid_spacing(used);
  const std::vector<double> levels = cutting_levels(commands, tools);
  auto grid_at = [&](double mm) {
    GridFrame g = make_grid(bounds, mm);
    if (options.engine == EngineKind::Voxel) g.z_levels = levels;
    return g;
  };
  GridFrame grid = grid_at(spacing);
  auto cells = [&](const GridFrame& g) {
    double n = double(g.nx) * double(g.ny);
    if (options.engine == EngineKind::Voxel) n *= double(voxel_layer_bounds(g).size() - 1);
    return n;
  };
  const double limit =
      double(options.engine == EngineKind::Voxel ? options.max_voxels : options.max_columns);
  if (cells(grid) > limit) {
    const double power = options.engine == EngineKind::Voxel ? 1.0 / 3.0 : 0.5;
    while (cells(grid) > limit) {
      spacing *= std::max(1.01, std::pow(cells(grid) / limit, power));
      grid = grid_at(spacing);
    }
    diag(Severity::Note, 0,
         "grid coarsened to " + format_mm3(spacing) + " mm to stay within " +
             std::to_string(std::size_t(limit)) + " cells");
  }
  const std::unique_ptr<RemovalEngine> engine = make_removal_engine(options.engine, *stock, grid);
  result.grid = grid;
  result.stock_description = stock->description();
  result.stock_volume_mm3 = engine->material_volume_mm3();
  result.memory_bytes = engine->memory_bytes();

  // The moves, step by step.
  const double fallback_step = recommended_sample_step(used, spacing);
  bool warned_no_samples = false;
  for (std::size_t k = 0; k < timeline.commands.size(); ++k) {
    const TimedCommand& tc = timeline.commands[k];
    if (tc.command >= commands.size()) continue;
    const CanonCommand& cmd = commands[tc.command];
    if (!is_move(cmd.kind)) continue;
    const auto tool = tools.find(cmd.state.tool);
    if (tool == tools.end() || !tool_problem(tool->second).empty()) continue;
    if (tc.samples.size() < 2 && !warned_no_samples && move_length(cmd) > 0) {
      warned_no_samples = true;
      diag(Severity::Note, tc.line + 1,
           "moves without path samples are sampled evenly in time by removal");
    }
    const std::vector<MotionSample> samples = samples_of(tc, cmd, fallback_step);
    CommandRemoval& out = result.commands[k];
    out.step_volume_mm3.resize(samples.size() - 1);
    for (std::size_t s = 0; s + 1 < samples.size(); ++s) {
      const Pose& a = samples[s].position;
      const Pose& b = samples[s + 1].position;
      const double v = engine->remove_step(tool->second, {a.x, a.y, a.z}, {b.x, b.y, b.z});
      out.step_volume_mm3[s] = v;
      out.removed_mm3 += v;
      const double dt = samples[s + 1].t_s - samples[s].t_s;
      if (dt > 0) out.mrr_peak_mm3_s = std::max(out.mrr_peak_mm3_s, v / dt);
    }
    if (tc.duration_s > 0) out.mrr_mean_mm3_s = out.removed_mm3 / tc.duration_s;
    result.removed_mm3 += out.removed_mm3;
    if (cmd.kind == CanonKind::Traverse && out.removed_mm3 > kCollisionMinMm3) {
      out.collision = true;
      diag(Severity::Warning, tc.line + 1,
           "rapid move cuts " + format_mm3(out.removed_mm3) + " mm^3 of stock with tool T" +
               std::to_string(cmd.state.tool) + " (collision)");
    }
  }
  result.memory_bytes = std::max(result.memory_bytes, engine->memory_bytes());
  result.stats = engine->stats();
  return result;
}

} // namespace ncjoule
