// The two engines against each other, determinism, air moves and collisions.
#include <doctest/doctest.h>

#include <cmath>

#include <tbb/global_control.h>

#include "fixture.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

StockSpec box_stock(const Box3& b) {
  StockSpec s;
  s.kind = StockSpec::Kind::Box;
  s.box = b;
  return s;
}

// Several tools and move kinds: a slot with a plunge, a helical entry and a circle, a ball
// ramp and groove, a drilled hole, a bull nose pass and a V-groove.
ProgramBuilder mixed_program() {
  ProgramBuilder p;
  p.tool(1).feed_rate(400).rapid(0, 0, 5).feed(0, 0, -3).feed(30, 0, -3).rapid(30, 0, 5);
  p.rapid(45, 10, 5).feed(45, 10, 0).arc(45, 10, -2, 40, 10, +1).arc(45, 10, -2, 40, 10, +1);
  p.rapid(45, 10, 5);
  p.tool(2).rapid(0, 15, 5).feed(0, 15, 0).feed(20, 18, -2.5).feed(35, 25, -2.5).rapid(35, 25, 5);
  p.tool(3).rapid(15, -12, 5).feed(15, -12, -6).rapid(15, -12, 5);
  p.tool(4).rapid(-5, 30, 5).feed(-5, 30, -1.5).feed(50, 30, -1.2).arc(50, 20, -1.2, 50, 25, -1);
  p.rapid(50, 20, 5);
  p.tool(5).rapid(0, -20, 5).feed(0, -20, -1).feed(40, -15, -1.5).rapid(40, -15, 5);
  return p;
}

std::map<int, Tool> mixed_tools() {
  Tool bull = flat_end_mill(4, 8);
  bull.shape = ToolShape::BullNose;
  bull.corner_radius_mm = 1.5;
  Tool vbit = flat_end_mill(5, 6);
  vbit.shape = ToolShape::Chamfer;
  vbit.tip_angle_deg = 90;
  return {{1, flat_end_mill(1, 10)},
          {2, ball_end_mill(2, 8)},
          {3, drill(3, 6, 118)},
          {4, bull},
          {5, vbit}};
}

const Box3 kMixedStock{-15, -30, -10, 65, 40, 0};

} // namespace

TEST_CASE("dexel and voxel engines agree on the same program") {
  const auto tools = mixed_tools();
  const ProgramBuilder p = mixed_program();
  const double grid = 0.2; // coarse enough for the voxel engine to run quickly
  const Timeline tl = constant_speed_timeline(p.commands(), recommended_sample_step(tools, grid));
  RemovalOptions o;
  o.grid_mm = grid;
  const RemovalResult dexel = simulate_removal(p.commands(), tl, tools, box_stock(kMixedStock), o);
  o.engine = EngineKind::Voxel;
  const RemovalResult voxel = simulate_removal(p.commands(), tl, tools, box_stock(kMixedStock), o);
  CHECK(dexel.diagnostics.empty());
  CHECK(voxel.diagnostics.empty());
  CHECK(voxel.engine == EngineKind::Voxel);
  REQUIRE(dexel.removed_mm3 > 1000);
  const double difference = std::abs(voxel.removed_mm3 - dexel.removed_mm3) / dexel.removed_mm3;
  report("dexel vs voxel relative difference, whole program", difference);
  CHECK(difference < 5e-3);
  // Tool by tool too, where each removes enough to compare.
  for (std::size_t k = 0; k < dexel.commands.size(); ++k) {
    const double d = dexel.commands[k].removed_mm3, v = voxel.commands[k].removed_mm3;
    if (d < 50) continue;
    CAPTURE(k);
    report("dexel vs voxel relative difference, command " + std::to_string(k), std::abs(v - d) / d);
    CHECK(std::abs(v - d) / d < 2e-2);
  }
}

TEST_CASE("results are identical run to run and whatever the number of threads") {
  // A 40 mm face mill on a fine grid: its footprint is large enough to be split over threads.
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 40)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(1000).rapid(-25, 0, 5).rapid(-25, 0, -1).feed(65, 5, -1.3);
  p.arc(65, 45, -1.3, 65, 25, +1).feed(-25, 40, -0.8).rapid(-25, 40, 5);
  const Box3 stock{0, -10, -5, 40, 50, 0};
  RemovalOptions o;
  o.grid_mm = 0.1;
  const Timeline tl = constant_speed_timeline(p.commands(), 0.5);
  const RemovalResult a = simulate_removal(p.commands(), tl, tools, box_stock(stock), o);
  const RemovalResult b = simulate_removal(p.commands(), tl, tools, box_stock(stock), o);
  RemovalResult one_thread;
  {
    tbb::global_control serial(tbb::global_control::max_allowed_parallelism, 1);
    one_thread = simulate_removal(p.commands(), tl, tools, box_stock(stock), o);
  }
  REQUIRE(a.removed_mm3 > 0);
  CHECK(a.removed_mm3 == b.removed_mm3);
  CHECK(a.removed_mm3 == one_thread.removed_mm3);
  for (std::size_t k = 0; k < a.commands.size(); ++k) {
    CHECK(a.commands[k].step_volume_mm3 == b.commands[k].step_volume_mm3);
    CHECK(a.commands[k].step_volume_mm3 == one_thread.commands[k].step_volume_mm3);
  }
}

TEST_CASE("air moves remove nothing: a rapid through the stock is a collision") {
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 6)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(300).rapid(-10, 0, 2).feed(30, 0, 0.5); // feeding above the stock
  p.rapid(30, 0, -2).rapid(-10, 0, -2);                       // a rapid along Z -2 through it
  const RemovalResult r = simulate_removal(p.commands(), constant_speed_timeline(p.commands(), 0.1),
                                           tools, box_stock({0, -10, -5, 20, 10, 0}));
  CHECK(r.commands[1].removed_mm3 == 0);
  CHECK_FALSE(r.commands[1].collision);
  CHECK(r.commands[2].removed_mm3 == 0); // beside the stock
  CHECK_FALSE(r.commands[2].collision);
  CHECK(r.commands[3].removed_mm3 == doctest::Approx(20 * 6 * 2).epsilon(2e-3));
  CHECK(r.commands[3].collision);
  REQUIRE(r.diagnostics.size() == 1);
  CHECK(r.diagnostics[0].severity == Severity::Warning);
  CHECK(r.diagnostics[0].line == p.commands()[3].line + 1);
  CHECK(r.diagnostics[0].message.find("collision") != std::string::npos);
}

TEST_CASE("a rapid into a guessed stock marks the guess too large there, not a collision") {
  // An adaptive's entry outside the part: a pass at Z0 (the guessed top), then the tool rapids
  // down beside the second pass's start at X-1 and feeds in at Z-3. The default box is the cuts
  // widened by the tool's radius, so the rapid comes down inside it. Given as the stock, the
  // same box makes it a collision.
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 6)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(300).rapid(0, 0, 5).rapid(0, 0, 1).feed(0, 0, 0).feed(30, 0, 0);
  p.rapid(30, 0, 5).rapid(-1, 0, 5).rapid(-1, 0, -2); // [6]: down beside the cut
  p.feed(-1, 0, -3).feed(30, 0, -3).rapid(30, 0, 5);
  const Timeline timeline = constant_speed_timeline(p.commands(), 0.1);
  const RemovalResult guessed =
      simulate_removal(p.commands(), timeline, tools, StockSpec{}); // the default box
  REQUIRE(guessed.stock_source == StockSource::Guessed);
  CHECK(guessed.stock_box.xmin == doctest::Approx(-4));
  CHECK(guessed.stock_box.zmin == doctest::Approx(-3));
  CHECK(guessed.stock_box.zmax == doctest::Approx(0));
  // The rapid from Z0 to Z-2 passes through a disk of the box: air, no volume, no collision.
  CHECK(guessed.commands[6].removed_mm3 == 0);
  CHECK_FALSE(guessed.commands[6].collision);
  REQUIRE(guessed.diagnostics.size() == 1);
  CHECK(guessed.diagnostics[0].severity == Severity::Note);
  CHECK(guessed.diagnostics[0].line == p.commands()[6].line + 1);
  CHECK(guessed.diagnostics[0].message.find("where 1 rapid goes (line ") != std::string::npos);
  CHECK(guessed.stock_description.find("trimmed where 1 rapid enters it") != std::string::npos);
  // The volume the rapid passed through is not counted anywhere, and the feed that follows
  // finds it gone.
  double sum = 0;
  for (const CommandRemoval& c : guessed.commands)
    sum += c.removed_mm3;
  CHECK(guessed.removed_mm3 == doctest::Approx(sum));

  const RemovalResult given =
      simulate_removal(p.commands(), timeline, tools, box_stock(guessed.stock_box));
  // The whole 6 mm disk, 2 mm deep: 56.5 mm^3, a collision.
  CHECK(given.commands[6].collision);
  CHECK(given.commands[6].removed_mm3 == doctest::Approx(3.14159265 * 9 * 2).epsilon(0.02));
  CHECK(given.removed_mm3 ==
        doctest::Approx(guessed.removed_mm3 + given.commands[6].removed_mm3).epsilon(1e-9));
}

TEST_CASE("grid and sample step helpers") {
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 12)}, {2, ball_end_mill(2, 3)}};
  CHECK(default_grid_spacing(tools) == doctest::Approx(3.0 / 120));
  // Steps: a quarter of the smallest radius (0.375 mm), as a whole number of grid pitches, at
  // least one pitch, and no longer than 1 mm unless the grid is coarser.
  CHECK(recommended_sample_step(tools, 0.5) == doctest::Approx(0.5));
  CHECK(recommended_sample_step(tools, 0.1) == doctest::Approx(0.4));
  CHECK(recommended_sample_step(tools, 0.025) == doctest::Approx(0.375));
  CHECK(recommended_sample_step({{1, flat_end_mill(1, 20)}}, 0.1) == doctest::Approx(1.0));
  CHECK(recommended_sample_step({{1, flat_end_mill(1, 20)}}, 1.5) == doctest::Approx(1.5));
  const GridFrame g = make_grid({0, 0, 0, 155, 2, 1}, 0.1);
  CHECK(g.nx == 1550);
  CHECK(g.ny == 20);
  CHECK(g.dx * g.nx == doctest::Approx(155));
}

TEST_CASE("a step grazing the stock within rounding removes nothing, a thin real cut counts") {
  // A pass 1e-13 mm into the top removes 6e-12 mm^3 by the geometry: below the stock model's
  // rounding, which C libraries do differently. It is air, on every system; a pass 1 um deep
  // (6e-3 mm^3 over 10 mm) is a cut.
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 6)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(300).rapid(5, 0, 2).feed(5, 0, -1e-13).feed(15, 0, -1e-13);
  p.rapid(15, 0, 2).rapid(5, 5, 2).feed(5, 5, -1e-3).feed(15, 5, -1e-3).rapid(15, 5, 2);
  for (const EngineKind engine : {EngineKind::Dexel, EngineKind::Voxel}) {
    CAPTURE(engine_name(engine));
    RemovalOptions o;
    o.engine = engine;
    const RemovalResult r =
        simulate_removal(p.commands(), constant_speed_timeline(p.commands(), 0.1), tools,
                         box_stock({0, -10, -5, 20, 10, 0}), o);
    CHECK(r.commands[1].removed_mm3 == 0);
    CHECK(r.commands[2].removed_mm3 == 0);
    for (const double v : r.commands[2].step_volume_mm3)
      CHECK(v == 0);
    CHECK(r.commands[6].removed_mm3 > 1e-3);
  }
}

TEST_CASE("removing batch after batch into the same results gives every result anew") {
  // A stream removes each batch into the results of one it is done with (their step vectors'
  // memory reused): nothing of what they held may carry over, neither into a cut nor into a move
  // that removes nothing (the V-bit's, left out of the tools). Batches of 3 moves into one dirty
  // vector against the whole program at once.
  auto tools = mixed_tools();
  tools.erase(5);
  const ProgramBuilder p = mixed_program();
  const Timeline tl = constant_speed_timeline(p.commands(), recommended_sample_step(tools, 0.2));
  RemovalOptions o;
  o.grid_mm = 0.2;
  const RemovalResult whole = simulate_removal(p.commands(), tl, tools, box_stock(kMixedStock), o);
  REQUIRE(whole.removed_mm3 > 1000);

  StockExtent extent;
  for (const CanonCommand& c : p.commands())
    extent.add(c);
  RemovalSimulator simulator(box_stock(kMixedStock), extent, tools, o);
  REQUIRE(simulator.ready());
  std::vector<CommandRemoval> out, all;
  for (std::size_t first = 0; first < tl.commands.size(); first += 3) {
    std::vector<TimedMove> moves;
    for (std::size_t k = first; k < std::min(first + 3, tl.commands.size()); ++k)
      moves.push_back({k, &p.commands()[tl.commands[k].command], &tl.commands[k]});
    for (CommandRemoval& r : out) { // what the last batch left, made dirtier still
      r.removed_mm3 = r.mrr_peak_mm3_s = 1e9;
      r.collision = true;
      r.step_volume_mm3.assign(r.step_volume_mm3.size() + 2, 7.0);
      r.step_depth_mm.assign(r.step_depth_mm.size() + 2, 7.0f);
    }
    simulator.remove(moves, out);
    REQUIRE(out.size() == moves.size());
    all.insert(all.end(), out.begin(), out.end());
  }
  REQUIRE(all.size() == whole.commands.size());
  std::size_t differing = 0, cutting = 0;
  for (std::size_t k = 0; k < all.size(); ++k) {
    const CommandRemoval &a = all[k], &b = whole.commands[k];
    cutting += b.removed_mm3 > 0;
    differing += !(a.step_volume_mm3 == b.step_volume_mm3 && a.step_depth_mm == b.step_depth_mm &&
                   a.removed_mm3 == b.removed_mm3 && a.mrr_mean_mm3_s == b.mrr_mean_mm3_s &&
                   a.mrr_peak_mm3_s == b.mrr_peak_mm3_s && a.collision == b.collision);
  }
  CHECK(cutting > 5);
  CHECK(differing == 0);
}
