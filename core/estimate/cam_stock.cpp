#include "cam_stock.hpp"

#include <algorithm>
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
                                                 std::size_t max_lines,
                                                 std::vector<Diagnostic>* problems) {
  std::optional<StockCorner> low, high;
  int low_line = 0, high_line = 0;
  std::optional<StockSpec> workpiece, block, size, vectric;
  std::optional<VectricOrigin> vectric_xy, vectric_z;
  int vectric_first = 0, vectric_last = 0;
  bool material_size_pending = false; // "( Material Size)" seen: its values on the next line
  const std::size_t lines = std::min(source.lines.size(), max_lines);
  for (std::size_t l = 0; l < lines && !(low && high); ++l) {
    const std::string_view text = source.line_text(l);
    const int line = int(l) + 1;
    const LineComments found = line_comments(text, dialect);
    // Sinumerik's blank is code: what comes before the line's first comment.
    if (!workpiece && found.has_code) {
      std::string_view code = text;
      if (!found.comments.empty() && found.comments.front().column > 0)
        code = text.substr(0, std::size_t(found.comments.front().column - 1));
      std::string problem;
      std::size_t column = 0;
      if (auto blank = sinumerik_workpiece(code, problem, column)) {
        workpiece = std::move(blank);
        workpiece->from = "sinumerik-workpiece";
        workpiece->origin = "WORKPIECE at line " + std::to_string(line);
      } else if (!problem.empty() && problems) {
        problems->push_back({Severity::Warning, source.path, line, int(column) + 1,
                             problem + "; the next source of the stock is used"});
      }
    }
    bool pending_now = false;
    for (const LineComment& comment : found.comments) {
      const std::string_view body = trim(comment.text);
      if (auto corner = stock_corner_of_comment(body)) {
        (corner->is_max ? high : low) = corner;
        (corner->is_max ? high_line : low_line) = line;
        continue;
      }
      if (auto stated = stock_box_of_comment(body)) {
        std::optional<StockSpec>& slot = stated->size_only ? size : block;
        if (!slot) {
          slot = std::move(stated);
          slot->from = "stock-comment";
          slot->origin = "the program's stock comment (line " + std::to_string(line) + ")";
        }
        continue;
      }
      if (auto origin = vectric_origin(body)) {
        (origin->is_z ? vectric_z : vectric_xy) = origin;
        if (vectric) vectric_last = std::max(vectric_last, line);
        continue;
      }
      const std::string lower = to_lower(body);
      const bool names_size = lower.rfind("material size", 0) == 0;
      if (vectric || !(names_size || material_size_pending)) continue;
      // "Material Size" with its values on this line, or on the next after a bare title.
      const std::string_view values = names_size ? body.substr(13) : body;
      if (auto sizes = xyz_sizes(values)) {
        vectric = vectric_material_box(*sizes, std::nullopt, std::nullopt);
        vectric_first = names_size ? line : line - 1;
        vectric_last = line;
      } else if (names_size) {
        pending_now = true;
      }
    }
    material_size_pending = pending_now;
  }
  if (low && high) {
    StockSpec spec;
    spec.kind = StockSpec::Kind::Box;
    const double lo[3] = {low->xyz[0].first, low->xyz[1].first, low->xyz[2].first};
    const double hi[3] = {high->xyz[0].first, high->xyz[1].first, high->xyz[2].first};
    spec.box = Box3{lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]};
    bool valid = true;
    for (std::size_t i = 0; i < 3; ++i) {
      spec.box_units[i] = low->xyz[i].second;
      spec.box_units[i + 3] = high->xyz[i].second;
      if (!(hi[i] > lo[i])) valid = false; // an empty or inverted box is no stock
    }
    if (valid) {
      spec.stated_by_program = true;
      spec.from = "stock-comment";
      spec.origin = "the program's stock comments (stockMin, line " + std::to_string(low_line) +
                    ", stockMax, line " + std::to_string(high_line) + ")";
      return spec;
    }
  }
  if (workpiece) return workpiece;
  if (block) return block;
  if (vectric) {
    const auto size_of = [&](int k) {
      return std::pair{vectric->box.xmax * (k == 0) + vectric->box.ymax * (k == 1) +
                           vectric->box.zmax * (k == 2),
                       vectric->box_units[std::size_t(k)]};
    };
    auto placed = vectric_material_box({size_of(0), size_of(1), size_of(2)}, vectric_xy, vectric_z);
    placed->from = "vectric";
    placed->origin = "Vectric Material Size block, lines " + std::to_string(vectric_first) + "-" +
                     std::to_string(vectric_last);
    return placed;
  }
  return size;
}

} // namespace ncjoule::estimate_detail
