// What stock the user asked for, and the default: the bounding box of the cutting moves.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>

#include "ncjoule/removal.hpp"

namespace ncjoule {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool parse_number(std::string_view text, double& value) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())))
    text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
    text.remove_suffix(1);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

bool is_cutting(CanonKind kind) {
  return kind == CanonKind::Feed || kind == CanonKind::Arc;
}

} // namespace

std::optional<StockSpec> parse_stock_spec(std::string_view text, std::string* error) {
  auto fail = [&](std::string message) -> std::optional<StockSpec> {
    if (error) *error = std::move(message);
    return std::nullopt;
  };
  StockSpec spec;
  const std::string low = lower(text);
  if (low.empty() || low == "auto" || low == "default") return spec;
  if (low.rfind("box:", 0) == 0) {
    double v[6];
    std::string_view rest = text.substr(4);
    for (int k = 0; k < 6; ++k) {
      const std::size_t comma = rest.find(',');
      if ((k < 5) != (comma != std::string_view::npos))
        return fail("stock box needs six numbers: box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (mm)");
      const std::string_view field = rest.substr(0, comma);
      if (!parse_number(field, v[k]))
        return fail("stock box value '" + std::string(field) + "' is not a number");
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

std::optional<Box3> default_stock_box(const std::vector<CanonCommand>& commands,
                                      const Timeline& timeline, const std::map<int, Tool>& tools) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  // A level move: travels in XY and starts and ends at one Z (lines, XY arcs).
  constexpr double kMinXyMm = 1e-6, kSameZMm = 1e-9;
  Box3 b{inf, inf, inf, -inf, -inf, -inf};
  double top_level = -inf; // highest Z of a level move
  double top_start = -inf; // highest Z a cutting move starts from (drilling-only programs)
  bool any = false;
  auto include = [&](const Pose& p, double radius) {
    b.xmin = std::min(b.xmin, p.x - radius), b.xmax = std::max(b.xmax, p.x + radius);
    b.ymin = std::min(b.ymin, p.y - radius), b.ymax = std::max(b.ymax, p.y + radius);
    b.zmin = std::min(b.zmin, p.z);
  };
  for (const TimedCommand& tc : timeline.commands) {
    if (tc.command >= commands.size()) continue;
    const CanonCommand& cmd = commands[tc.command];
    if (!is_cutting(cmd.kind)) continue;
    const auto tool = tools.find(cmd.state.tool);
    if (tool == tools.end()) continue;
    const double r = tool->second.radius();
    any = true;
    include(cmd.start, r);
    include(cmd.end, r);
    for (const MotionSample& s : tc.samples)
      include(s.position, r);
    // An arc's sides bulge past its end points: without samples, walk along it.
    if (cmd.kind == CanonKind::Arc && tc.samples.size() < 3)
      for (int k = 1; k < 64; ++k)
        include(point_on_move(cmd, k / 64.0), r);
    top_start = std::max(top_start, cmd.start.z);
    const bool travels_in_xy =
        cmd.kind == CanonKind::Arc ||
        std::hypot(cmd.end.x - cmd.start.x, cmd.end.y - cmd.start.y) > kMinXyMm;
    if (travels_in_xy && std::abs(cmd.end.z - cmd.start.z) <= kSameZMm)
      top_level = std::max(top_level, cmd.start.z);
  }
  if (!any) return std::nullopt;
  b.zmax = top_level > -inf ? top_level : top_start;
  return b; // may have no height (every level move at one Z): the caller says so
}

} // namespace ncjoule
