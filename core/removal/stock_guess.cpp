// The stock a machinist would take when nothing states it: rules read off the cuts of a setup
// (removal.hpp, guess_stock; docs/removal.md, "The guessed stock").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "ncjoule/removal.hpp"

namespace ncjoule {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Cutting above Z0 that does not move the top off Z0: ramps, helical entries and lead-outs that
// start above the stock, and a program's odd pass in air. Past this share of the cutting travel,
// the program cuts above Z0 (its Z0 is on the table or below the stock's top).
constexpr double kAboveZ0Share = 0.1;
// What a face at Z0 is taken to remove when it says nothing else: a usual facing allowance.
constexpr double kFacingAllowanceMm = 0.5, kFacingAllowanceIn = 0.02;
// A facing tool cuts this share of its travel across XY at one or two levels...
constexpr double kFacingLevelShare = 0.9;
// ... and its passes cover the paths of the other tools, to this much (mm).
constexpr double kCoverSlackMm = 1.0;

std::string mm(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", v);
  return text;
}

double xy_area(const Box3& b) {
  return std::max(0.0, b.xmax - b.xmin) * std::max(0.0, b.ymax - b.ymin);
}

Box3 unite(const Box3& a, const Box3& b) {
  return Box3{std::min(a.xmin, b.xmin), std::min(a.ymin, b.ymin), std::min(a.zmin, b.zmin),
              std::max(a.xmax, b.xmax), std::max(a.ymax, b.ymax), std::max(a.zmax, b.zmax)};
}

const Box3 kNothing{kInf, kInf, kInf, -kInf, -kInf, -kInf};

// Below this share of its extent swept in one layer, a tool cuts lines (a contour, an outline, an
// engraving) rather than an area.
constexpr double kAreaCoverage = 0.5;

// The part of a tool's path that bounds the stock: with the top at Z0, its path at or below Z0
// (a lead-in or a ramp from above the stock says nothing of where the stock is).
Box3 path_of(const ToolCuts& t, bool z0_top) {
  const Box3& low = t.centre_below_z0;
  return z0_top && low.xmax >= low.xmin && low.ymax >= low.ymin ? low : t.centre;
}

// How much of the area of its path's extent a tool sweeps in its busiest layer: a raster, a
// pocket or a facing pass covers it (1 or more), a contour or an engraving only a band along it.
double coverage(const ToolCuts& t, const Box3& path) {
  const double area = xy_area(path);
  if (!(area > 0)) return 0;
  double busiest = 0;
  for (const auto& [z, length] : t.levels)
    busiest = std::max(busiest, length);
  const double off_level = std::max(0.0, t.length_above_z0 + t.length_below_z0 - t.level_length);
  return std::max(busiest, off_level) * 2 * t.radius / area;
}

// Whether a tool faces: nearly all its travel at one or two levels at the top of the setup's
// cuts, its passes (widened by its radius) covering every other tool's path. A face mill runs
// past the part on every side, so its passes say where the stock's top is, not its outline.
bool faces(std::size_t k, const std::vector<ToolCuts>& all, bool z0_top) {
  const ToolCuts& t = all[k];
  const double travel = t.length_above_z0 + t.length_below_z0;
  if (t.levels.empty() || !(travel > 0) || t.level_length < kFacingLevelShare * travel)
    return false;
  const double top_two = t.levels[0].second + (t.levels.size() > 1 ? t.levels[1].second : 0.0);
  if (top_two < kFacingLevelShare * t.level_length) return false;
  const Box3 path = path_of(t, z0_top);
  const Box3 swept{path.xmin - t.radius, path.ymin - t.radius, 0,
                   path.xmax + t.radius, path.ymax + t.radius, 0};
  bool others = false;
  for (std::size_t j = 0; j < all.size(); ++j) {
    if (j == k) continue;
    const ToolCuts& o = all[j];
    others = true;
    if (o.top_level > t.levels[0].first + kZ0ToleranceMm) return false; // cuts above the face
    // The other tool's path runs up to its radius outside the part.
    const Box3 p = path_of(o, z0_top);
    const double slack = kCoverSlackMm + o.radius;
    if (p.xmin < swept.xmin - slack || p.xmax > swept.xmax + slack || p.ymin < swept.ymin - slack ||
        p.ymax > swept.ymax + slack)
      return false;
  }
  return others;
}

// Whether Z0 is the stock's top: the cuts travel at or below it, but for entries from above
// (ramps, helices, lead-ins) and the odd pass in air. A drilling program travels nowhere across
// XY while cutting: its plunges tell, when they reach below Z0.
bool top_at_z0(const std::vector<ToolCuts>& cuts, double bottom) {
  double above = 0, below = 0;
  for (const ToolCuts& c : cuts)
    above += c.length_above_z0, below += c.length_below_z0;
  const double travel = above + below;
  return travel > 0 ? below > 0 && above <= kAboveZ0Share * travel : bottom < -kZ0ToleranceMm;
}

} // namespace

std::optional<StockGuess> guess_stock(const std::vector<ToolCuts>& cuts, bool program_inch,
                                      const Box3* first_setup) {
  if (cuts.empty()) return std::nullopt;
  StockGuess guess;

  // Bottom: the lowest cut.
  double bottom = kInf;
  for (const ToolCuts& c : cuts)
    bottom = std::min(bottom, c.centre.zmin);

  const bool z0_top = top_at_z0(cuts, bottom);
  std::vector<bool> facing(cuts.size(), false);
  for (std::size_t k = 0; k < cuts.size(); ++k)
    facing[k] = faces(k, cuts, z0_top);
  const bool all_face = std::all_of(facing.begin(), facing.end(), [](bool f) { return f; });

  // Outline: where the tools cut; a face mill's passes only where nothing else cuts.
  Box3 outline = kNothing;
  std::string facing_tools, line_tools;
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    const std::string name = "T" + std::to_string(cuts[k].number);
    if (facing[k]) facing_tools += (facing_tools.empty() ? "" : ", ") + name;
    if (facing[k] && !all_face) continue;
    // A tool that cuts lines cuts inside the stock: its edge, not its centre, is within it. One
    // that clears an area runs its passes to the stock's edge.
    Box3 path = path_of(cuts[k], z0_top);
    if (coverage(cuts[k], path) < kAreaCoverage) {
      const double r = cuts[k].radius;
      path.xmin -= r, path.ymin -= r, path.xmax += r, path.ymax += r;
      line_tools += (line_tools.empty() ? "" : ", ") + name;
    }
    outline = unite(outline, path);
  }
  guess.box = outline;
  guess.box.zmin = bottom;
  std::string rule = "outline: the extent of the tool paths";
  if (z0_top) rule += " below Z0";
  if (!line_tools.empty())
    rule += ", to the edge of those that cut lines rather than areas (" + line_tools + ")";
  if (!facing_tools.empty() && !all_face)
    rule += ", but for the facing passes of " + facing_tools + ", which run past the part";
  guess.rules.push_back(rule);

  // Top.
  double top = 0;
  if (z0_top) {
    guess.rules.push_back("top: Z0, since the cuts run at or below it (a post puts Z0 on the "
                          "stock's top)");
  } else {
    // Z0 is not the top: the highest level a cut travels at (CAM clears level by level; ramps
    // and plunges start above the material), else where the cuts start (drilling), else where
    // they travel.
    double top_level = -kInf, top_start = -kInf, top_travel = -kInf;
    for (const ToolCuts& c : cuts) {
      top_level = std::max(top_level, c.top_level);
      top_start = std::max(top_start, c.top_start);
      top_travel = std::max(top_travel, c.top_travel);
    }
    top = top_level > -kInf ? top_level : top_start;
    if (!(top > bottom) && top_travel > bottom) top = top_travel;
    guess.rules.push_back("top: " + mm(top) +
                          ", the highest level a cut travels at (the program cuts above Z0)");
  }
  // A face at the top (at Z0 or above it) has material above it: one facing step.
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    const auto& levels = cuts[k].levels;
    if (!facing[k] || levels.empty() || levels[0].first < top - kZ0ToleranceMm) continue;
    double step = program_inch ? kFacingAllowanceIn * 25.4 : kFacingAllowanceMm;
    if (levels.size() > 1 && levels[0].first - levels[1].first <= 5 * step)
      step = levels[0].first - levels[1].first;
    if (levels[0].first + step > top) {
      top = levels[0].first + step;
      guess.rules.back() = "top: " + mm(top) + ", one facing step above the face of T" +
                           std::to_string(cuts[k].number) + " at Z" + mm(levels[0].first);
    }
  }
  guess.box.zmax = top;

  // A later setup cuts what the first one left: no wider, no longer, no taller.
  if (first_setup && !first_setup->empty()) {
    const Box3& f = *first_setup;
    bool bounded = false;
    auto clamp = [&](double& lo, double& hi, double size) {
      if (hi - lo <= size) return;
      const double centre = (lo + hi) / 2;
      lo = centre - size / 2, hi = centre + size / 2;
      bounded = true;
    };
    clamp(guess.box.xmin, guess.box.xmax, f.xmax - f.xmin);
    clamp(guess.box.ymin, guess.box.ymax, f.ymax - f.ymin);
    if (guess.box.zmax - guess.box.zmin > f.zmax - f.zmin) {
      guess.box.zmin = guess.box.zmax - (f.zmax - f.zmin);
      bounded = true;
    }
    if (bounded)
      guess.rules.push_back("no larger than the first setup's stock (what it left is cut here)");
  }
  return guess;
}

} // namespace ncjoule
