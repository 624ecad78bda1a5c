// The extent of a program's cuts, gathered one command at a time: what the default stock is
// sized from (StockExtent in removal.hpp), and what the guess of a stock reads (ToolCuts).
#include <algorithm>
#include <cmath>
#include <limits>

#include "ncjoule/removal.hpp"

namespace ncjoule {
namespace {

// The XY length a move travels above Z0 (beyond kZ0ToleranceMm) and at or below it: lines split
// where they cross, arcs walked along.
void add_xy_length(const CanonCommand& cmd, double& above, double& below) {
  const int pieces = cmd.kind == CanonKind::Arc ? 32 : 1;
  Pose a = cmd.start;
  for (int k = 1; k <= pieces; ++k) {
    const Pose b = k == pieces ? cmd.end : point_on_move(cmd, double(k) / pieces);
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double xy = std::sqrt(dx * dx + dy * dy);
    const double lo = std::min(a.z, b.z), hi = std::max(a.z, b.z);
    double share_below = 1;
    if (lo > kZ0ToleranceMm)
      share_below = 0;
    else if (hi > kZ0ToleranceMm)
      share_below = (kZ0ToleranceMm - lo) / (hi - lo);
    below += xy * share_below;
    above += xy * (1 - share_below);
    a = b;
  }
}

// Box3 of an extent; an empty (inverted) box where it holds nothing.
Box3 to_box(double xmin, double ymin, double zmin, double xmax, double ymax, double zmax) {
  return Box3{xmin, ymin, zmin, xmax, ymax, zmax};
}

} // namespace

void StockExtent::LevelLengths::add(double z, double length) {
  const double key = std::round(z * 1e4) * 1e-4;
  if (auto it = at.find(key); it != at.end()) {
    it->second += length;
  } else if (at.size() < kMaxLevelZs) {
    at.emplace(key, length);
  } else {
    (z > kZ0ToleranceMm ? above : below) += length;
  }
}

void StockExtent::Extent::include(const Pose& p) {
  xmin = std::min(xmin, p.x), xmax = std::max(xmax, p.x);
  ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
  zmin = std::min(zmin, p.z), zmax = std::max(zmax, p.z);
}

// An arc's sides bulge past its end points: walk along it, unless the extent holds its whole
// circle already (then no point of it can widen the extent: most arcs of a long program).
void StockExtent::include_arc(Extent& into, const CanonCommand& arc) {
  Pose low, high;
  arc_bounds(arc, low, high);
  if (into.xmin <= low.x && high.x <= into.xmax && into.ymin <= low.y && high.y <= into.ymax &&
      into.zmin <= low.z && high.z <= into.zmax)
    return;
  for (int k = 1; k < 64; ++k)
    into.include(point_on_move(arc, k / 64.0));
}

void StockExtent::Extent::include(const Extent& e) {
  xmin = std::min(xmin, e.xmin), xmax = std::max(xmax, e.xmax);
  ymin = std::min(ymin, e.ymin), ymax = std::max(ymax, e.ymax);
  zmin = std::min(zmin, e.zmin), zmax = std::max(zmax, e.zmax);
}

void StockExtent::add(const CanonCommand& cmd) {
  if (!(cmd.kind == CanonKind::Feed || cmd.kind == CanonKind::Arc)) return;
  // A level move: travels in XY and starts and ends at one Z (lines, XY arcs).
  constexpr double kSameZMm = 1e-9;
  PerTool& t = tools_[cmd.state.tool];
  const bool across_xy = travels_in_xy(cmd);
  const bool level = across_xy && std::abs(cmd.end.z - cmd.start.z) <= kSameZMm;
  if (level) {
    // Straight on from the rise (no rapid between: a rapid down beside the part and a cut in
    // from the side is not a link).
    constexpr double kSameMm = 1e-6;
    const bool continues = std::abs(cmd.start.x - t.hop_from.x) <= kSameMm &&
                           std::abs(cmd.start.y - t.hop_from.y) <= kSameMm &&
                           std::abs(cmd.start.z - t.hop_from.z) <= kSameMm;
    if (t.rose && continues && t.hop.size() < kMaxHopMoves) {
      t.hop.push_back(cmd);
      t.hop_from = cmd.end;
      return;
    }
    flush_hop(t); // a long run at one height after a rise: a waterline stepping up, cutting
    add_level(t, cmd);
    return;
  }
  if (!t.hop.empty() && cmd.end.z < cmd.start.z) {
    // Up, across, down: the moves across linked two cuts at a retract height.
    for (const CanonCommand& link : t.hop)
      ++t.above_plunge, t.length += move_length(link);
    t.hop.clear();
  }
  flush_hop(t);
  t.rose = !across_xy && cmd.end.z > cmd.start.z;
  t.hop_from = cmd.end;
  if (cmd.end.z < cmd.start.z && std::isnan(t.first_plunge_start))
    t.first_plunge_start = cmd.start.z;
  include_move(t, t.other, cmd);
  add_xy_length(cmd, t.other_above, t.other_below);
  // The path at or below Z0: lines to where they cross it, arcs walked along.
  const int pieces = cmd.kind == CanonKind::Arc ? 64 : 1;
  Pose a = cmd.start;
  for (int k = 1; k <= pieces; ++k) {
    const Pose b = k == pieces ? cmd.end : point_on_move(cmd, double(k) / pieces);
    if (a.z <= kZ0ToleranceMm) t.other_low.include(a);
    if (b.z <= kZ0ToleranceMm) t.other_low.include(b);
    if ((a.z <= kZ0ToleranceMm) != (b.z <= kZ0ToleranceMm)) {
      const double u = (kZ0ToleranceMm - a.z) / (b.z - a.z);
      Pose at = a;
      at.x = a.x + u * (b.x - a.x), at.y = a.y + u * (b.y - a.y), at.z = kZ0ToleranceMm;
      t.other_low.include(at);
    }
    a = b;
  }
  if (across_xy) t.top_travel = std::max(t.top_travel, std::max(cmd.start.z, cmd.end.z));
}

void StockExtent::flush_hop(PerTool& t) {
  std::vector<CanonCommand> held;
  held.swap(t.hop);
  t.rose = false;
  for (const CanonCommand& cmd : held)
    add_level(t, cmd);
}

void StockExtent::add_level(PerTool& t, const CanonCommand& cmd) {
  constexpr double kLevelMm = 1e-6;
  const bool plunged = !std::isnan(t.first_plunge_start);
  // After the first plunge, a level move at or above its start crosses a clearance plane.
  if (plunged && cmd.start.z >= t.first_plunge_start - kLevelMm) {
    ++t.above_plunge;
    t.length += move_length(cmd);
    return;
  }
  const double feed = cmd.state.feed_mode == FeedMode::UnitsPerMinute ? cmd.state.feed : 0.0;
  auto it = std::find_if(t.levels.begin(), t.levels.end(),
                         [&](const Level& l) { return l.feed == feed; });
  if (it == t.levels.end()) {
    // A program of many feeds: those past kMaxFeeds share the last bucket.
    if (t.levels.size() < kMaxFeeds) t.levels.push_back(Level{feed});
    it = t.levels.end() - 1;
  }
  ++(plunged ? it->moves_after : it->moves_before);
  double above = 0, below = 0;
  add_xy_length(cmd, above, below);
  (plunged ? it->length_after : it->length_before).add(cmd.start.z, above + below);
  include_move(t, plunged ? it->after : it->before, cmd);
  if (cmd.start.z <= kZ0ToleranceMm) {
    Extent& low = plunged ? it->after_low : it->before_low;
    low.include(cmd.start);
    low.include(cmd.end);
    if (cmd.kind == CanonKind::Arc) include_arc(low, cmd);
  }
}

void StockExtent::include_move(PerTool& t, Extent& into, const CanonCommand& cmd) {
  into.include(cmd.start);
  into.include(cmd.end);
  if (cmd.kind == CanonKind::Arc) include_arc(into, cmd);
  t.top_start = std::max(t.top_start, cmd.start.z);
  t.length += move_length(cmd);
  if (levels_.size() < kMaxLevels) {
    levels_.push_back(cmd.start.z);
    levels_.push_back(cmd.end.z);
    if (levels_.size() >= 2 * kMaxLevels) {
      std::sort(levels_.begin(), levels_.end());
      levels_.erase(std::unique(levels_.begin(), levels_.end()), levels_.end());
    }
  }
}

double StockExtent::cutting_feed_of(const PerTool& t) {
  // The feed the tool cuts its deepest level at: that level surely cuts.
  double deepest = std::numeric_limits<double>::infinity(), cutting_feed = 0;
  for (const Level& l : t.levels) {
    const double z = std::min(l.before.zmin, l.after.zmin);
    if (z < deepest - 1e-9)
      deepest = z, cutting_feed = l.feed;
    else if (std::abs(z - deepest) <= 1e-9)
      cutting_feed = std::max(cutting_feed, l.feed);
  }
  return cutting_feed;
}

bool StockExtent::positioning_feed(const PerTool& t, const Level& l) {
  constexpr double kHighFeedFactor = 2.5;
  const double cutting_feed = cutting_feed_of(t);
  return cutting_feed > 0 && l.feed > kHighFeedFactor * cutting_feed;
}

bool StockExtent::before_plunge_positioning(const PerTool& t, const Level& l) {
  // Before the first plunge: moves wholly at or above its start crossed a clearance plane.
  constexpr double kLevelMm = 1e-6;
  return !std::isnan(t.first_plunge_start) && l.before.zmin >= t.first_plunge_start - kLevelMm;
}

StockExtent::Extent StockExtent::cutting_levels_of(const PerTool& t, std::size_t& positioning,
                                                   bool below_z0) {
  positioning += t.above_plunge;
  Extent out;
  for (const Level& l : t.levels) {
    if (positioning_feed(t, l)) {
      positioning += l.moves_before + l.moves_after;
      continue;
    }
    out.include(below_z0 ? l.after_low : l.after);
    if (before_plunge_positioning(t, l))
      positioning += l.moves_before;
    else
      out.include(below_z0 ? l.before_low : l.before);
  }
  return out;
}

std::vector<ToolCuts> StockExtent::tool_cuts(const std::map<int, Tool>& tools) const {
  if (holds_hops()) return settled().tool_cuts(tools);
  std::vector<ToolCuts> out;
  for (const auto& [number, t] : tools_) {
    const auto tool = tools.find(number);
    if (tool == tools.end()) continue;
    std::size_t positioning = 0;
    Extent cuts = cutting_levels_of(t, positioning);
    ToolCuts c;
    c.number = number;
    c.radius = tool->second.radius();
    c.top_level = cuts.zmax;
    cuts.include(t.other);
    if (!(cuts.xmax >= cuts.xmin)) continue; // only positioning
    c.centre = to_box(cuts.xmin, cuts.ymin, cuts.zmin, cuts.xmax, cuts.ymax, cuts.zmax);
    std::size_t ignored = 0;
    Extent low = cutting_levels_of(t, ignored, true);
    low.include(t.other_low);
    c.centre_below_z0 = to_box(low.xmin, low.ymin, low.zmin, low.xmax, low.ymax, low.zmax);
    c.top_start = t.top_start;
    c.top_travel = t.top_travel;
    c.length_above_z0 = t.other_above;
    c.length_below_z0 = t.other_below;
    std::map<double, double> levels;
    auto count = [&](const LevelLengths& lengths) {
      for (const auto& [z, length] : lengths.at) {
        levels[z] += length;
        (z > kZ0ToleranceMm ? c.length_above_z0 : c.length_below_z0) += length;
        c.level_length += length;
      }
      c.length_above_z0 += lengths.above;
      c.length_below_z0 += lengths.below;
      c.level_length += lengths.above + lengths.below;
    };
    for (const Level& l : t.levels) {
      if (positioning_feed(t, l)) continue;
      count(l.length_after);
      if (!before_plunge_positioning(t, l)) count(l.length_before);
    }
    for (auto it = levels.rbegin(); it != levels.rend() && c.levels.size() < kMaxLevelZs; ++it)
      c.levels.emplace_back(it->first, it->second);
    out.push_back(std::move(c));
  }
  return out;
}

bool StockExtent::holds_hops() const {
  return std::any_of(tools_.begin(), tools_.end(),
                     [](const auto& entry) { return !entry.second.hop.empty(); });
}

StockExtent StockExtent::settled() const {
  StockExtent out = *this; // hops still held at the end: nothing came down after them
  for (auto& [number, t] : out.tools_)
    out.flush_hop(t);
  return out;
}

std::size_t StockExtent::positioning_moves() const {
  if (holds_hops()) return settled().positioning_moves();
  std::size_t positioning = 0;
  for (const auto& [number, t] : tools_)
    cutting_levels_of(t, positioning);
  return positioning;
}

std::optional<Box3> StockExtent::box(const std::map<int, Tool>& tools) const {
  if (holds_hops()) return settled().box(tools);
  constexpr double inf = std::numeric_limits<double>::infinity();
  Box3 b{inf, inf, inf, -inf, -inf, -inf};
  double top_level = -inf;  // highest Z of a level move that cuts
  double top_start = -inf;  // highest Z a cutting move starts from (drilling-only programs)
  double top_travel = -inf; // highest Z of a cutting move that travels in XY (ramps, helices)
  bool any = false;
  for (const auto& [number, t] : tools_) {
    const auto tool = tools.find(number);
    if (tool == tools.end()) continue; // moves of an unknown tool are left out
    const double r = tool->second.radius();
    std::size_t positioning = 0;
    Extent cuts = cutting_levels_of(t, positioning);
    top_level = std::max(top_level, cuts.zmax);
    cuts.include(t.other);
    if (!(cuts.xmax >= cuts.xmin)) continue; // only positioning
    any = true;
    b.xmin = std::min(b.xmin, cuts.xmin - r), b.xmax = std::max(b.xmax, cuts.xmax + r);
    b.ymin = std::min(b.ymin, cuts.ymin - r), b.ymax = std::max(b.ymax, cuts.ymax + r);
    b.zmin = std::min(b.zmin, cuts.zmin);
    top_start = std::max(top_start, t.top_start);
    top_travel = std::max(top_travel, t.top_travel);
  }
  if (!any) return std::nullopt;
  b.zmax = top_level > -inf ? top_level : top_start;
  // Every level move at the bottom (a helix or ramp down to one depth, then the cut): the ramps
  // start at the top of the stock.
  if (!(b.zmax > b.zmin) && top_travel > b.zmin) b.zmax = top_travel;
  return b; // may have no height (every level move at one Z): the caller says so
}

std::vector<double> StockExtent::cutting_levels() const {
  if (holds_hops()) return settled().cutting_levels();
  std::vector<double> levels = levels_;
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  return levels;
}

double StockExtent::cutting_length(int number, double top_z) const {
  if (holds_hops()) return settled().cutting_length(number, top_z);
  const auto it = tools_.find(number);
  if (it == tools_.end()) return 0.0;
  double air = 0;
  auto add_air = [&](const LevelLengths& lengths) {
    for (const auto& [z, length] : lengths.at)
      if (z >= top_z - kZ0ToleranceMm) air += length;
  };
  for (const Level& l : it->second.levels)
    add_air(l.length_before), add_air(l.length_after);
  return std::max(0.0, it->second.length - air);
}

std::optional<Box3> default_stock_box(const std::vector<CanonCommand>& commands,
                                      const Timeline& timeline, const std::map<int, Tool>& tools) {
  StockExtent extent;
  for (const TimedCommand& tc : timeline.commands)
    if (tc.command < commands.size()) extent.add(commands[tc.command]);
  return extent.box(tools);
}

} // namespace ncjoule
