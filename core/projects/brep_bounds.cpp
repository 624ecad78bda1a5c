#include "brep_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "ncjoule/text.hpp"

namespace ncjoule::projects_detail {
namespace {

// The lines of `text`, trimmed.
std::vector<std::string_view> lines_of(std::string_view text) {
  std::vector<std::string_view> out;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    out.push_back(trim(text.substr(begin, end - begin)));
    begin = end + 1;
  }
  return out;
}

// `count` finite numbers separated by blanks, or std::nullopt.
std::optional<std::vector<double>> numbers(std::string_view line, std::size_t count) {
  std::vector<double> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
      ++i;
    if (i >= line.size()) break;
    std::size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t')
      ++j;
    const auto v = parse_number(line.substr(i, j - i));
    if (!v || !std::isfinite(*v)) return std::nullopt;
    out.push_back(*v);
    i = j;
  }
  if (out.size() != count) return std::nullopt;
  return out;
}

} // namespace

std::optional<Box3> brep_vertex_bounds(std::string_view text, std::string& why) {
  const std::vector<std::string_view> lines = lines_of(text);
  std::size_t k = 0;
  while (k < lines.size() && lines[k].empty())
    ++k;
  if (k >= lines.size() || lines[k].rfind("CASCADE Topology", 0) != 0)
    return why = "is not an OpenCASCADE BREP", std::nullopt;
  double shift[3] = {0, 0, 0};
  std::size_t locations = 0;
  for (; k < lines.size(); ++k)
    if (lines[k].rfind("Locations ", 0) == 0) {
      const auto n = numbers(lines[k].substr(10), 1);
      if (!n || *n->data() < 0) return why = "has a bad Locations line", std::nullopt;
      locations = std::size_t(n->front());
      break;
    }
  if (locations > 1) return why = "places its parts at more than one location", std::nullopt;
  if (locations == 1) {
    // "1" (a matrix location) then three rows of four: rotation and translation.
    if (k + 4 >= lines.size() || lines[k + 1] != "1")
      return why = "has a location that is not a plain matrix", std::nullopt;
    for (int r = 0; r < 3; ++r) {
      const auto row = numbers(lines[k + 2 + r], 4);
      if (!row) return why = "has a location row that is not four numbers", std::nullopt;
      for (int c = 0; c < 3; ++c)
        if (std::abs((*row)[c] - (r == c ? 1.0 : 0.0)) > 1e-9)
          return why = "has a location that turns the shape", std::nullopt;
      shift[r] = (*row)[3];
    }
  }
  constexpr double inf = std::numeric_limits<double>::infinity();
  Box3 box{inf, inf, inf, -inf, -inf, -inf};
  std::size_t vertices = 0;
  for (; k < lines.size(); ++k) {
    if (lines[k] != "Ve" || k + 2 >= lines.size()) continue;
    const auto p = numbers(lines[k + 2], 3);
    if (!p) return why = "has a vertex that is not three numbers", std::nullopt;
    box.xmin = std::min(box.xmin, (*p)[0]), box.xmax = std::max(box.xmax, (*p)[0]);
    box.ymin = std::min(box.ymin, (*p)[1]), box.ymax = std::max(box.ymax, (*p)[1]);
    box.zmin = std::min(box.zmin, (*p)[2]), box.zmax = std::max(box.zmax, (*p)[2]);
    ++vertices;
  }
  if (vertices == 0) return why = "has no vertex", std::nullopt;
  box.xmin += shift[0], box.xmax += shift[0];
  box.ymin += shift[1], box.ymax += shift[1];
  box.zmin += shift[2], box.zmax += shift[2];
  return box;
}

} // namespace ncjoule::projects_detail
