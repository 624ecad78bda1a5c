// What stock the user asked for, and the default: the bounding box of the cutting moves.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>

#include "ncjoule/removal.hpp"
#include "ncjoule/text.hpp"

namespace ncjoule {

std::optional<std::pair<double, LengthUnit>> parse_length(std::string_view text) {
  const std::string_view t = trim(text);
  LengthUnit unit = LengthUnit::Program;
  std::string_view number = t;
  const std::string low = to_lower(t);
  for (const auto& [suffix, u] : {std::pair<std::string_view, LengthUnit>{"inch", LengthUnit::Inch},
                                  {"in", LengthUnit::Inch},
                                  {"\"", LengthUnit::Inch},
                                  {"mm", LengthUnit::Mm}}) {
    if (low.size() > suffix.size() &&
        low.compare(low.size() - suffix.size(), suffix.size(), suffix.data(), suffix.size()) == 0) {
      unit = u;
      number = trim(t.substr(0, t.size() - suffix.size()));
      break;
    }
  }
  const std::optional<double> value = parse_number(number);
  if (!value) return std::nullopt;
  return std::pair{*value, unit};
}

std::optional<StockSpec> parse_stock_spec(std::string_view text,
                                          std::vector<Diagnostic>* diagnostics,
                                          const TextOrigin& origin, LengthUnit units) {
  // A problem with the part of `text` at `where`, or with the whole text.
  auto fail = [&](std::string message, std::string_view where = {}) -> std::optional<StockSpec> {
    const std::size_t offset = where.data() ? std::size_t(where.data() - text.data()) : 0;
    if (diagnostics) diagnostics->push_back(origin.at(offset, std::move(message)));
    return std::nullopt;
  };
  StockSpec spec;
  spec.origin = origin.file;
  const std::string low = to_lower(text);
  if (low.empty() || low == "auto" || low == "default") return spec;
  if (low.rfind("box:", 0) == 0) {
    double v[6];
    std::string_view rest = text.substr(4);
    for (int k = 0; k < 6; ++k) {
      const std::size_t comma = rest.find(',');
      if ((k < 5) != (comma != std::string_view::npos))
        return fail("stock box needs six numbers: box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (each may "
                    "carry a unit, mm or in; without one, the program's units)",
                    rest);
      const std::string_view field = rest.substr(0, comma);
      const auto length = parse_length(field);
      if (!length)
        return fail("stock box value '" + std::string(field) +
                        "' is not a number (with an optional unit: mm, in)",
                    field);
      v[k] = length->first;
      spec.box_units[std::size_t(k)] =
          length->second == LengthUnit::Program ? units : length->second;
      rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    }
    spec.kind = StockSpec::Kind::Box;
    spec.box = Box3{v[0], v[1], v[2], v[3], v[4], v[5]};
    // Compared in one unit: a box written in two units ("0,0,-1in,100mm,...") is checked so.
    const StockSpec mm = spec.in_mm(false);
    if (mm.box.empty()) return fail("stock box has a maximum not above its minimum");
    return spec;
  }
  if (low.size() > 4 && low.compare(low.size() - 4, 4, ".stl") == 0) {
    spec.kind = StockSpec::Kind::Stl;
    spec.stl_path = std::string(text);
    spec.stl_units = units;
    return spec;
  }
  return fail("stock '" + std::string(text) +
              "' is neither box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX nor an .stl file");
}

StockSpec StockSpec::in_mm(bool program_inch) const {
  auto scale = [&](LengthUnit u) {
    const bool inch = u == LengthUnit::Inch || (u == LengthUnit::Program && program_inch);
    return inch ? 25.4 : 1.0;
  };
  StockSpec out = *this;
  double* values[6] = {&out.box.xmin, &out.box.ymin, &out.box.zmin,
                       &out.box.xmax, &out.box.ymax, &out.box.zmax};
  for (std::size_t k = 0; k < 6; ++k) {
    *values[k] *= scale(box_units[k]);
    out.box_units[k] = LengthUnit::Mm;
  }
  if (kind == Kind::Stl && scale(stl_units) != 1.0)
    out.stl_units = LengthUnit::Inch;
  else
    out.stl_units = LengthUnit::Mm;
  return out;
}

bool StockSpec::follows_program_units() const {
  if (kind == Kind::Stl) return stl_units == LengthUnit::Program;
  if (kind != Kind::Box) return false;
  // A 0 is 0 in any unit: "box:0,0,-1in,4in,3in,0" is all in inches.
  const double values[6] = {box.xmin, box.ymin, box.zmin, box.xmax, box.ymax, box.zmax};
  for (std::size_t k = 0; k < 6; ++k)
    if (box_units[k] == LengthUnit::Program && values[k] != 0) return true;
  return false;
}

Box3 place_sized_stock(const Box3& size, const std::optional<Box3>& cuts, std::string& how) {
  const double extent[3] = {size.xmax - size.xmin, size.ymax - size.ymin, size.zmax - size.zmin};
  // How much of [lo, hi] lies outside [a, b].
  const auto outside = [](double lo, double hi, double a, double b) {
    return std::max(0.0, a - lo) + std::max(0.0, hi - b);
  };
  double lo[3], hi[3];
  how.clear();
  static const char* const names[] = {"X", "Y"};
  for (int i = 0; i < 2; ++i) {
    const double w = extent[i];
    const double starts[3] = {0, -w / 2, -w};
    static const char* const placed[] = {" from 0", " centred", " up to 0"};
    int best = 0;
    if (cuts) {
      const double c_lo = i == 0 ? cuts->xmin : cuts->ymin, c_hi = i == 0 ? cuts->xmax : cuts->ymax;
      double least = outside(c_lo, c_hi, starts[0], starts[0] + w);
      for (int k = 1; k < 3; ++k)
        if (const double o = outside(c_lo, c_hi, starts[k], starts[k] + w); o < least - 1e-9)
          least = o, best = k;
    }
    lo[i] = starts[best], hi[i] = starts[best] + w;
    how += std::string(i ? ", " : "") + names[i] + placed[best];
  }
  const double h = extent[2];
  const bool above = cuts && cuts->zmin >= 0; // nothing cuts below Z0: Z0 is the stock's bottom
  lo[2] = above ? 0 : -h, hi[2] = above ? h : 0;
  how += above ? ", bottom at Z0" : ", top at Z0";
  return Box3{lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]};
}

std::string stock_mismatch(const Box3& stock, const Box3& cuts, const StockSpec& spec,
                           bool program_inch) {
  const double stock_size = std::max(stock.xmax - stock.xmin, stock.ymax - stock.ymin);
  const double cut_size = std::max(cuts.xmax - cuts.xmin, cuts.ymax - cuts.ymin);
  // Seen from above: a program that cuts above its stock only (air) is another matter.
  const bool overlaps = stock.xmin < cuts.xmax && cuts.xmin < stock.xmax &&
                        stock.ymin < cuts.ymax && cuts.ymin < stock.ymax;
  constexpr double kFactor = 20;
  const double ratio = cut_size > 0 ? stock_size / cut_size : 1;
  if (overlaps && ratio <= kFactor && ratio >= 1 / kFactor) return {};
  char what[200];
  if (ratio > kFactor || ratio < 1 / kFactor)
    std::snprintf(what, sizeof what,
                  "the stock is %.3g times %s than the program's cuts (%.1f mm across, the cuts "
                  "%.1f mm)",
                  ratio > 1 ? ratio : 1 / ratio, ratio > 1 ? "larger" : "smaller", stock_size,
                  cut_size);
  else
    std::snprintf(what, sizeof what,
                  "the stock (X%.1f..%.1f Y%.1f..%.1f mm) is beside the program's cuts "
                  "(X%.1f..%.1f Y%.1f..%.1f mm), not under them",
                  stock.xmin, stock.xmax, stock.ymin, stock.ymax, cuts.xmin, cuts.xmax, cuts.ymin,
                  cuts.ymax);
  std::string out = what;
  if (spec.follows_program_units())
    out += std::string(": a mix-up of units? Values written without a unit are read in the "
                       "program's units (") +
           (program_inch ? "inches, G20" : "mm") +
           "); write 'in' or 'mm' after a number (box:0,0,-1in,4in,3in,0)";
  else
    out += ": a mix-up of units, or a stock for another work offset?";
  return out;
}

void StockExtent::Extent::include(const Pose& p) {
  xmin = std::min(xmin, p.x), xmax = std::max(xmax, p.x);
  ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
  zmin = std::min(zmin, p.z), zmax = std::max(zmax, p.z);
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
  include_move(t, plunged ? it->after : it->before, cmd);
}

void StockExtent::include_move(PerTool& t, Extent& into, const CanonCommand& cmd) {
  into.include(cmd.start);
  into.include(cmd.end);
  // An arc's sides bulge past its end points: walk along it.
  if (cmd.kind == CanonKind::Arc)
    for (int k = 1; k < 64; ++k)
      into.include(point_on_move(cmd, k / 64.0));
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

StockExtent::Extent StockExtent::cutting_levels_of(const PerTool& t, std::size_t& positioning) {
  positioning += t.above_plunge;
  Extent out;
  if (t.levels.empty()) return out;
  // The feed the tool cuts its deepest level at: that level surely cuts.
  double deepest = std::numeric_limits<double>::infinity(), cutting_feed = 0;
  for (const Level& l : t.levels) {
    const double z = std::min(l.before.zmin, l.after.zmin);
    if (z < deepest - 1e-9)
      deepest = z, cutting_feed = l.feed;
    else if (std::abs(z - deepest) <= 1e-9)
      cutting_feed = std::max(cutting_feed, l.feed);
  }
  constexpr double kHighFeedFactor = 2.5;
  constexpr double kLevelMm = 1e-6;
  for (const Level& l : t.levels) {
    if (cutting_feed > 0 && l.feed > kHighFeedFactor * cutting_feed) {
      positioning += l.moves_before + l.moves_after;
      continue;
    }
    out.include(l.after);
    // Before the first plunge: moves wholly at or above its start crossed a clearance plane.
    if (!std::isnan(t.first_plunge_start) && l.before.zmin >= t.first_plunge_start - kLevelMm)
      positioning += l.moves_before;
    else
      out.include(l.before);
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

double StockExtent::cutting_length(int number) const {
  if (holds_hops()) return settled().cutting_length(number);
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
