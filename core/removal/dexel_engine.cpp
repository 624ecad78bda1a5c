// The Z-dexel engine: every column of the grid keeps its material as sorted intervals along Z.
// A 3-axis tool only ever removes material above its lower envelope, so a column loses the tops
// of its intervals and never splits one: its interval list only shrinks, in place.
#include <algorithm>
#include <cmath>
#include <limits>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "engines.hpp"
#include "swept_step.hpp"
#include "tile_sum.hpp"

namespace ncjoule::detail {
namespace {

constexpr double kNoMaterial = -std::numeric_limits<double>::infinity();
// Below this many footprint columns a step runs on one thread: a column of the dexel grid costs
// a few nanoseconds, less than handing tiles to other threads.
constexpr std::size_t kParallelMinColumns = 40'000;

class DexelEngine final : public RemovalEngine {
public:
  DexelEngine(const StockShape& stock, const GridFrame& grid) : grid_(grid) {
    std::vector<std::uint32_t> first;
    stock.fill_columns(grid_, first, intervals_);
    const std::size_t n = grid_.columns();
    first_.assign(first.begin(), first.begin() + n);
    count_.resize(n);
    top_.resize(n);
    for (std::size_t c = 0; c < n; ++c) {
      count_[c] = std::uint16_t(std::min<std::uint32_t>(first[c + 1] - first[c], 65535));
      top_[c] = count_[c] ? intervals_[first_[c] + count_[c] - 1].hi : kNoMaterial;
    }
    tile_top_.assign(tile_count(grid_), kNoMaterial);
    row_top_.assign(tile_count(grid_) * kTileColumns, kNoMaterial);
    for (std::size_t tile = 0; tile < tile_top_.size(); ++tile)
      refresh_tile_top(tile);
  }

  EngineKind kind() const override { return EngineKind::Dexel; }
  const GridFrame& grid() const override { return grid_; }
  const EngineStats& stats() const override { return stats_; }

  std::size_t memory_bytes() const override {
    return intervals_.capacity() * sizeof(ZInterval) + first_.capacity() * sizeof(std::uint32_t) +
           count_.capacity() * sizeof(std::uint16_t) +
           (top_.capacity() + tile_top_.capacity() + row_top_.capacity()) * sizeof(double);
  }

  bool material_at(const Point3& p) const override {
    const int i = detail::clamped_index(std::floor((p.x() - grid_.x0) / grid_.dx));
    const int j = detail::clamped_index(std::floor((p.y() - grid_.y0) / grid_.dy));
    if (i < 0 || j < 0 || i >= grid_.nx || j >= grid_.ny) return false;
    const std::size_t c = std::size_t(j) * std::size_t(grid_.nx) + std::size_t(i);
    for (std::uint32_t k = 0; k < count_[c]; ++k) {
      const ZInterval& iv = intervals_[first_[c] + k];
      if (p.z() > iv.lo && p.z() < iv.hi) return true;
    }
    return false;
  }

  std::optional<bool> material_above(const Point3& from, const Point3& to, double radius,
                                     double z_floor) const override {
    // A column counts when its centre lies within radius + half the cell's diagonal of the
    // segment: every cell the inflated footprint touches, and a few it only comes near.
    const double reach = radius + 0.5 * std::hypot(grid_.dx, grid_.dy);
    const double x_lo = std::min(from.x(), to.x()) - reach,
                 x_hi = std::max(from.x(), to.x()) + reach;
    const double y_lo = std::min(from.y(), to.y()) - reach,
                 y_hi = std::max(from.y(), to.y()) + reach;
    const int i0 = std::max(0, detail::clamped_index(std::floor((x_lo - grid_.x0) / grid_.dx)));
    const int i1 =
        std::min(grid_.nx - 1, detail::clamped_index(std::floor((x_hi - grid_.x0) / grid_.dx)));
    const int j0 = std::max(0, detail::clamped_index(std::floor((y_lo - grid_.y0) / grid_.dy)));
    const int j1 =
        std::min(grid_.ny - 1, detail::clamped_index(std::floor((y_hi - grid_.y0) / grid_.dy)));
    const double ax = from.x(), ay = from.y();
    const double ux = to.x() - ax, uy = to.y() - ay;
    const double length2 = ux * ux + uy * uy;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const std::size_t c = std::size_t(j) * std::size_t(grid_.nx) + std::size_t(i);
        if (!(top_[c] > z_floor)) continue;
        const double px = grid_.column_x(i) - ax, py = grid_.column_y(j) - ay;
        const double u = length2 > 0 ? std::clamp((px * ux + py * uy) / length2, 0.0, 1.0) : 0.0;
        if (std::hypot(px - u * ux, py - u * uy) <= reach) return true;
      }
    return false;
  }

  double material_volume_mm3() const override {
    double length = 0;
    for (std::size_t c = 0; c < count_.size(); ++c)
      for (std::uint32_t k = 0; k < count_[c]; ++k)
        length += intervals_[first_[c] + k].hi - intervals_[first_[c] + k].lo;
    return length * grid_.dx * grid_.dy;
  }

  double remove_step(const Tool& tool, const Point3& from, const Point3& to) override {
    const SweptStep step(tool, from, to);
    const double zlow = step.lowest_tip_z();
    const TileResult r = for_each_footprint_column(
        grid_, step, kParallelMinColumns, scratch_,
        [&](std::size_t tile) { return tile_top_[tile] <= zlow; },
        [&](std::size_t c, int, int, double x, double y, TileResult& acc) {
          cut_column(step, zlow, c, x, y, acc);
        },
        [&](std::size_t tile, const TileResult& acc) {
          if (acc.volume_mm3 > 0) refresh_tile_top(tile);
        });
    const double volume = r.volume_mm3 * grid_.dx * grid_.dy;
    ++stats_.steps;
    stats_.columns_visited += r.columns_visited;
    stats_.cells_tested += r.cells_tested;
    return volume;
  }

  // The batch: steps binned by the tiles their footprints touch; every tile, in parallel,
  // applies its steps in order; a step's volume sums its tiles in tile order, as remove_step
  // does, so the result is the same bit for bit. The batch runs in chunks of consecutive steps
  // that together touch at most kMaxTileEntries tiles: a tool far wider than the grid's spacing
  // (each of its steps touches thousands of tiles) would otherwise hold the bins of a whole
  // batch at once, hundreds of MiB beside the stock model. Chunks run in order and a step lies
  // in one chunk, so every tile still sees its steps in order: the same numbers.
  void remove_steps(const std::vector<RemovalStep>& steps, std::vector<double>& volumes,
                    std::vector<double>* cut_tops) override {
    const std::size_t n = steps.size();
    volumes.assign(n, 0.0);
    if (cut_tops) cut_tops->assign(n, kNoMaterial);
    if (n == 0) return;
    std::vector<SweptStep> swept;
    std::vector<FootprintRange> ranges;
    swept.reserve(n);
    ranges.reserve(n);
    for (std::size_t k = 0; k < n; ++k) {
      swept.emplace_back(*steps[k].tool, steps[k].from, steps[k].to);
      ranges.push_back(footprint_range(grid_, swept.back()));
    }
    tile_steps_.resize(tile_count(grid_));
    std::vector<double> length(n, 0.0);
    for (std::size_t begin = 0; begin < n;) {
      std::size_t end = begin, entries = 0;
      for (; end < n; ++end) {
        const FootprintRange& f = ranges[end];
        const std::size_t touched =
            f.empty() ? 0 : std::size_t(f.ti1 - f.ti0 + 1) * std::size_t(f.tj1 - f.tj0 + 1);
        if (end > begin && entries + touched > kMaxTileEntries) break;
        entries += touched;
      }
      remove_chunk(begin, end, swept, ranges, length, cut_tops);
      begin = end;
    }
    for (std::size_t k = 0; k < n; ++k)
      volumes[k] = length[k] * grid_.dx * grid_.dy;
    stats_.steps += n;
  }

private:
  struct TileStep {
    std::uint32_t step = 0;
    TileResult result;
  };

  // At most this many (step, tile) bins at once in remove_steps: 40 bytes each, 20 MiB.
  static constexpr std::size_t kMaxTileEntries = std::size_t(1) << 19;

  // The first and last column a step covers on each grid row of one row of tiles (first > last
  // where it covers none), as SweptStep::row_span gives them: slots made on a step's first tile
  // in the row of tiles, each row worked out the first time a tile with material on that row
  // asks for it (span), then read by the step's other tiles there.
  class RowSpans {
  public:
    RowSpans(std::size_t begin, std::size_t end) : begin_(begin), slot_(end - begin, -1) {}
    // Step k's rows from max(f.j0, tj * kTileColumns) on, two ints each.
    int* of(std::size_t k, const FootprintRange& f, int tj) {
      std::int64_t& slot = slot_[k - begin_];
      if (slot < 0) {
        slot = std::int64_t(columns_.size());
        const int ja = std::max(f.j0, tj * kTileColumns);
        const int jb = std::min(f.j1, tj * kTileColumns + kTileColumns - 1);
        columns_.resize(columns_.size() + 2 * std::size_t(jb - ja + 1), kUnknown);
      }
      return columns_.data() + slot;
    }
    // The first and last column of `row` (a row from `of`), the step's span on grid row j.
    static const int* span(int* row, const SweptStep& step, int j, const GridFrame& grid) {
      if (row[0] == kUnknown) {
        double xlo, xhi;
        if (step.row_span(grid.column_y(j), xlo, xhi)) {
          row[0] = first_column_index(xlo, grid.x0, grid.dx);
          row[1] = last_column_index(xhi, grid.x0, grid.dx);
        } else {
          row[0] = 1, row[1] = 0;
        }
      }
      return row;
    }

  private:
    static constexpr int kUnknown = std::numeric_limits<int>::min();
    std::size_t begin_;
    std::vector<std::int64_t> slot_; // by step: where its rows start in columns_, or -1
    std::vector<int> columns_;       // first and last column of each row, row after row
  };

  // Whether grid row j, in `tile`, has no material above z there.
  bool row_clear(std::size_t tile, int j, double z) const {
    return row_top_[tile * kTileColumns + std::size_t(j % kTileColumns)] <= z;
  }

  // The footprint's columns in tile (ti, tj), row by row, cut to the step's envelope: as
  // visit_tile_columns (tile_sum.hpp) visits them, with each row's columns from `rows` (the
  // rows from max(f.j0, tj * kTileColumns) on), except rows of the tile with no material above
  // the step's lowest tip: no column there is cut, and most rows of a long program's steps run
  // where the material is gone already.
  void visit_tile(const SweptStep& step, const FootprintRange& f, int* rows, int ti, int tj,
                  std::size_t tile, double zlow, TileResult& r) {
    const int ia = std::max(f.i0, ti * kTileColumns);
    const int ib = std::min(f.i1, ti * kTileColumns + kTileColumns - 1);
    const int ja = std::max(f.j0, tj * kTileColumns);
    const int jb = std::min(f.j1, tj * kTileColumns + kTileColumns - 1);
    for (int j = ja; j <= jb; ++j, rows += 2) {
      if (row_clear(tile, j, zlow)) continue;
      const int* span = RowSpans::span(rows, step, j, grid_);
      const int a = std::max(ia, span[0]);
      const int b = std::min(ib, span[1]);
      if (a > b) continue;
      r.columns_visited += std::uint64_t(b - a + 1);
      const double y = grid_.column_y(j);
      const std::size_t row = std::size_t(j) * std::size_t(grid_.nx);
      for (int i = a; i <= b; ++i)
        cut_column(step, zlow, row + std::size_t(i), grid_.column_x(i), y, r);
    }
  }

  // Steps [begin, end) of a batch: binned by tile, every tile's steps applied in order (tiles in
  // parallel), then each step's length summed over its tiles in tile order into `length`.
  void remove_chunk(std::size_t begin, std::size_t end, const std::vector<SweptStep>& swept,
                    const std::vector<FootprintRange>& ranges, std::vector<double>& length,
                    std::vector<double>* cut_tops) {
    const int across = tiles_across(grid_);
    std::vector<std::uint32_t> touched; // tiles with steps, in tile order
    std::size_t footprints = 0, tiles_wide = 0;
    for (std::size_t k = begin; k < end; ++k) {
      const FootprintRange& f = ranges[k];
      if (f.empty()) continue;
      ++footprints, tiles_wide += std::size_t(f.ti1 - f.ti0 + 1);
      for (int tj = f.tj0; tj <= f.tj1; ++tj)
        for (int ti = f.ti0; ti <= f.ti1; ++ti) {
          const std::size_t tile = std::size_t(tj) * std::size_t(across) + std::size_t(ti);
          // A tile with no material above the step's lowest tip now has none later in the
          // chunk either (material only goes): the step would cut nothing there.
          if (tile_top_[tile] <= swept[k].lowest_tip_z()) continue;
          if (tile_steps_[tile].empty()) touched.push_back(std::uint32_t(tile));
          tile_steps_[tile].push_back({std::uint32_t(k), {}});
        }
    }
    std::sort(touched.begin(), touched.end());
    // Tiles in parallel by rows of tiles: a step's footprint usually spans several tiles of a
    // row, and the columns a step covers on a row of the grid (SweptStep::row_span, the kernel's
    // largest cost) are the same in each, so one task works them out once for its row of tiles.
    // A batch in few rows of tiles (a raster along X: each batch's steps lie along one or two
    // rows) splits its rows into runs of tiles, so that every core has work; each tile is still
    // cut by one task, its steps in order, so the numbers do not depend on the split. Only where
    // the steps are narrow (two tiles wide on average): a step in several runs has its rows'
    // spans worked out in each, which costs more than it gains for a wide tool (a drill's
    // plunge on a fine grid spans a dozen tiles).
    std::vector<std::size_t> row_starts; // where each task's tiles begin in `touched`
    for (std::size_t t = 0; t < touched.size(); ++t)
      if (t == 0 || touched[t] / std::size_t(across) != touched[t - 1] / std::size_t(across))
        row_starts.push_back(t);
    const std::size_t tasks_wanted = 4 * std::size_t(tbb::this_task_arena::max_concurrency());
    if (row_starts.size() < tasks_wanted && touched.size() > row_starts.size() &&
        tiles_wide <= 2 * footprints) {
      const std::size_t per_task = (touched.size() + tasks_wanted - 1) / tasks_wanted;
      std::vector<std::size_t> split;
      for (std::size_t r = 0; r < row_starts.size(); ++r) {
        const std::size_t last = r + 1 < row_starts.size() ? row_starts[r + 1] : touched.size();
        for (std::size_t t = row_starts[r]; t < last; t += per_task)
          split.push_back(t);
      }
      row_starts.swap(split);
    }
    row_starts.push_back(touched.size());
    auto run_row = [&](std::size_t first, std::size_t last) {
      RowSpans spans(begin, end);
      for (std::size_t t = first; t < last; ++t) {
        const std::size_t tile = touched[t];
        const int ti = int(tile % std::size_t(across)), tj = int(tile / std::size_t(across));
        std::vector<TileStep>& list = tile_steps_[tile];
        for (std::size_t e = 0; e < list.size();) {
          TileStep& ts = list[e];
          const SweptStep& step = swept[ts.step];
          const std::size_t run = plunge_run(list, e, swept);
          if (run > 1) {
            const FootprintRange& f = ranges[ts.step];
            cut_plunge(list.data() + e, run, swept, f, spans.of(ts.step, f, tj), ti, tj, tile);
            e += run;
            continue;
          }
          ++e;
          const double zlow = step.lowest_tip_z();
          if (tile_top_[tile] <= zlow) continue; // no material above the tool in this tile
          visit_tile(step, ranges[ts.step], spans.of(ts.step, ranges[ts.step], tj), ti, tj, tile,
                     zlow, ts.result);
          if (ts.result.volume_mm3 > 0) refresh_tile_top(tile);
        }
      }
    };
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, row_starts.size() - 1, 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t r = range.begin(); r != range.end(); ++r)
            run_row(row_starts[r], row_starts[r + 1]);
        },
        tbb::simple_partitioner());
    // Tile order, step by step: the order remove_step adds them in.
    for (std::uint32_t tile : touched) {
      for (const TileStep& ts : tile_steps_[tile]) {
        length[ts.step] += ts.result.volume_mm3;
        if (cut_tops) (*cut_tops)[ts.step] = std::max((*cut_tops)[ts.step], ts.result.cut_top_mm);
        stats_.columns_visited += ts.result.columns_visited;
        stats_.cells_tested += ts.result.cells_tested;
      }
      tile_steps_[tile].clear();
    }
  }

  // How many of a tile's steps from `e` on are vertical steps of one tool on one axis (a
  // plunge's or a peck's steps): 1 where step e is not followed by such.
  static std::size_t plunge_run(const std::vector<TileStep>& list, std::size_t e,
                                const std::vector<SweptStep>& swept) {
    const SweptStep& first = swept[list[e].step];
    std::size_t n = 1;
    if (!first.vertical()) return n;
    while (e + n < list.size() && first.same_axis(swept[list[e + n].step]))
      ++n;
    return n;
  }

  // Steps run[0..n) of one tile, vertical steps on one axis (plunge_run), applied column by
  // column rather than step by step: a column's envelope differs from step to step only by the
  // step's lowest tip, so its offset is worked out once for all of them. A step changes only the
  // columns it cuts, so each column ends as the steps in order leave it, and each step sums its
  // columns in the order visit_tile does: the same numbers bit for bit, for a fraction of the
  // work (a drill's peck at a fine grid is hundreds of steps over the same disc of columns).
  void cut_plunge(TileStep* run, std::size_t n, const std::vector<SweptStep>& swept,
                  const FootprintRange& f, int* rows, int ti, int tj, std::size_t tile) {
    const SweptStep& axis = swept[run[0].step];
    std::vector<double> tips(n); // each step's lowest tip, at hand for the column loop
    for (std::size_t s = 0; s < n; ++s)
      tips[s] = swept[run[s].step].lowest_tip_z();
    const double lowest = *std::min_element(tips.begin(), tips.end());
    if (tile_top_[tile] <= lowest) return; // no material above the tool in this tile
    const int ia = std::max(f.i0, ti * kTileColumns);
    const int ib = std::min(f.i1, ti * kTileColumns + kTileColumns - 1);
    const int ja = std::max(f.j0, tj * kTileColumns);
    const int jb = std::min(f.j1, tj * kTileColumns + kTileColumns - 1);
    bool cut = false;
    for (int j = ja; j <= jb; ++j, rows += 2) {
      if (row_clear(tile, j, lowest)) continue;
      const int* span = RowSpans::span(rows, axis, j, grid_);
      const int a = std::max(ia, span[0]);
      const int b = std::min(ib, span[1]);
      if (a > b) continue;
      for (std::size_t s = 0; s < n; ++s)
        run[s].result.columns_visited += std::uint64_t(b - a + 1);
      const double y = grid_.column_y(j);
      const std::size_t row = std::size_t(j) * std::size_t(grid_.nx);
      for (int i = a; i <= b; ++i) {
        const std::size_t c = row + std::size_t(i);
        double top = top_[c];
        if (top <= lowest) continue;
        const double offset = axis.plunge_offset(grid_.column_x(i), y);
        for (std::size_t s = 0; s < n; ++s) {
          // cut_column's steps, with the envelope lowest tip + offset.
          if (top <= tips[s]) continue;
          TileResult& acc = run[s].result;
          ++acc.cells_tested;
          const double env = tips[s] + offset;
          if (env >= top) continue;
          acc.cut_top_mm = std::max(acc.cut_top_mm, top);
          acc.volume_mm3 += clip_column(c, env);
          top = top_[c];
          cut = true;
        }
      }
    }
    if (cut) refresh_tile_top(tile);
  }

  // Cuts column c down to the step's envelope.
  void cut_column(const SweptStep& step, double zlow, std::size_t c, double x, double y,
                  TileResult& acc) {
    // The tool bottom never goes below the lowest tip: columns already at or below it need no
    // envelope.
    if (top_[c] <= zlow) return;
    ++acc.cells_tested;
    const double e = step.envelope_at(x, y);
    if (e >= top_[c]) return;
    acc.cut_top_mm = std::max(acc.cut_top_mm, top_[c]);
    acc.volume_mm3 += clip_column(c, e);
  }

  // The tile's highest column top, and that of each of its rows, after its columns were cut.
  void refresh_tile_top(std::size_t tile) {
    const int across = tiles_across(grid_);
    const int ti = int(tile % std::size_t(across));
    const int ia = ti * kTileColumns;
    const int ja = int(tile / std::size_t(across)) * kTileColumns;
    const int ib = std::min(grid_.nx, ia + kTileColumns),
              jb = std::min(grid_.ny, ja + kTileColumns);
    double t = kNoMaterial;
    for (int j = ja; j < jb; ++j) {
      const double* row = top_.data() + std::size_t(j) * std::size_t(grid_.nx);
      double r = kNoMaterial;
      for (int i = ia; i < ib; ++i)
        r = std::max(r, row[i]);
      row_top_[tile * kTileColumns + std::size_t(j - ja)] = r;
      t = std::max(t, r);
    }
    tile_top_[tile] = t;
  }

  // Removes the material of column c above z; returns the length removed.
  double clip_column(std::size_t c, double z) {
    double removed = 0;
    std::uint16_t n = count_[c];
    while (n > 0) {
      ZInterval& iv = intervals_[first_[c] + n - 1];
      if (iv.lo >= z) { // the whole interval is above the tool
        removed += iv.hi - iv.lo;
        --n;
        continue;
      }
      if (iv.hi > z) {
        removed += iv.hi - z;
        iv.hi = z;
      }
      break;
    }
    count_[c] = n;
    top_[c] = n ? intervals_[first_[c] + n - 1].hi : kNoMaterial;
    return removed;
  }

  GridFrame grid_;
  std::vector<ZInterval> intervals_;
  std::vector<std::uint32_t> first_;
  std::vector<std::uint16_t> count_;
  std::vector<double> top_;      // top of each column's material: most columns stop here
  std::vector<double> tile_top_; // highest top_ in each tile: whole tiles stop here
  std::vector<double> row_top_;  // highest top_ on each grid row of each tile, tile by tile
  std::vector<TileResult> scratch_;
  std::vector<std::vector<TileStep>> tile_steps_; // remove_steps: each tile's steps, in order
  EngineStats stats_;
};

} // namespace

std::unique_ptr<RemovalEngine> make_dexel_engine(const StockShape& stock, const GridFrame& grid) {
  return std::make_unique<DexelEngine>(stock, grid);
}

} // namespace ncjoule::detail
