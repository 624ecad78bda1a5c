// The nine straight cuts of Anziani's Table 2: a 12 mm flat end mill cutting 155 mm of stock
// at a given axial depth, radial width and feed. The stock is exactly the material the cut
// should take (a strip `width` wide along the tool's side, `depth` deep), so the steady MRR
// must be depth * width * feed.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

#include "fixture.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

struct Table2Cut {
  int test;
  double depth_mm, width_mm, feed_mm_min;
};
constexpr Table2Cut kCuts[] = {{1, 3.0, 0.50, 120}, {2, 6.0, 1.50, 120}, {3, 9.0, 2.00, 120},
                               {4, 6.0, 0.50, 180}, {5, 9.0, 1.50, 180}, {6, 3.0, 2.00, 180},
                               {7, 9.0, 0.50, 240}, {8, 3.0, 1.50, 240}, {9, 6.0, 2.00, 240}};
constexpr double kLength = 155, kRadius = 6;

} // namespace

namespace {
// Steady-state MRR of one cut, and the checks on its transients. `step` is the planner's sample
// spacing; the default is what removal asks for.
void check_cut(const Table2Cut& cut, double step, double tolerance, bool check_transients) {
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 2 * kRadius)}};
  {
    CAPTURE(cut.test);
    // Tool centre on y = 0 moving +X; its side at y = R takes the strip [R - width, R].
    const Box3 stock{0, kRadius - cut.width_mm, -cut.depth_mm - 5, kLength, kRadius, 0};
    ProgramBuilder p;
    p.tool(1).feed_rate(cut.feed_mm_min);
    p.rapid(-kRadius - 2, 0, 5).rapid(-kRadius - 2, 0, -cut.depth_mm);
    p.feed(kLength + kRadius + 2, 0, -cut.depth_mm);
    p.rapid(kLength + kRadius + 2, 0, 5);
    const Timeline tl = constant_speed_timeline(p.commands(), step);
    StockSpec spec;
    spec.kind = StockSpec::Kind::Box;
    spec.box = stock;
    // The finest automatic grid (d/120): what the bounds below are worked out for.
    RemovalOptions options;
    options.grid_mm = default_grid_spacing(tools);
    const RemovalResult r = simulate_removal(p.commands(), tl, tools, spec, options);
    REQUIRE(r.diagnostics.empty());

    const double expected = cut.depth_mm * cut.width_mm * cut.feed_mm_min / 60.0;
    const TimedCommand& cutting = tl.commands[2];
    const CommandRemoval& cr = r.commands[2];
    REQUIRE(cr.step_volume_mm3.size() + 1 == cutting.samples.size());

    // Steady state: steps with the tool centre well inside [R, L - R].
    double volume = 0, time = 0;
    std::vector<double> mrr(cr.step_volume_mm3.size());
    for (std::size_t s = 0; s < mrr.size(); ++s) {
      const double dt = cutting.samples[s + 1].t_s - cutting.samples[s].t_s;
      mrr[s] = cr.step_volume_mm3[s] / dt;
      const double x0 = cutting.samples[s].position.x, x1 = cutting.samples[s + 1].position.x;
      if (x0 >= kRadius && x1 <= kLength - kRadius) volume += cr.step_volume_mm3[s], time += dt;
    }
    const double steady = volume / time;
    const double error = std::abs(steady - expected) / expected;
    report("table2 test " + std::to_string(cut.test) + " step " + std::to_string(step) +
               " steady MRR relative error",
           error);
    CHECK(error < tolerance);
    // The whole cut removes the whole strip.
    CHECK(r.removed_mm3 == doctest::Approx(kLength * cut.width_mm * cut.depth_mm).epsilon(1e-9));
    CHECK(r.commands[0].removed_mm3 == 0);
    CHECK(r.commands[1].removed_mm3 == 0);
    CHECK(r.commands[3].removed_mm3 == 0);
    if (!check_transients) return;

    // Entry: MRR rises from zero through intermediate values to the steady value, never
    // falling on the way; exit: the mirror image.
    std::size_t first = 0;
    while (first < mrr.size() && mrr[first] == 0)
      ++first;
    std::size_t full = first;
    while (full < mrr.size() && mrr[full] < expected * (1 - 1e-4))
      ++full;
    REQUIRE(full < mrr.size());
    CHECK(full > first + 1); // a visible ramp, more than one step long
    CHECK(mrr[first] < 0.5 * expected);
    for (std::size_t s = first; s < full; ++s)
      CHECK(mrr[s + 1] >= mrr[s] * (1 - 1e-9));
    std::size_t last = mrr.size() - 1;
    while (mrr[last] == 0)
      --last;
    std::size_t leave = last;
    while (leave > 0 && mrr[leave] < expected * (1 - 1e-4))
      --leave;
    CHECK(last > leave + 1);
    CHECK(mrr[last] < 0.5 * expected);
    for (std::size_t s = leave; s < last; ++s)
      CHECK(mrr[s + 1] <= mrr[s] * (1 + 1e-9));
    CHECK(cr.mrr_peak_mm3_s == doctest::Approx(expected).epsilon(1e-3));
    CHECK(cr.mrr_mean_mm3_s < expected); // the mean over the move includes air and transients
  }
}
} // namespace

TEST_CASE("Anziani Table 2 cuts: steady MRR and entry/exit transients") {
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 2 * kRadius)}};
  const double step = recommended_sample_step(tools, default_grid_spacing(tools));
  for (const Table2Cut& cut : kCuts)
    check_cut(cut, step, 1e-4, true);
}

TEST_CASE("Anziani Table 2 cuts sampled off the grid's pitch") {
  // Steps that are a multiple of the grid's pitch cross the same number of columns every
  // step: the mean is exact. Other steps cross a column in one step or the next, so the mean
  // over a window is off by at most one cell per row at each end of the window
  // (0.1 mm / 143 mm = 7e-4 for one row); with several rows at different phases it stays well
  // below that.
  for (const Table2Cut& cut : kCuts) {
    check_cut(cut, 0.5, 1e-4, false);
    check_cut(cut, 0.0731, 2.5e-4, false);
    check_cut(cut, 0.3173, 2.5e-4, false);
  }
}
