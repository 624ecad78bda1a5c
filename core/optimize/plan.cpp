// The plan: replays the moves on a fresh dexel model of the stock and decides, move by move
// before it removes anything, which feed moves run clear of the material (optimize.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

#include "block_rewrite.hpp"
#include "dog_leg.hpp"
#include "ncjoule/optimize.hpp"
#include "simple_block.hpp"

namespace ncjoule {
namespace {

using optimize_detail::read_simple_block;
using optimize_detail::SimpleBlock;

Point3 point(const Pose& p) {
  return Point3(p.x, p.y, p.z);
}

// How often each line produced a move, and whether any of its commands ran in a subprogram.
struct LineUse {
  int moves = 0;
  bool elsewhere = false; // a command of it came from a call (call_line != line)
};

// The air feed along a move (mm/min): `base`, capped so that no axis passes its max_feed.
double capped_feed(const CanonCommand& c, const Kinematics& k, double base_mm_min) {
  const double d[3] = {c.end.x - c.start.x, c.end.y - c.start.y, c.end.z - c.start.z};
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  double feed = base_mm_min;
  for (int i = 0; i < 3; ++i) {
    const double share = std::abs(d[i]) / length;
    if (share > 1e-9 && k.axes[i].max_feed_mm_s > 0)
      feed = std::min(feed, k.axes[i].max_feed_mm_s * 60 / share);
  }
  return feed;
}

// The feed as it will be written: rounded down to what the program's units write (1 mm/min,
// 0.1 in/min), so that the cap holds after rounding.
double writable_feed(double mm_min, bool inch) {
  if (inch) return std::floor(mm_min / 25.4 * 10) / 10 * 25.4;
  return std::floor(mm_min);
}

// Removes what a move sweeps: lines in one step, arcs in chords no longer than `step`.
void remove_move(RemovalEngine& engine, const Tool& tool, const CanonCommand& c, double step) {
  if (c.kind != CanonKind::Arc) {
    engine.remove_step(tool, point(c.start), point(c.end));
    return;
  }
  const double length = move_length(c);
  const double sweep = std::abs(arc_geometry(c).sweep);
  const int n = std::clamp(int(std::ceil(std::max(length / step, sweep / (std::numbers::pi / 36)))),
                           1, 100'000);
  Pose from = c.start;
  for (int k = 1; k <= n; ++k) {
    const Pose to = k == n ? c.end : point_on_move(c, double(k) / n);
    engine.remove_step(tool, point(from), point(to));
    from = to;
  }
}

bool rotary_moves(const CanonCommand& c) {
  return c.start.a != c.end.a || c.start.b != c.end.b || c.start.c != c.end.c;
}

} // namespace

const char* edit_rule_name(EditRule rule) {
  switch (rule) {
  case EditRule::AirFeed:
    return "air";
  case EditRule::RapidLink:
    return "rapid";
  case EditRule::LoadFeed:
    return "load";
  case EditRule::RestoreG1:
    break;
  }
  return "restore";
}

OptimizePlan plan_optimization(const OptimizeInput& in, const OptimizeOptions& options) {
  if (!in.source || !in.commands || !in.tools || !in.stock)
    throw std::invalid_argument("plan_optimization: source, commands, tools and stock are needed");
  OptimizePlan plan;
  plan.margin_mm = std::max(options.margin_mm, 2 * std::max(in.grid.dx, in.grid.dy));
  double air =
      options.air_feed_mm_min > 0 ? options.air_feed_mm_min : in.kinematics.air_feed_mm_s * 60;
  if (!(air > 0))
    for (const AxisLimits& axis : in.kinematics.axes)
      air = std::max(air, axis.max_feed_mm_s * 60);
  plan.air_feed_mm_min = air;
  plan.load_share = options.load_share;
  plan.max_feed_factor = options.max_feed_factor;
  plan.min_feed_factor = options.min_feed_factor;
  plan.finish_depth_mm = options.finish_depth_mm;
  const bool inch = plan.inch = std::any_of(in.commands->begin(), in.commands->end(),
                                            [](const CanonCommand& c) { return c.state.inch; });

  std::unordered_map<int, LineUse> use;
  for (const CanonCommand& c : *in.commands) {
    LineUse& u = use[c.line];
    if (is_move(c.kind)) ++u.moves;
    if (c.call_line != c.line) u.elsewhere = true;
  }

  const std::unique_ptr<RemovalEngine> engine =
      make_removal_engine(EngineKind::Dexel, *in.stock, in.grid);
  const double chord = recommended_sample_step(*in.tools, std::min(in.grid.dx, in.grid.dy));
  const double margin = plan.margin_mm;
  // Whether the segment, inflated by the tool's reach plus the margin, is clear of material.
  auto clear = [&](const Point3& a, const Point3& b, double reach) {
    const std::optional<bool> found =
        engine->material_above(a, b, reach + margin, std::min(a.z(), b.z()) - margin);
    return found && !*found;
  };

  std::map<int, BlockEdit> edits;
  for (const CanonCommand& c : *in.commands) {
    if (!is_move(c.kind)) continue;
    const auto tool_it = in.tools->find(c.state.tool);
    const Tool* tool = tool_it != in.tools->end() ? &tool_it->second : nullptr;
    if (is_feed_move(c.kind)) ++plan.feed_moves;
    bool removed = false; // the move's removal is done (rule c asks it for the cut's depth)
    if (c.kind == CanonKind::Feed && tool && tool->diameter_mm > 0 && c.start_known &&
        c.machine_axes == 0 && !rotary_moves(c) && move_length(c) > 1e-6) {
      const double reach = std::max(tool->radius(), tool->shank_diameter_mm / 2);
      const LineUse& u = use[c.line];
      auto simple_block = [&]() -> std::optional<SimpleBlock> {
        if (u.moves == 1 && !u.elsewhere && c.state.feed_mode == FeedMode::UnitsPerMinute &&
            c.state.feed > 0 && std::size_t(c.line) < in.source->lines.size())
          return read_simple_block(in.source->line_text(std::size_t(c.line)), in.dialect);
        return std::nullopt;
      };
      const bool is_clear = clear(point(c.start), point(c.end), reach);
      if (!is_clear && options.load_feeds && in.loads) {
        const auto load = in.loads->find(c.line);
        const std::optional<SimpleBlock> block =
            load != in.loads->end() && load->second.load > 0 ? simple_block() : std::nullopt;
        if (block) {
          // Rule c: the cut's depth below the material's top, and its width (volume per length
          // over the depth), from this move's own removal.
          std::vector<double> volumes, tops;
          engine->remove_steps({RemovalStep{tool, point(c.start), point(c.end)}}, volumes, &tops);
          removed = true;
          const double volume = volumes.empty() ? 0 : volumes[0];
          const double top = tops.empty() ? std::nan("") : tops[0];
          const double depth = top - std::min(c.start.z, c.end.z);
          const double xy = std::hypot(c.end.x - c.start.x, c.end.y - c.start.y);
          const double width = xy > 1e-6 && depth > 0 ? volume / (xy * depth) : tool->diameter_mm;
          if (volume > 0 && std::isfinite(top)) {
            if (!(depth >= options.finish_depth_mm) || !(width >= options.finish_depth_mm)) {
              ++plan.finishing_passes;
            } else {
              const LoadAt& at = load->second;
              const double base = at.feed_mm_min > 0 ? at.feed_mm_min : c.state.feed;
              double target = base * std::pow(options.load_share / at.load, 1 / at.exponent);
              target = std::min(target, c.state.feed * options.max_feed_factor);
              const bool floored = target < c.state.feed * options.min_feed_factor;
              if (floored) target = c.state.feed * options.min_feed_factor;
              target = std::min(target, capped_feed(c, in.kinematics, target));
              const double feed = writable_feed(target, inch);
              const bool lower = feed < c.state.feed && feed > 0;
              const bool raise = feed >= c.state.feed * 1.05;
              if (lower || raise) {
                BlockEdit edit;
                edit.line = c.line;
                edit.rule = EditRule::LoadFeed;
                edit.feed_mm_min = feed;
                edit.was_feed_mm_min = c.state.feed;
                edit.has_f_word = block->has('F');
                edit.has_motion_word = block->has('G');
                if (optimize_detail::rewrite_block(in.source->line_text(std::size_t(c.line)),
                                                   in.dialect, edit, inch)) {
                  edits[c.line] = edit;
                  ++(lower ? plan.load_lowered : plan.load_raised);
                  plan.load_floored += floored;
                } else {
                  ++plan.too_long;
                }
              }
            }
          }
        }
      }
      if (is_clear) {
        ++plan.clear_moves;
        const std::optional<SimpleBlock> block = simple_block();
        if (block) {
          ++plan.simple_clear_moves;
          BlockEdit edit;
          edit.line = c.line;
          edit.was_feed_mm_min = c.state.feed;
          edit.has_f_word = block->has('F');
          edit.has_motion_word = block->has('G');
          bool done = false;
          // Rule b: a move that does not descend, as a rapid whose own path is clear too.
          if (options.rapid_links && c.end.z >= c.start.z - 1e-9) {
            bool path_clear = true;
            if (in.kinematics.rapid_mode == RapidMode::DogLeg) {
              CanonCommand rapid = c;
              rapid.kind = CanonKind::Traverse;
              const kinematics_detail::DogLegMove leg(rapid, in.kinematics);
              // Pieces of at most a quarter of the margin along the path (no longer than the
              // sum of the axes' travels); within a piece the path stays within a piece's length
              // of its ends, which the reach is widened by.
              const std::array<double, 3> travel = axis_travel(c);
              const double path = travel[0] + travel[1] + travel[2];
              const int pieces = std::clamp(int(std::ceil(path / (0.25 * margin))), 16, 4096);
              const double widen = path / pieces;
              Pose from = c.start;
              for (int k = 1; k <= pieces && path_clear; ++k) {
                const Pose to = leg.position_at(leg.duration() * k / pieces);
                path_clear = clear(point(from), point(to), reach + widen);
                from = to;
              }
            }
            if (path_clear) {
              edit.rule = EditRule::RapidLink;
              done = true;
            }
          }
          // Rule a: the air feed, where it is faster than the programmed one.
          if (!done && options.air_feeds) {
            const double feed = writable_feed(capped_feed(c, in.kinematics, air), inch);
            if (feed > c.state.feed * 1.05) {
              edit.rule = EditRule::AirFeed;
              edit.feed_mm_min = feed;
              done = true;
            }
          }
          if (done && !optimize_detail::rewrite_block(in.source->line_text(std::size_t(c.line)),
                                                      in.dialect, edit, inch)) {
            ++plan.too_long;
            done = false;
          }
          if (done) edits[c.line] = edit;
        }
      }
    }
    if (tool && tool->diameter_mm > 0 && !removed) remove_move(*engine, *tool, c, chord);
  }

  // What a changed block leaves different in the modal state is put back right after it when a
  // later block relies on it: a feed move that writes no F of its own, a G1 move that writes no
  // motion word. A block that writes its own F (the interpreter's SetFeedRate) or motion word
  // makes both programs agree again.
  bool pending_f = false, pending_g1 = false;
  int f_origin = -1, g_origin = -1;
  double f_value = 0;
  for (const CanonCommand& c : *in.commands) {
    const auto it = edits.find(c.line);
    if (it != edits.end()) {
      if (c.kind != CanonKind::Feed) continue;
      BlockEdit& e = it->second;
      if (changes_feed(e.rule)) {
        // Load blocks in a row at the same feed share the first one's F.
        if (e.rule == EditRule::LoadFeed && pending_f && !e.has_f_word &&
            edits[f_origin].rule == EditRule::LoadFeed &&
            edits[f_origin].feed_mm_min == e.feed_mm_min)
          e.modal_feed = true;
        // A raised feed still moves on G1: on its own word, or on the modal one, which it then
        // writes (or a block of its own puts back where the line would be too long).
        if (pending_g1 && !e.has_motion_word) {
          BlockEdit with_g1 = e;
          with_g1.insert_g1 = true;
          if (optimize_detail::rewrite_block(in.source->line_text(std::size_t(e.line)), in.dialect,
                                             with_g1, inch))
            e.insert_g1 = true;
          else
            edits[g_origin].restore_g1 = true;
        }
        pending_g1 = false;
        pending_f = true;
        f_origin = e.line;
        f_value = c.state.feed;
      } else {
        if (e.has_f_word) pending_f = false;
        pending_g1 = true;
        g_origin = e.line;
      }
      continue;
    }
    if (c.kind == CanonKind::SetFeedRate) pending_f = false;
    if (pending_g1 && is_move(c.kind) && c.call_line == c.line &&
        std::size_t(c.line) < in.source->lines.size() &&
        optimize_detail::writes_motion_word(in.source->line_text(std::size_t(c.line)), in.dialect))
      pending_g1 = false;
    if (is_feed_move(c.kind)) {
      if (pending_f) {
        BlockEdit& e = edits[f_origin];
        e.restore_feed = true;
        e.restore_feed_mm_min = f_value;
        pending_f = false;
      }
      if (pending_g1 && c.kind == CanonKind::Feed) {
        // The block that relies on G1 writes it where it is simple and runs once; else a block
        // of its own after the change puts G1 back (on LinuxCNC a G1 alone is a feed of no
        // length, where the tool is).
        BlockEdit restore;
        restore.line = c.line;
        restore.rule = EditRule::RestoreG1;
        restore.was_feed_mm_min = c.state.feed;
        const LineUse& u = use[c.line];
        if (u.moves == 1 && !u.elsewhere && std::size_t(c.line) < in.source->lines.size() &&
            optimize_detail::rewrite_block(in.source->line_text(std::size_t(c.line)), in.dialect,
                                           restore, inch))
          edits[c.line] = restore;
        else
          edits[g_origin].restore_g1 = true;
        pending_g1 = false;
      }
    }
  }
  for (auto& [line, edit] : edits)
    plan.edits.push_back(edit);
  return plan;
}

} // namespace ncjoule
