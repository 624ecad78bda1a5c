// Stock from a triangle mesh: each column centre is cast vertically through the triangles, and
// the crossings, sorted along Z, pair up into material intervals.
#include <algorithm>
#include <cmath>
#include <limits>

#include "ncjoule/removal.hpp"

namespace ncjoule {
namespace {

struct XY {
  double x, y;
};

// Signed area test of point p against the edge a->b, computed from the edge's end points in a
// fixed order, so that the two triangles sharing an edge get exactly opposite values.
double edge_side(XY a, XY b, XY p) {
  const bool swap = (b.x < a.x) || (b.x == a.x && b.y < a.y);
  if (swap) std::swap(a, b);
  const double s = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
  return swap ? -s : s;
}

// Whether a counter-clockwise edge a->b owns points lying exactly on it (the top-left rule of
// rasterisers): a point on an edge shared by two triangles belongs to exactly one of them.
bool owns_boundary(XY a, XY b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  return dy < 0 || (dy == 0 && dx < 0);
}

struct Crossing {
  std::size_t column;
  double z;
  bool operator<(const Crossing& o) const {
    return column != o.column ? column < o.column : z < o.z;
  }
};

class MeshStock final : public StockShape {
public:
  MeshStock(TriangleMesh mesh, std::string description, std::size_t* open_columns)
      : mesh_(std::move(mesh)), description_(std::move(description)), open_columns_(open_columns) {}
  Box3 bounds() const override { return mesh_.bounds(); }
  std::string description() const override { return description_; }

  void fill_columns(const GridFrame& grid, std::vector<std::uint32_t>& first,
                    std::vector<ZInterval>& intervals) const override {
    std::vector<Crossing> crossings;
    for (const Triangle& t : mesh_.triangles)
      add_crossings(grid, t, crossings);
    std::sort(crossings.begin(), crossings.end());

    first.assign(grid.columns() + 1, 0);
    intervals.clear();
    std::size_t open = 0, k = 0;
    for (std::size_t c = 0; c < grid.columns(); ++c) {
      std::size_t end = k;
      while (end < crossings.size() && crossings[end].column == c)
        ++end;
      if ((end - k) % 2 != 0) ++open;
      for (std::size_t m = k; m + 1 < end; m += 2) {
        const double lo = crossings[m].z, hi = crossings[m + 1].z;
        if (hi <= lo) continue;
        // Touching intervals (a solid made of stacked boxes) join into one.
        if (intervals.size() > first[c] && intervals.back().hi >= lo)
          intervals.back().hi = hi;
        else
          intervals.push_back({lo, hi});
      }
      first[c + 1] = std::uint32_t(intervals.size());
      k = end;
    }
    if (open_columns_) *open_columns_ = open;
  }

private:
  static void add_crossings(const GridFrame& grid, const Triangle& t, std::vector<Crossing>& out) {
    XY a{t.v[0][0], t.v[0][1]}, b{t.v[1][0], t.v[1][1]}, c{t.v[2][0], t.v[2][1]};
    double za = t.v[0][2], zb = t.v[1][2], zc = t.v[2][2];
    double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (area == 0) return; // seen edge-on from above: no vertical ray crosses it
    if (area < 0) {        // make it counter-clockwise seen from above
      std::swap(b, c), std::swap(zb, zc);
      area = -area;
    }
    const double xmin = std::min({a.x, b.x, c.x}), xmax = std::max({a.x, b.x, c.x});
    const double ymin = std::min({a.y, b.y, c.y}), ymax = std::max({a.y, b.y, c.y});
    const int i0 = std::max(0, int(std::ceil((xmin - grid.x0) / grid.dx - 0.5)));
    const int i1 = std::min(grid.nx - 1, int(std::floor((xmax - grid.x0) / grid.dx - 0.5)));
    const int j0 = std::max(0, int(std::ceil((ymin - grid.y0) / grid.dy - 0.5)));
    const int j1 = std::min(grid.ny - 1, int(std::floor((ymax - grid.y0) / grid.dy - 0.5)));
    const bool own_ab = owns_boundary(a, b), own_bc = owns_boundary(b, c),
               own_ca = owns_boundary(c, a);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const XY p{grid.column_x(i), grid.column_y(j)};
        const double wa = edge_side(b, c, p), wb = edge_side(c, a, p), wc = edge_side(a, b, p);
        if (wa < 0 || wb < 0 || wc < 0) continue;
        if ((wa == 0 && !own_bc) || (wb == 0 && !own_ca) || (wc == 0 && !own_ab)) continue;
        const double z = (wa * za + wb * zb + wc * zc) / (wa + wb + wc);
        out.push_back({std::size_t(j) * grid.nx + i, z});
      }
    }
  }

  TriangleMesh mesh_;
  std::string description_;
  std::size_t* open_columns_;
};

} // namespace

Box3 TriangleMesh::bounds() const {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Box3 b{inf, inf, inf, -inf, -inf, -inf};
  for (const Triangle& t : triangles)
    for (const auto& v : t.v) {
      b.xmin = std::min(b.xmin, v[0]), b.xmax = std::max(b.xmax, v[0]);
      b.ymin = std::min(b.ymin, v[1]), b.ymax = std::max(b.ymax, v[1]);
      b.zmin = std::min(b.zmin, v[2]), b.zmax = std::max(b.zmax, v[2]);
    }
  if (triangles.empty()) b = Box3{};
  return b;
}

double TriangleMesh::crossings_per_column() const {
  const Box3 b = bounds();
  const double area = (b.xmax - b.xmin) * (b.ymax - b.ymin);
  if (!(area > 0)) return 0;
  double covered = 0; // the triangles' areas seen from above
  for (const Triangle& t : triangles)
    covered += std::abs((t.v[1][0] - t.v[0][0]) * (t.v[2][1] - t.v[0][1]) -
                        (t.v[1][1] - t.v[0][1]) * (t.v[2][0] - t.v[0][0])) /
               2;
  return covered / area;
}

std::unique_ptr<StockShape> make_mesh_stock(TriangleMesh mesh, std::string description,
                                            std::size_t* open_columns) {
  return std::make_unique<MeshStock>(std::move(mesh), std::move(description), open_columns);
}

} // namespace ncjoule
