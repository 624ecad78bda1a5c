// What stock the user asked for, and the default: the bounding box of the cutting moves.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>

#include "ncjoule/removal.hpp"
#include "ncjoule/text.hpp"

namespace ncjoule {
std::optional<StockSpec> parse_stock_spec(std::string_view text,
                                          std::vector<Diagnostic>* diagnostics,
                                          const TextOrigin& origin) {
  // A problem with the part of `text` at `where`, or with the whole text.
  auto fail = [&](std::string message, std::string_view where = {}) -> std::optional<StockSpec> {
    const std::size_t offset = where.data() ? std::size_t(where.data() - text.data()) : 0;
    if (diagnostics) diagnostics->push_back(origin.at(offset, std::move(message)));
    return std::nullopt;
  };
  StockSpec spec;
  const std::string low = to_lower(text);
  if (low.empty() || low == "auto" || low == "default") return spec;
  if (low.rfind("box:", 0) == 0) {
    double v[6];
    std::string_view rest = text.substr(4);
    for (int k = 0; k < 6; ++k) {
      const std::size_t comma = rest.find(',');
      if ((k < 5) != (comma != std::string_view::npos))
        return fail("stock box needs six numbers: box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (mm)", rest);
      const std::string_view field = rest.substr(0, comma);
      const std::optional<double> value = parse_number(field);
      if (!value)
        return fail("stock box value '" + std::string(field) + "' is not a number", field);
      v[k] = *value;
      rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    }
    spec.kind = StockSpec::Kind::Box;
    spec.box = Box3{v[0], v[1], v[2], v[3], v[4], v[5]};
    if (spec.box.empty()) return fail("stock box has a maximum not above its minimum");
    return spec;
  }
  if (low.size() > 4 && low.compare(low.size() - 4, 4, ".stl") == 0) {
    spec.kind = StockSpec::Kind::Stl;
    spec.stl_path = std::string(text);
    return spec;
  }
  return fail("stock '" + std::string(text) +
              "' is neither box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX nor an .stl file");
}

void StockExtent::add(const CanonCommand& cmd) {
  if (!(cmd.kind == CanonKind::Feed || cmd.kind == CanonKind::Arc)) return;
  // A level move: travels in XY and starts and ends at one Z (lines, XY arcs).
  constexpr double kSameZMm = 1e-9;
  PerTool& t = tools_[cmd.state.tool];
  auto include = [&](const Pose& p) {
    t.xmin = std::min(t.xmin, p.x), t.xmax = std::max(t.xmax, p.x);
    t.ymin = std::min(t.ymin, p.y), t.ymax = std::max(t.ymax, p.y);
    t.zmin = std::min(t.zmin, p.z);
  };
  include(cmd.start);
  include(cmd.end);
  // An arc's sides bulge past its end points: walk along it.
  if (cmd.kind == CanonKind::Arc)
    for (int k = 1; k < 64; ++k)
      include(point_on_move(cmd, k / 64.0));
  t.top_start = std::max(t.top_start, cmd.start.z);
  t.length += move_length(cmd);
  const bool across_xy = travels_in_xy(cmd);
  if (across_xy && std::abs(cmd.end.z - cmd.start.z) <= kSameZMm)
    t.top_level = std::max(t.top_level, cmd.start.z);
  if (across_xy) t.top_travel = std::max(t.top_travel, std::max(cmd.start.z, cmd.end.z));
  if (levels_.size() < kMaxLevels) {
    levels_.push_back(cmd.start.z);
    levels_.push_back(cmd.end.z);
    if (levels_.size() >= 2 * kMaxLevels) {
      std::sort(levels_.begin(), levels_.end());
      levels_.erase(std::unique(levels_.begin(), levels_.end()), levels_.end());
    }
  }
}

std::optional<Box3> StockExtent::box(const std::map<int, Tool>& tools) const {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Box3 b{inf, inf, inf, -inf, -inf, -inf};
  double top_level = -inf;  // highest Z of a level move
  double top_start = -inf;  // highest Z a cutting move starts from (drilling-only programs)
  double top_travel = -inf; // highest Z of a cutting move that travels in XY (ramps, helices)
  bool any = false;
  for (const auto& [number, t] : tools_) {
    const auto tool = tools.find(number);
    if (tool == tools.end()) continue; // moves of an unknown tool are left out
    const double r = tool->second.radius();
    any = true;
    b.xmin = std::min(b.xmin, t.xmin - r), b.xmax = std::max(b.xmax, t.xmax + r);
    b.ymin = std::min(b.ymin, t.ymin - r), b.ymax = std::max(b.ymax, t.ymax + r);
    b.zmin = std::min(b.zmin, t.zmin);
    top_level = std::max(top_level, t.top_level);
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
  std::vector<double> levels = levels_;
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  return levels;
}

double StockExtent::cutting_length(int number) const {
  const auto it = tools_.find(number);
  return it == tools_.end() ? 0.0 : it->second.length;
}

std::optional<Box3> default_stock_box(const std::vector<CanonCommand>& commands,
                                      const Timeline& timeline, const std::map<int, Tool>& tools) {
  StockExtent extent;
  for (const TimedCommand& tc : timeline.commands)
    if (tc.command < commands.size()) extent.add(commands[tc.command]);
  return extent.box(tools);
}

} // namespace ncjoule
