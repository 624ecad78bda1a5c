// Playing a timed program on the stock: the volume of every sampled step, per command and in
// total, the MRR through each command, and collisions of rapids with the stock. The memory of
// the stock model is estimated before it is allocated, and checked against a budget.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ncjoule/removal.hpp"

namespace ncjoule {
namespace {

// A rapid removing less than this is grazing within rounding, not a collision.
constexpr double kCollisionMinMm3 = 1e-6;
// A step removing less than this (a cube of 1 um side) removes nothing: what is left is the
// rounding of the stock model's arithmetic, which differs between C libraries (a glancing step
// gives 1.7e-16 mm^3 with one and 2.5e-16 or 0 with another). Counting it would make the block
// a cut on one system and air on the other.
constexpr double kRoundingMm3 = 1e-9;

// A length (mm) to the nearest nanometre. Sample positions of arcs come from sin and cos, and a
// coarsened grid's spacing from pow, whose last bits differ between C libraries; a grid column
// whose centre lies on the tool's edge would be cut on one system and not on the other. Taken to
// a nanometre first, the same program cuts the same columns everywhere.
double to_nanometre(double mm) {
  return std::nearbyint(mm * 1e6) * 1e-6;
}

Point3 to_nanometre(double x, double y, double z) {
  return Point3(to_nanometre(x), to_nanometre(y), to_nanometre(z));
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

// Sample points of a move; when the planner gave none, the move's own geometry at a fixed
// number of points, evenly spread in time.
std::vector<MotionSample> samples_of(const TimedCommand& tc, const CanonCommand& cmd,
                                     double max_step_mm) {
  if (tc.samples.size() >= 2) return tc.samples;
  const double length = move_length(cmd);
  // At most 100,000 points, as the planner samples (a move to X1e23 is not a billion steps).
  const int n = int(std::clamp(std::ceil(length / max_step_mm - 1e-9), 1.0, 1e5));
  std::vector<MotionSample> out(std::size_t(n) + 1);
  for (int k = 0; k <= n; ++k) {
    const double u = double(k) / n;
    out[k].u = u;
    out[k].t_s = tc.start_s + u * tc.duration_s;
    out[k].position = point_on_move(cmd, u);
  }
  return out;
}

// The memory a column of the dexel engine takes: its first index, count and top, a share of a
// tile's top, and its intervals (one for a box, a few for a mesh).
std::size_t dexel_column_bytes(StockSpec::Kind kind) {
  const std::size_t intervals = kind == StockSpec::Kind::Stl ? 3 : 1;
  return sizeof(std::uint32_t) + sizeof(std::uint16_t) + sizeof(double) +
         intervals * sizeof(ZInterval);
}

std::string mib(std::size_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f MiB", double(bytes) / (1 << 20));
  return buf;
}

} // namespace

std::size_t estimated_removal_memory(EngineKind engine, const GridFrame& grid,
                                     StockSpec::Kind stock_kind, double crossings_per_column) {
  const double columns = double(grid.nx) * double(grid.ny);
  // Filling from a mesh sorts every crossing (column, z) in one array and pairs them into
  // intervals: held together for a moment, whichever engine keeps the stock (the array of
  // crossings at up to twice its size, as it grows).
  const double filling = stock_kind == StockSpec::Kind::Stl
                             ? columns * crossings_per_column * (2 * 16 + sizeof(ZInterval) / 2)
                             : 0;
  if (engine == EngineKind::Voxel) {
    const double layers = double(voxel_layer_bounds(grid).size() - 1);
    return std::size_t(std::min(columns * layers + filling, 1e18));
  }
  return std::size_t(std::min(columns * double(dexel_column_bytes(stock_kind)) + filling, 1e18));
}

RemovalSimulator::RemovalSimulator(const StockSpec& spec, const StockExtent& extent,
                                   const std::map<int, Tool>& tools, const RemovalOptions& options)
    : tools_(tools), options_(options) {
  totals_.engine = options.engine;
  totals_.z_mirrored = options.mirror_z;
  auto diag = [&](Severity s, int line, std::string message) {
    totals_.diagnostics.push_back({s, options.source_path, line, 0, std::move(message)});
  };
  for (auto it = tools_.begin(); it != tools_.end();) {
    if (const std::string problem = tool_problem(it->second); !problem.empty()) {
      diag(Severity::Error, 0, "tool T" + std::to_string(it->first) + " " + problem);
      it = tools_.erase(it);
    } else {
      ++it;
    }
  }

  // The stock.
  switch (spec.kind) {
  case StockSpec::Kind::Box: {
    Box3 placed = spec.box;
    std::string how;
    if (spec.size_only) {
      std::optional<Box3> cuts = extent.box(tools_);
      if (cuts && options.mirror_z)
        *cuts = Box3{cuts->xmin, cuts->ymin, -cuts->zmax, cuts->xmax, cuts->ymax, -cuts->zmin};
      placed = place_sized_stock(spec.box, cuts, how);
    }
    Box3 box = placed;
    if (options.mirror_z) box.zmin = -placed.zmax, box.zmax = -placed.zmin;
    // A stock the program's comments state says so; others are given by the user.
    stock_ = make_box_stock(
        box, format_box(placed) +
                 (spec.stated_by_program
                      ? " (from " + spec.origin +
                            (spec.size_only ? "; placed where the cuts fit it: " + how : "") + ")"
                      : " (given)"));
    break;
  }
  case StockSpec::Kind::Stl: {
    std::vector<Diagnostic> problems;
    auto mesh = read_stl(spec.stl_path, problems);
    if (!mesh) {
      for (Diagnostic& d : problems) {
        d.message = "stock: " + d.message + "; nothing is removed";
        totals_.diagnostics.push_back(std::move(d));
      }
      totals_.stock_description = "none (" + spec.stl_path + " could not be read)";
      return;
    }
    const std::string text = "STL " + spec.stl_path + " (" +
                             std::to_string(mesh->triangles.size()) + " triangles, bounds " +
                             format_box(mesh->bounds()) + ")";
    if (spec.stl_units == LengthUnit::Inch) // an STL has no unit: this one was said to be inches
      for (Triangle& t : mesh->triangles)
        for (auto& vertex : t.v)
          for (double& c : vertex)
            c *= 25.4;
    crossings_ = mesh->crossings_per_column();
    if (options.mirror_z) // crossings pair up along each column: the winding does not matter
      for (Triangle& t : mesh->triangles)
        for (auto& vertex : t.v)
          vertex[2] = -vertex[2];
    stock_ = make_mesh_stock(std::move(*mesh), text);
    break;
  }
  case StockSpec::Kind::Default: {
    const std::optional<StockGuess> guess =
        guess_stock(extent.tool_cuts(tools_), options.program_inch,
                    options.first_setup_stock ? &*options.first_setup_stock : nullptr);
    if (!guess || guess->box.empty()) {
      const char* why = !guess ? "the program has no cutting move with a known tool"
                               : "its cuts have no extent to guess a stock from";
      diag(Severity::Warning, 0,
           std::string("no stock given and ") + why +
               ": nothing is removed (give a stock box or STL)");
      totals_.stock_description = "none (no stock given, and " + std::string(why) + ")";
      return;
    }
    std::string rules;
    for (const std::string& rule : guess->rules)
      rules += "; " + rule;
    stock_ = make_box_stock(guess->box,
                            format_box(guess->box) + " (guessed, no stock given" + rules + ")");
    break;
  }
  }
  totals_.stock_description = stock_->description();
  totals_.stock_source = spec.kind == StockSpec::Kind::Default ? StockSource::Guessed
                         : spec.stated_by_program              ? StockSource::Program
                                                               : StockSource::Given;
  totals_.stock_from = spec.kind == StockSpec::Kind::Default ? "guess" : spec.from;
  totals_.stock_origin = spec.origin;
  totals_.stock_box = stock_->bounds();
  if (options.mirror_z)
    totals_.stock_box.zmin = -stock_->bounds().zmax,
    totals_.stock_box.zmax = -stock_->bounds().zmin;
  if (options.mirror_z)
    totals_.stock_description += "; Z mirrored (+Z points into the work): the program's Z" +
                                 format_mm3(-stock_->bounds().zmax) + " is the stock's top, Z" +
                                 format_mm3(-stock_->bounds().zmin) + " its bottom";
  const Box3 bounds = stock_->bounds();
  if (bounds.empty()) {
    diag(Severity::Error, 0, "stock has no volume: nothing is removed");
    return;
  }
  // A stock wider than any machine is in the wrong units or at absurd coordinates: no grid
  // helps, so none is tried.
  const double widest =
      std::max({bounds.xmax - bounds.xmin, bounds.ymax - bounds.ymin, bounds.zmax - bounds.zmin});
  if (!(widest <= kMaxStockWidthMm)) {
    char size[64] = "too wide to measure";
    if (std::isfinite(widest)) std::snprintf(size, sizeof size, "%.3g mm wide", widest);
    diag(Severity::Error, 0,
         std::string("stock is ") + size + ", more than any machine's travel (" +
             std::to_string(int(kMaxStockWidthMm / 1000)) +
             " m): check its units and coordinates; nothing is removed");
    return;
  }

  if (spec.kind != StockSpec::Kind::Default)
    if (const auto cuts = extent.box(tools_))
      if (std::string why = stock_mismatch(bounds, *cuts, spec, options.program_inch); !why.empty())
        diag(Severity::Warning, 0, std::move(why));

  // The grid: the one given, or the automatic one within the cell caps and the memory budget.
  const std::size_t budget =
      options.memory_budget_bytes ? options.memory_budget_bytes : kDefaultRemovalMemoryBudget;
  const std::vector<double> levels =
      options.engine == EngineKind::Voxel ? extent.cutting_levels() : std::vector<double>{};
  auto grid_at = [&](double mm) {
    GridFrame g = make_grid(bounds, mm);
    g.z_levels = levels;
    return g;
  };
  auto cells = [&](const GridFrame& g) {
    double n = double(g.nx) * double(g.ny);
    if (options.engine == EngineKind::Voxel) n *= double(voxel_layer_bounds(g).size() - 1);
    return n;
  };
  const double cell_limit =
      double(options.engine == EngineKind::Voxel ? options.max_voxels : options.max_columns);
  double spacing =
      options.grid_mm > 0
          ? options.grid_mm
          : automatic_grid_spacing(extent, tools_, options.work_columns,
                                   (bounds.xmax - bounds.xmin) * (bounds.ymax - bounds.ymin),
                                   bounds.zmax);
  // Far too fine a grid is refused before its frame is even made: its cell count would overflow.
  const double width = std::max(bounds.xmax - bounds.xmin, bounds.ymax - bounds.ymin);
  if (!(spacing > 0) || !std::isfinite(spacing) || width / spacing > 1e8) {
    diag(Severity::Error, 0,
         "removal grid of " + format_mm3(spacing) + " mm over a stock " + format_mm3(width) +
             " mm wide has too many columns: give a coarser --grid");
    return;
  }
  grid_ = grid_at(spacing);
  const bool given = options.grid_mm > 0;
  const std::size_t needed = estimated_removal_memory(options.engine, grid_, spec.kind, crossings_);
  if (given && needed > budget) {
    diag(Severity::Error, 0,
         "removal grid of " + format_mm3(spacing) + " mm over the stock needs about " +
             mib(needed) + ", over the memory budget of " + mib(budget) +
             ": give a coarser --grid, or a larger --memory-limit; nothing is removed");
    return;
  }
  if (!given && (cells(grid_) > cell_limit || needed > budget)) {
    const double power = options.engine == EngineKind::Voxel ? 1.0 / 3.0 : 0.5;
    while (cells(grid_) > cell_limit ||
           estimated_removal_memory(options.engine, grid_, spec.kind, crossings_) > budget) {
      const double over =
          std::max(cells(grid_) / cell_limit,
                   double(estimated_removal_memory(options.engine, grid_, spec.kind, crossings_)) /
                       double(budget));
      spacing = to_nanometre(spacing * std::max(1.01, std::pow(over, power)));
      grid_ = grid_at(spacing);
    }
    diag(Severity::Note, 0,
         "removal grid coarsened to " + format_mm3(spacing) + " mm to stay within " +
             std::to_string(std::size_t(cell_limit)) + " cells and " + mib(budget));
  }
  engine_ = make_removal_engine(options.engine, *stock_, grid_);
  totals_.grid = grid_;
  totals_.stock_volume_mm3 = engine_->material_volume_mm3();
  totals_.memory_bytes = engine_->memory_bytes();
  sample_step_ = recommended_sample_step(tools_, spacing);
}

RemovalSimulator::~RemovalSimulator() = default;

void RemovalSimulator::remove(const std::vector<TimedMove>& moves,
                              std::vector<CommandRemoval>& out) {
  // `out`'s results are emptied, not made anew: a stream that hands them back (a spare batch)
  // fills their step vectors again without allocating. A long move's are let go: each result
  // keeps the largest it ever held, and a batch's 2,048 results kept at most 64 steps each hold
  // 1.5 MiB, where a few thousand each would grow to hundreds.
  out.resize(moves.size());
  for (CommandRemoval& r : out) {
    constexpr std::size_t kKeptSteps = 64;
    std::vector<double> volumes = std::move(r.step_volume_mm3);
    std::vector<float> depths = std::move(r.step_depth_mm);
    r = CommandRemoval{};
    if (volumes.capacity() <= kKeptSteps) r.step_volume_mm3 = std::move(volumes);
    if (depths.capacity() <= kKeptSteps) r.step_depth_mm = std::move(depths);
    r.step_volume_mm3.clear();
    r.step_depth_mm.clear();
  }
  if (!engine_) return;
  const double z_sign = options_.mirror_z ? -1.0 : 1.0;
  // Every move's steps, in order, in one batch; first[k] is move k's first step.
  steps_.clear();
  std::vector<std::size_t> first(moves.size() + 1, 0);
  std::vector<std::vector<MotionSample>> sampled(moves.size());
  for (std::size_t k = 0; k < moves.size(); ++k) {
    first[k] = steps_.size();
    const CanonCommand& cmd = *moves[k].command;
    const TimedCommand& tc = *moves[k].timed;
    if (!is_move(cmd.kind)) continue;
    if (!warned_rotary_ &&
        (cmd.start.a != cmd.end.a || cmd.start.b != cmd.end.b || cmd.start.c != cmd.end.c)) {
      // The stock model is 3-axis: it does not turn with a rotary table or a 4th axis.
      warned_rotary_ = true;
      totals_.diagnostics.push_back(
          {Severity::Warning, options_.source_path, tc.line + 1, 0,
           "the program turns a rotary axis (A/B/C) here: removal is 3-axis (the stock does not "
           "turn), so volumes, MRR, cutting power and collisions from here on are "
           "approximations; times are not"});
    }
    const auto tool = tools_.find(cmd.state.tool);
    if (tool == tools_.end()) continue;
    // A rapid from where the program has not yet said the spindle is ("G0 X Y" before the
    // first Z: the assumed start at Z0 is not the real one) removes nothing.
    if (cmd.kind == CanonKind::Traverse && !cmd.start_known) continue;
    if (!first_move_checked_) {
      // A program that starts with its tool in the material: the stock, the work offset or the
      // start point is wrong, and the first moves would cut where nothing can.
      first_move_checked_ = true;
      const Pose& at = cmd.start;
      if (engine_->material_at(Point3(at.x, at.y, z_sign * at.z))) {
        char text[200];
        std::snprintf(text, sizeof text,
                      "the program's first move starts inside the stock (X%.3f Y%.3f Z%.3f mm): "
                      "check the stock, the work offset and the start point",
                      at.x, at.y, at.z);
        totals_.diagnostics.push_back(
            {Severity::Warning, options_.source_path, tc.line + 1, 0, text});
      }
    }
    if (tc.samples.size() < 2 && !warned_no_samples_ && move_length(cmd) > 0) {
      warned_no_samples_ = true;
      totals_.diagnostics.push_back({Severity::Note, options_.source_path, tc.line + 1, 0,
                                     "moves without path samples are sampled evenly in time by "
                                     "removal"});
    }
    const std::vector<MotionSample>* samples = &tc.samples;
    if (tc.samples.size() < 2) {
      sampled[k] = samples_of(tc, cmd, sample_step_ > 0 ? sample_step_ : 1.0);
      samples = &sampled[k];
    }
    for (std::size_t s = 0; s + 1 < samples->size(); ++s) {
      const Pose& a = (*samples)[s].position;
      const Pose& b = (*samples)[s + 1].position;
      steps_.push_back({&tool->second, to_nanometre(a.x, a.y, z_sign * a.z),
                        to_nanometre(b.x, b.y, z_sign * b.z)});
    }
    out[k].step_volume_mm3.resize(samples->size() - 1);
  }
  first[moves.size()] = steps_.size();
  engine_->remove_steps(steps_, volumes_, &cut_tops_);

  for (std::size_t k = 0; k < moves.size(); ++k) {
    CommandRemoval& r = out[k];
    if (r.step_volume_mm3.empty()) continue;
    const CanonCommand& cmd = *moves[k].command;
    const TimedCommand& tc = *moves[k].timed;
    const std::vector<MotionSample>& samples = sampled[k].empty() ? tc.samples : sampled[k];
    const bool depths = !std::isnan(cut_tops_[first[k]]);
    if (depths) r.step_depth_mm.resize(r.step_volume_mm3.size());
    for (std::size_t s = 0; s < r.step_volume_mm3.size(); ++s) {
      const double v = volumes_[first[k] + s] < kRoundingMm3 ? 0.0 : volumes_[first[k] + s];
      if (depths) {
        const RemovalStep& step = steps_[first[k] + s];
        const double depth = cut_tops_[first[k] + s] - std::min(step.from.z(), step.to.z());
        r.step_depth_mm[s] = v > 0 && depth > 0 ? float(depth) : 0.0f;
      }
      r.step_volume_mm3[s] = v;
      r.removed_mm3 += v;
      const double dt = samples[s + 1].t_s - samples[s].t_s;
      if (dt > 0) r.mrr_peak_mm3_s = std::max(r.mrr_peak_mm3_s, v / dt);
    }
    if (tc.duration_s > 0) r.mrr_mean_mm3_s = r.removed_mm3 / tc.duration_s;
    if (cmd.kind == CanonKind::Traverse && r.removed_mm3 > kCollisionMinMm3 &&
        totals_.stock_source == StockSource::Guessed) {
      // A CAM rapids through air only: a guessed box that a rapid enters is larger there than
      // the real stock (an adaptive's entry outside the part falls inside the box the tool's
      // radius widened). What the rapid passes through is taken as air, not as a cut.
      ++air_rapids_;
      air_rapid_mm3_ += r.removed_mm3;
      if (air_rapid_lines_.size() < 5) air_rapid_lines_.push_back(tc.line + 1);
      std::fill(r.step_volume_mm3.begin(), r.step_volume_mm3.end(), 0.0);
      std::fill(r.step_depth_mm.begin(), r.step_depth_mm.end(), 0.0f);
      r.removed_mm3 = r.mrr_mean_mm3_s = r.mrr_peak_mm3_s = 0;
      continue;
    }
    totals_.removed_mm3 += r.removed_mm3;
    if (cmd.kind == CanonKind::Traverse && r.removed_mm3 > kCollisionMinMm3) {
      r.collision = true;
      totals_.diagnostics.push_back({Severity::Warning, options_.source_path, tc.line + 1, 0,
                                     "rapid move cuts " + format_mm3(r.removed_mm3) +
                                         " mm^3 of stock with tool T" +
                                         std::to_string(cmd.state.tool) + " (collision)"});
    }
  }
}

RemovalResult RemovalSimulator::summary() const {
  RemovalResult r = totals_;
  if (engine_) {
    r.memory_bytes = std::max(r.memory_bytes, engine_->memory_bytes());
    r.stats = engine_->stats();
  }
  if (air_rapids_ > 0) {
    std::string lines;
    for (const int line : air_rapid_lines_)
      lines += (lines.empty() ? "" : ", ") + std::to_string(line);
    if (air_rapids_ > air_rapid_lines_.size()) lines += ", ...";
    const std::string count =
        std::to_string(air_rapids_) + (air_rapids_ == 1 ? " rapid" : " rapids");
    r.diagnostics.push_back(
        {Severity::Note, options_.source_path, air_rapid_lines_.front(), 0,
         "the guessed stock reaches where " + count + (air_rapids_ == 1 ? " goes" : " go") + " (" +
             (air_rapids_ == 1 ? "line " : "lines ") + lines +
             "): a CAM rapids through air only, so the real stock is smaller there; the " +
             format_mm3(air_rapid_mm3_) +
             " mm^3 they pass through is taken as air, not as a cut (give the stock to check "
             "rapids for collisions)"});
    r.stock_description +=
        "; trimmed where " + count + (air_rapids_ == 1 ? " enters" : " enter") + " it";
  }
  return r;
}

RemovalResult simulate_removal(const std::vector<CanonCommand>& commands, const Timeline& timeline,
                               const std::map<int, Tool>& tools, const StockSpec& spec,
                               const RemovalOptions& options) {
  StockExtent extent;
  for (const TimedCommand& tc : timeline.commands)
    if (tc.command < commands.size())
      extent.add(options.mirror_z ? mirrored_z(commands[tc.command]) : commands[tc.command]);
  // The tools moves use (the grid is sized for them).
  std::map<int, Tool> used;
  for (const CanonCommand& c : commands)
    if (is_move(c.kind))
      if (auto it = tools.find(c.state.tool); it != tools.end()) used.insert(*it);
  RemovalSimulator simulator(spec, extent, used.empty() ? tools : used, options);
  std::vector<TimedMove> moves;
  for (std::size_t k = 0; k < timeline.commands.size(); ++k) {
    const TimedCommand& tc = timeline.commands[k];
    if (tc.command < commands.size()) moves.push_back({k, &commands[tc.command], &tc});
  }
  std::vector<CommandRemoval> removed;
  simulator.remove(moves, removed);
  RemovalResult result = simulator.summary();
  result.commands.resize(timeline.commands.size());
  for (std::size_t m = 0; m < moves.size(); ++m)
    result.commands[moves[m].index] = std::move(removed[m]);
  return result;
}

} // namespace ncjoule
