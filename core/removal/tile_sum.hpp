// Splitting one step's work over fixed tiles of the column grid, run in parallel with TBB,
// and summing the tiles' results in tile order, so that a step's volume is the same bit for bit
// whatever the number of threads or the order in which tiles finish.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "ncjoule/removal.hpp"
#include "swept_step.hpp"

namespace ncjoule::detail {

// Tiles are squares of this many columns, fixed in the grid (not placed relative to the step).
inline constexpr int kTileColumns = 32;

inline int tiles_across(const GridFrame& grid) {
  return (grid.nx + kTileColumns - 1) / kTileColumns;
}
inline std::size_t tile_count(const GridFrame& grid) {
  return std::size_t(tiles_across(grid)) * std::size_t((grid.ny + kTileColumns - 1) / kTileColumns);
}
// The tile holding column (i, j).
inline std::size_t tile_of(const GridFrame& grid, int i, int j) {
  return std::size_t(j / kTileColumns) * std::size_t(tiles_across(grid)) +
         std::size_t(i / kTileColumns);
}

struct TileResult {
  double volume_mm3 = 0;
  // The highest top of material the step cut into (mm, the engine's Z), -inf where it cut none.
  double cut_top_mm = -std::numeric_limits<double>::infinity();
  std::uint64_t columns_visited = 0;
  std::uint64_t cells_tested = 0;
};

// The columns a step's footprint may cover, as index ranges, and the tiles they fall in.
struct FootprintRange {
  int i0 = 0, i1 = -1, j0 = 0, j1 = -1;     // columns
  int ti0 = 0, ti1 = -1, tj0 = 0, tj1 = -1; // tiles
  bool empty() const { return i0 > i1 || j0 > j1; }
};

// A column index as an int, clamped far outside any grid first: a step at X1e23 (a program's
// absurd coordinate) must give an index past the grid, not an overflowing conversion.
inline int clamped_index(double v) {
  constexpr double kFar = 1e9;
  if (!(v > -kFar)) return -int(kFar);
  if (!(v < kFar)) return int(kFar);
  return int(v);
}
inline int first_column_index(double lo, double origin, double d) {
  return clamped_index(std::ceil((lo - origin) / d - 0.5));
}
inline int last_column_index(double hi, double origin, double d) {
  return clamped_index(std::floor((hi - origin) / d - 0.5));
}

inline FootprintRange footprint_range(const GridFrame& grid, const SweptStep& step) {
  FootprintRange f;
  f.i0 = std::max(0, first_column_index(step.footprint_xmin(), grid.x0, grid.dx));
  f.i1 = std::min(grid.nx - 1, last_column_index(step.footprint_xmax(), grid.x0, grid.dx));
  f.j0 = std::max(0, first_column_index(step.footprint_ymin(), grid.y0, grid.dy));
  f.j1 = std::min(grid.ny - 1, last_column_index(step.footprint_ymax(), grid.y0, grid.dy));
  if (f.empty()) return f;
  f.ti0 = f.i0 / kTileColumns, f.ti1 = f.i1 / kTileColumns;
  f.tj0 = f.j0 / kTileColumns, f.tj1 = f.j1 / kTileColumns;
  return f;
}

// Visits the footprint's columns in tile (ti, tj), row by row (visit_column as below); with
// `skip` (a tile with no material above the tool), nothing: not even the footprint's rows are
// worked out, since most steps of a long program run where the material is gone already.
template <class VisitColumn>
void visit_tile_columns(const GridFrame& grid, const SweptStep& step, const FootprintRange& f,
                        int ti, int tj, bool skip, VisitColumn&& visit_column, TileResult& r) {
  if (skip) return;
  const int ia = std::max(f.i0, ti * kTileColumns);
  const int ib = std::min(f.i1, ti * kTileColumns + kTileColumns - 1);
  const int ja = std::max(f.j0, tj * kTileColumns);
  const int jb = std::min(f.j1, tj * kTileColumns + kTileColumns - 1);
  for (int j = ja; j <= jb; ++j) {
    const double y = grid.column_y(j);
    double xlo, xhi;
    if (!step.row_span(y, xlo, xhi)) continue;
    const int a = std::max(ia, first_column_index(xlo, grid.x0, grid.dx));
    const int b = std::min(ib, last_column_index(xhi, grid.x0, grid.dx));
    if (a > b) continue;
    r.columns_visited += std::uint64_t(b - a + 1);
    const std::size_t row = std::size_t(j) * std::size_t(grid.nx);
    for (int i = a; i <= b; ++i)
      visit_column(row + std::size_t(i), i, j, grid.column_x(i), y, r);
  }
}

// Calls visit_column(column index, i, j, x, y, TileResult&) for every column whose centre the
// step's footprint may cover, tile by tile, except in tiles where skip_tile(tile) is true (their
// columns are not visited); tile_done(tile, result) follows each tile that was not
// skipped, on the thread that ran it. Returns the sum over tiles in tile order. Steps that touch
// fewer than `parallel_min_columns` columns run on the calling thread (same result). `scratch`
// is reused from step to step.
template <class SkipTile, class VisitColumn, class TileDone>
TileResult for_each_footprint_column(const GridFrame& grid, const SweptStep& step,
                                     std::size_t parallel_min_columns,
                                     std::vector<TileResult>& scratch, SkipTile&& skip_tile,
                                     VisitColumn&& visit_column, TileDone&& tile_done) {
  const FootprintRange f = footprint_range(grid, step);
  if (f.empty()) return {};
  const int tiles_x = f.ti1 - f.ti0 + 1;
  const std::size_t tiles = std::size_t(tiles_x) * std::size_t(f.tj1 - f.tj0 + 1);

  auto run_tile = [&](std::size_t t) {
    TileResult r;
    const int ti = f.ti0 + int(t % tiles_x), tj = f.tj0 + int(t / tiles_x);
    const std::size_t tile = tile_of(grid, ti * kTileColumns, tj * kTileColumns);
    const bool skip = skip_tile(tile);
    visit_tile_columns(grid, step, f, ti, tj, skip, visit_column, r);
    if (!skip) tile_done(tile, r);
    return r;
  };

  const std::size_t footprint = std::size_t(f.i1 - f.i0 + 1) * std::size_t(f.j1 - f.j0 + 1);
  TileResult total;
  auto add = [&total](const TileResult& r) {
    total.volume_mm3 += r.volume_mm3;
    total.cut_top_mm = std::max(total.cut_top_mm, r.cut_top_mm);
    total.columns_visited += r.columns_visited;
    total.cells_tested += r.cells_tested;
  };
  if (tiles == 1 || footprint < parallel_min_columns) {
    for (std::size_t t = 0; t < tiles; ++t)
      add(run_tile(t));
    return total;
  }
  scratch.assign(tiles, TileResult{});
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, tiles, 1),
      [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t t = range.begin(); t != range.end(); ++t)
          scratch[t] = run_tile(t);
      },
      tbb::simple_partitioner());
  for (const TileResult& r : scratch)
    add(r);
  return total;
}

} // namespace ncjoule::detail
