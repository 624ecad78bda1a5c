#include "cam_stock.hpp"

#include <string>

#include "ncjoule/text.hpp"

namespace ncjoule::estimate_detail {

std::optional<StockCorner> stock_corner_of_comment(std::string_view comment) {
  const std::string_view text = trim(comment);
  const std::string low = to_lower(text);
  std::size_t at = 0;
  if (low.rfind("stock", 0) != 0) return std::nullopt;
  at = 5;
  while (at < low.size() && (low[at] == ' ' || low[at] == '_'))
    ++at;
  StockCorner corner;
  if (low.compare(at, 3, "min") == 0)
    corner.is_max = false;
  else if (low.compare(at, 3, "max") == 0)
    corner.is_max = true;
  else
    return std::nullopt;
  at += 3;
  while (at < low.size() && low[at] == ' ')
    ++at;
  if (at >= low.size() || (low[at] != ':' && low[at] != '=')) return std::nullopt;
  const std::string_view values = trim(text.substr(at + 1));
  // Three lengths, separated by commas (and blanks).
  std::size_t k = 0, begin = 0;
  while (begin <= values.size()) {
    std::size_t end = values.find(',', begin);
    if (end == std::string_view::npos) end = values.size();
    if (k == 3) return std::nullopt;
    const auto length = parse_length(values.substr(begin, end - begin));
    if (!length) return std::nullopt;
    corner.xyz[k++] = *length;
    begin = end + 1;
  }
  if (k != 3) return std::nullopt;
  return corner;
}

namespace {

// Numbers separated by `separators` (and blanks), each with an optional unit; nullopt unless
// there are exactly `count`.
std::optional<std::vector<std::pair<double, LengthUnit>>>
lengths(std::string_view text, std::string_view separators, std::size_t count) {
  std::vector<std::pair<double, LengthUnit>> out;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    std::size_t end = text.find_first_of(separators, begin);
    if (end == std::string_view::npos) end = text.size();
    const auto length = parse_length(trim(text.substr(begin, end - begin)));
    if (!length || out.size() == count) return std::nullopt;
    out.push_back(*length);
    begin = end + 1;
  }
  if (out.size() != count) return std::nullopt;
  return out;
}

} // namespace

std::optional<StockSpec> stock_box_of_comment(std::string_view comment) {
  const std::string_view text = trim(comment);
  const std::string low = to_lower(text);
  StockSpec spec;
  spec.kind = StockSpec::Kind::Box;
  spec.stated_by_program = true;
  if (low.rfind("stock/block,", 0) == 0) {
    // APT-style (Carbide Create and others): STOCK/BLOCK,W,L,H,X0,Y0,Z0 with (X0, Y0, Z0) the
    // work origin measured from the stock's low corner.
    const auto v = lengths(text.substr(12), ",", 6);
    if (!v) return std::nullopt;
    spec.box = Box3{-(*v)[3].first,
                    -(*v)[4].first,
                    -(*v)[5].first,
                    (*v)[0].first - (*v)[3].first,
                    (*v)[1].first - (*v)[4].first,
                    (*v)[2].first - (*v)[5].first};
    for (std::size_t i = 0; i < 3; ++i)
      spec.box_units[i] = spec.box_units[i + 3] = (*v)[i].second;
  } else if (low.rfind("stock", 0) == 0) {
    // "STOCK 4.125 x 3.625 x 1.000", "STOCK SIZE: 100 X 60 X 20": the size only.
    std::size_t at = 5;
    if (low.compare(at, 5, " size") == 0) at += 5;
    while (at < low.size() && (low[at] == ' ' || low[at] == ':' || low[at] == '='))
      ++at;
    const auto v = lengths(std::string_view(low).substr(at), "x*", 3);
    if (!v) return std::nullopt;
    spec.size_only = true;
    spec.box = Box3{0, 0, 0, (*v)[0].first, (*v)[1].first, (*v)[2].first};
    for (std::size_t i = 0; i < 3; ++i)
      spec.box_units[i] = spec.box_units[i + 3] = (*v)[i].second;
  } else {
    return std::nullopt;
  }
  if (!(spec.box.xmax > spec.box.xmin && spec.box.ymax > spec.box.ymin &&
        spec.box.zmax > spec.box.zmin))
    return std::nullopt;
  return spec;
}

std::optional<StockSpec> stock_from_cam_comments(const SourceFile& source, const Dialect& dialect,
                                                 std::size_t max_lines) {
  std::optional<StockCorner> low, high;
  std::optional<StockSpec> box; // STOCK/BLOCK or a size, when there is no min/max pair
  int low_line = 0, high_line = 0;
  for (std::size_t l = 0; l < source.lines.size() && l < max_lines && !(low && high); ++l)
    for (const LineComment& comment : line_comments(source.line_text(l), dialect).comments) {
      if (auto corner = stock_corner_of_comment(comment.text)) {
        (corner->is_max ? high : low) = corner;
        (corner->is_max ? high_line : low_line) = int(l) + 1;
      } else if (!box || box->size_only) {
        if (auto stated = stock_box_of_comment(comment.text)) {
          if (box && stated->size_only) continue; // the first size wins
          box = std::move(stated);
          box->origin = "the program's stock comment (line " + std::to_string(l + 1) + ")";
        }
      }
    }
  if (!low || !high) return box;
  StockSpec spec;
  spec.kind = StockSpec::Kind::Box;
  const double lo[3] = {low->xyz[0].first, low->xyz[1].first, low->xyz[2].first};
  const double hi[3] = {high->xyz[0].first, high->xyz[1].first, high->xyz[2].first};
  spec.box = Box3{lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]};
  for (std::size_t i = 0; i < 3; ++i) {
    spec.box_units[i] = low->xyz[i].second;
    spec.box_units[i + 3] = high->xyz[i].second;
    if (!(hi[i] > lo[i])) return std::nullopt; // an empty or inverted box is no stock
  }
  spec.stated_by_program = true;
  spec.origin = "the program's stock comments (stockMin, line " + std::to_string(low_line) +
                ", stockMax, line " + std::to_string(high_line) + ")";
  return spec;
}

} // namespace ncjoule::estimate_detail
