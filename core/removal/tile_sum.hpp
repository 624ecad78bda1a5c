// Splitting one step's work over fixed tiles of the column grid, run in parallel with TBB,
// and summing the tiles' results in tile order, so that a step's volume is the same bit for bit
// whatever the number of threads or the order in which tiles finish.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
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
  std::uint64_t columns_visited = 0;
  std::uint64_t cells_tested = 0;
};

// Calls visit_column(column index, i, j, x, y, TileResult&) for every column whose centre the
// step's footprint may cover, tile by tile, except in tiles where skip_tile(tile) is true (their
// columns still count as visited); tile_done(tile, result) follows each tile that was not
// skipped, on the thread that ran it. Returns the sum over tiles in tile order. Steps that touch
// fewer than `parallel_min_columns` columns run on the calling thread (same result). `scratch`
// is reused from step to step.
template <class SkipTile, class VisitColumn, class TileDone>
TileResult for_each_footprint_column(const GridFrame& grid, const SweptStep& step,
                                     std::size_t parallel_min_columns,
                                     std::vector<TileResult>& scratch, SkipTile&& skip_tile,
                                     VisitColumn&& visit_column, TileDone&& tile_done) {
  auto first_index = [](double lo, double origin, double d) {
    return int(std::ceil((lo - origin) / d - 0.5));
  };
  auto last_index = [](double hi, double origin, double d) {
    return int(std::floor((hi - origin) / d - 0.5));
  };
  const int i0 = std::max(0, first_index(step.footprint_xmin(), grid.x0, grid.dx));
  const int i1 = std::min(grid.nx - 1, last_index(step.footprint_xmax(), grid.x0, grid.dx));
  const int j0 = std::max(0, first_index(step.footprint_ymin(), grid.y0, grid.dy));
  const int j1 = std::min(grid.ny - 1, last_index(step.footprint_ymax(), grid.y0, grid.dy));
  if (i0 > i1 || j0 > j1) return {};

  const int ti0 = i0 / kTileColumns, ti1 = i1 / kTileColumns;
  const int tj0 = j0 / kTileColumns, tj1 = j1 / kTileColumns;
  const int tiles_x = ti1 - ti0 + 1;
  const std::size_t tiles = std::size_t(tiles_x) * std::size_t(tj1 - tj0 + 1);

  auto run_tile = [&](std::size_t t) {
    TileResult r;
    const int ti = ti0 + int(t % tiles_x), tj = tj0 + int(t / tiles_x);
    const std::size_t tile = tile_of(grid, ti * kTileColumns, tj * kTileColumns);
    const bool skip = skip_tile(tile);
    const int ia = std::max(i0, ti * kTileColumns);
    const int ib = std::min(i1, ti * kTileColumns + kTileColumns - 1);
    const int ja = std::max(j0, tj * kTileColumns);
    const int jb = std::min(j1, tj * kTileColumns + kTileColumns - 1);
    for (int j = ja; j <= jb; ++j) {
      const double y = grid.column_y(j);
      double xlo, xhi;
      if (!step.row_span(y, xlo, xhi)) continue;
      const int a = std::max(ia, first_index(xlo, grid.x0, grid.dx));
      const int b = std::min(ib, last_index(xhi, grid.x0, grid.dx));
      if (a > b) continue;
      r.columns_visited += std::uint64_t(b - a + 1);
      if (skip) continue;
      const std::size_t row = std::size_t(j) * std::size_t(grid.nx);
      for (int i = a; i <= b; ++i)
        visit_column(row + std::size_t(i), i, j, grid.column_x(i), y, r);
    }
    if (!skip) tile_done(tile, r);
    return r;
  };

  const std::size_t footprint = std::size_t(i1 - i0 + 1) * std::size_t(j1 - j0 + 1);
  TileResult total;
  auto add = [&total](const TileResult& r) {
    total.volume_mm3 += r.volume_mm3;
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
