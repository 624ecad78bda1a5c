// The stock blocks of a program's header that span lines or are code, not a comment: Vectric's
// Material Size block and Sinumerik's WORKPIECE blank (cam_stock.hpp; docs/stock.md shows each
// with the posts that write it).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "cam_stock.hpp"
#include "ncjoule/text.hpp"

namespace ncjoule::estimate_detail {
namespace {

bool is_blank(char c) {
  return c == ' ' || c == '\t';
}

// The length after `key` ("X") followed by blanks and '=' or ':' in `low` (lower-cased `text`);
// the first such key whose value reads.
std::optional<std::pair<double, LengthUnit>> keyed_length(std::string_view text,
                                                          const std::string& low, char key) {
  for (std::size_t at = 0; (at = low.find(key, at)) != std::string::npos; ++at) {
    // The key stands alone: not a letter of a word ("max", "box").
    if (at > 0 && std::isalpha(static_cast<unsigned char>(low[at - 1]))) continue;
    std::size_t i = at + 1;
    while (i < low.size() && is_blank(low[i]))
      ++i;
    if (i >= low.size() || (low[i] != '=' && low[i] != ':')) continue;
    ++i;
    while (i < low.size() && is_blank(low[i]))
      ++i;
    std::size_t end = i;
    while (end < low.size() && !is_blank(low[end]) && low[end] != ',' && low[end] != ';' &&
           low[end] != ')' &&
           !(low[end] == 'x' && end > i && std::isdigit(static_cast<unsigned char>(low[end - 1]))))
      ++end;
    if (auto length = parse_length(text.substr(i, end - i))) return length;
  }
  return std::nullopt;
}

} // namespace

std::optional<std::array<std::pair<double, LengthUnit>, 3>> xyz_sizes(std::string_view text) {
  const std::string low = to_lower(text);
  std::array<std::pair<double, LengthUnit>, 3> out;
  const char keys[3] = {'x', 'y', 'z'};
  for (int k = 0; k < 3; ++k) {
    auto v = keyed_length(text, low, keys[k]);
    if (!v || !(v->first > 0) || !std::isfinite(v->first)) return std::nullopt;
    out[k] = *v;
  }
  return out;
}

std::optional<VectricOrigin> vectric_origin(std::string_view comment) {
  const std::string low = to_lower(trim(comment));
  const std::size_t eq = low.find('=');
  if (eq == std::string::npos) return std::nullopt;
  const std::string key = std::string(trim(std::string_view(low).substr(0, eq)));
  const std::string value = std::string(trim(std::string_view(low).substr(eq + 1)));
  VectricOrigin o;
  if (key == "z origin for material" || key == "z zero position" || key == "z origin") {
    o.is_z = true;
    if (value.find("surface") != std::string::npos && value.find("table") == std::string::npos)
      o.z = VectricOrigin::Z::Top;
    else if (value.find("bed") != std::string::npos || value.find("table") != std::string::npos ||
             value.find("bottom") != std::string::npos)
      o.z = VectricOrigin::Z::Bottom;
    else if (value.find("cent") != std::string::npos)
      o.z = VectricOrigin::Z::Centre;
    else
      return std::nullopt;
    return o;
  }
  if (key == "xy origin for material" || key == "xy datum position" || key == "xy origin") {
    const bool top = value.find("top") != std::string::npos,
               bottom = value.find("bottom") != std::string::npos,
               left = value.find("left") != std::string::npos,
               right = value.find("right") != std::string::npos;
    if ((top || bottom) && (left || right)) {
      o.x = left ? VectricOrigin::Side::Low : VectricOrigin::Side::High;
      o.y = bottom ? VectricOrigin::Side::Low : VectricOrigin::Side::High;
    } else if (value.find("cent") != std::string::npos) {
      o.x = o.y = VectricOrigin::Side::Centre;
    } else {
      return std::nullopt;
    }
    return o;
  }
  return std::nullopt;
}

std::optional<StockSpec>
vectric_material_box(const std::array<std::pair<double, LengthUnit>, 3>& size,
                     const std::optional<VectricOrigin>& xy,
                     const std::optional<VectricOrigin>& z) {
  StockSpec spec;
  spec.kind = StockSpec::Kind::Box;
  spec.stated_by_program = true;
  for (std::size_t i = 0; i < 3; ++i)
    spec.box_units[i] = spec.box_units[i + 3] = size[i].second;
  const double sx = size[0].first, sy = size[1].first, sz = size[2].first;
  if (!xy || !z) {
    spec.size_only = true;
    spec.box = Box3{0, 0, 0, sx, sy, sz};
    return spec;
  }
  auto span = [](VectricOrigin::Side side, double length, double& low, double& high) {
    low = side == VectricOrigin::Side::Low    ? 0
          : side == VectricOrigin::Side::High ? -length
                                              : -length / 2;
    high = low + length;
  };
  span(xy->x, sx, spec.box.xmin, spec.box.xmax);
  span(xy->y, sy, spec.box.ymin, spec.box.ymax);
  spec.box.zmin = z->z == VectricOrigin::Z::Top      ? -sz
                  : z->z == VectricOrigin::Z::Bottom ? 0
                                                     : -sz / 2;
  spec.box.zmax = spec.box.zmin + sz;
  return spec;
}

std::optional<StockSpec> sinumerik_workpiece(std::string_view code, std::string& problem,
                                             std::size_t& problem_column) {
  const std::string low = to_lower(code);
  const std::size_t at = low.find("workpiece(");
  if (at == std::string::npos) return std::nullopt;
  problem_column = at;
  // The arguments, split at commas outside quotes.
  std::vector<std::string_view> args;
  std::size_t begin = at + 10, i = begin;
  bool quoted = false, closed = false;
  for (; i < code.size(); ++i) {
    const char c = code[i];
    if (c == '"')
      quoted = !quoted;
    else if (!quoted && (c == ',' || c == ')')) {
      args.push_back(trim(code.substr(begin, i - begin)));
      begin = i + 1;
      if (c == ')') {
        closed = true;
        break;
      }
    }
  }
  if (!closed) return problem = "WORKPIECE( is not closed", std::nullopt;
  auto unquoted = [](std::string_view a) {
    return a.size() >= 2 && a.front() == '"' && a.back() == '"' ? a.substr(1, a.size() - 2) : a;
  };
  if (args.size() < 4)
    return problem = "WORKPIECE has no blank type (its 4th argument)", std::nullopt;
  const std::string type = to_lower(unquoted(args[3]));
  // The numbers after the type: bits, Z0, Z1, ZB, then the type's sizes; an empty one is 0.
  std::vector<double> v;
  for (std::size_t k = 4; k < args.size(); ++k) {
    if (args[k].empty()) {
      v.push_back(0);
      continue;
    }
    const auto n = parse_number(args[k]);
    if (!n || !std::isfinite(*n))
      return problem = "WORKPIECE argument " + std::to_string(k + 1) + " '" + std::string(args[k]) +
                       "' is not a number",
             std::nullopt;
    v.push_back(*n);
  }
  const std::size_t need = type == "box" ? 8 : type == "rectangle" ? 6 : 5;
  if (v.size() < need)
    return problem = "WORKPIECE \"" + type + "\" needs " + std::to_string(need + 4) +
                     " arguments, it has " + std::to_string(args.size()),
           std::nullopt;
  const int bits = int(v[0]);
  const double z0 = v[1];
  // Z1: absolute (bit 64), else measured from Z0 (down, whichever its sign).
  const double z1 = (bits & 64) ? v[2] : z0 - std::abs(v[2]);
  StockSpec spec;
  spec.kind = StockSpec::Kind::Box;
  spec.stated_by_program = true;
  spec.box.zmin = std::min(z0, z1), spec.box.zmax = std::max(z0, z1);
  if (type == "box") {
    // Two corners: X0, Y0, then X1, Y1 absolute (bits 16, 32) or as lengths from X0, Y0.
    const double x0 = v[4], y0 = v[5];
    const double x1 = (bits & 16) ? v[6] : x0 + v[6], y1 = (bits & 32) ? v[7] : y0 + v[7];
    spec.box.xmin = std::min(x0, x1), spec.box.xmax = std::max(x0, x1);
    spec.box.ymin = std::min(y0, y1), spec.box.ymax = std::max(y0, y1);
  } else if (type == "rectangle") {
    // A cuboid centred on the origin: its length and width.
    spec.box.xmin = -std::abs(v[4]) / 2, spec.box.xmax = std::abs(v[4]) / 2;
    spec.box.ymin = -std::abs(v[5]) / 2, spec.box.ymax = std::abs(v[5]) / 2;
  } else {
    problem_column = at;
    return problem = "WORKPIECE blank \"" + type +
                     "\" is not modelled (ncjoule takes box and STL stocks: a BOX or RECTANGLE "
                     "blank, or --stock)",
           std::nullopt;
  }
  if (spec.box.empty()) return problem = "WORKPIECE blank has no volume", std::nullopt;
  return spec;
}

} // namespace ncjoule::estimate_detail
