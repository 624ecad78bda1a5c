// Removed volume against closed-form volumes, at the default grid.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "fixture.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

constexpr double kPi = std::numbers::pi;

StockSpec box_stock(const Box3& b) {
  StockSpec s;
  s.kind = StockSpec::Kind::Box;
  s.box = b;
  return s;
}

// Runs the program with the planner step removal asks for at the default grid.
RemovalResult run(const ProgramBuilder& p, const std::map<int, Tool>& tools, const Box3& stock,
                  EngineKind engine = EngineKind::Dexel, double grid = 0,
                  double step_override = -1) {
  RemovalOptions o;
  o.engine = engine;
  o.grid_mm = grid;
  const double step =
      step_override >= 0
          ? step_override
          : recommended_sample_step(tools, grid > 0 ? grid : default_grid_spacing(tools));
  return simulate_removal(p.commands(), constant_speed_timeline(p.commands(), step), tools,
                          box_stock(stock), o);
}

double relative_error(double got, double want) {
  return std::abs(got - want) / want;
}

} // namespace

TEST_CASE("full-width slot with a plunge: cylinder plus slot") {
  const double R = 5, depth = 4, L = 50;
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 2 * R)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(300).rapid(0, 0, 5).feed(0, 0, -depth).feed(L, 0, -depth).rapid(L, 0, 5);
  const RemovalResult r = run(p, tools, {-20, -20, -10, 80, 20, 0});
  const double plunge = kPi * R * R * depth;
  const double want = plunge + 2 * R * L * depth;
  report("slot+plunge relative error", relative_error(r.removed_mm3, want));
  CHECK(relative_error(r.removed_mm3, want) < 2e-3);
  CHECK(relative_error(r.commands[1].removed_mm3, plunge) < 2e-3); // the plunge alone
  CHECK(r.commands[0].removed_mm3 == 0);
  CHECK(r.commands[3].removed_mm3 == 0); // retracting through its own slot
}

TEST_CASE("a full circle of a flat end mill cuts an annulus") {
  const double R = 3, Rc = 15, depth = 2;
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 2 * R)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(600).rapid(Rc, 0, 5).feed(Rc, 0, -depth);
  p.arc(Rc, 0, -depth, 0, 0, +1).rapid(Rc, 0, 5);
  const RemovalResult r = run(p, tools, {-25, -25, -5, 25, 25, 0});
  const double want = kPi * ((Rc + R) * (Rc + R) - (Rc - R) * (Rc - R)) * depth;
  report("annulus relative error", relative_error(r.removed_mm3, want));
  CHECK(relative_error(r.removed_mm3, want) < 2e-3);
}

TEST_CASE("a ball-nose groove: a half cylinder plus one sphere's worth of ends") {
  const double R = 4, L = 40;
  const std::map<int, Tool> tools{{1, ball_end_mill(1, 2 * R)}};
  SUBCASE("sunk to the ball's centre") {
    ProgramBuilder p;
    p.tool(1).feed_rate(300).rapid(0, 0, 5).feed(0, 0, -R).feed(L, 0, -R).rapid(L, 0, 5);
    const RemovalResult r = run(p, tools, {-10, -10, -8, 50, 10, 0});
    // Half cylinder along the groove; the two ends are quarter spheres, a hemisphere together.
    const double want = kPi * R * R / 2 * L + 2.0 / 3.0 * kPi * R * R * R;
    report("ball groove (depth R) relative error", relative_error(r.removed_mm3, want));
    CHECK(relative_error(r.removed_mm3, want) < 2e-3);
  }
  SUBCASE("shallower than the radius") {
    const double d = 2.5;
    ProgramBuilder p;
    p.tool(1).feed_rate(300).rapid(0, 0, 5).feed(0, 0, -d).feed(L, 0, -d).rapid(L, 0, 5);
    const RemovalResult r = run(p, tools, {-10, -10, -8, 50, 10, 0});
    // Circular segment swept along the groove, plus a spherical cap (half at each end).
    const double segment = R * R * std::acos((R - d) / R) - (R - d) * std::sqrt(2 * R * d - d * d);
    const double cap = kPi * d * d * (3 * R - d) / 3;
    const double want = segment * L + cap;
    report("ball groove (depth 2.5) relative error", relative_error(r.removed_mm3, want));
    CHECK(relative_error(r.removed_mm3, want) < 2e-3);
    CHECK(relative_error(r.commands[1].removed_mm3, cap) < 2e-3);
  }
}

TEST_CASE("a drilled hole with a 118-degree point: cylinder plus cone") {
  const double R = 4, depth = 10; // depth of the tip below the top
  const std::map<int, Tool> tools{{1, drill(1, 2 * R, 118)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(120).rapid(0, 0, 3).feed(0, 0, -depth).rapid(0, 0, 3);
  const RemovalResult r = run(p, tools, {-10, -10, -15, 10, 10, 0});
  const double cone = R / std::tan(59 * kPi / 180);
  const double want = kPi * R * R * (depth - cone) + kPi * R * R * cone / 3;
  report("drill relative error", relative_error(r.removed_mm3, want));
  CHECK(relative_error(r.removed_mm3, want) < 2e-3);
}

TEST_CASE("a straight ramp of a flat end mill: a wedge plus the cylinder at its end") {
  const double R = 5, depth = 3, L = 40;
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 2 * R)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(300).rapid(0, 0, 5).feed(0, 0, 0).feed(L, 0, -depth).rapid(L, 0, 5);
  const RemovalResult r = run(p, tools, {-10, -10, -8, 50, 10, 0});
  // Each row across the ramp: depth grows linearly over L, then the end disc at full depth.
  const double want = R * depth * L + kPi * R * R * depth;
  report("ramp relative error", relative_error(r.removed_mm3, want));
  CHECK(relative_error(r.removed_mm3, want) < 2e-3);
}

TEST_CASE("long steps are swept exactly: samples only at the end points miss nothing") {
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 10)}, {2, ball_end_mill(2, 8)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(300).rapid(0, 0, 5).feed(0, 0, -4).feed(50, 0, -4).feed(50, 20, -6);
  p.rapid(50, 20, 5).tool(2).rapid(0, 20, 5).feed(0, 20, 0).feed(30, 10, -3).rapid(30, 10, 5);
  const Box3 stock{-10, -10, -10, 60, 30, 0};
  const RemovalResult fine = run(p, tools, stock);
  const RemovalResult ends = run(p, tools, stock, EngineKind::Dexel, 0, 0); // one step per move
  for (std::size_t k = 0; k < fine.commands.size(); ++k) {
    CAPTURE(k);
    CHECK(ends.commands[k].removed_mm3 ==
          doctest::Approx(fine.commands[k].removed_mm3).epsilon(1e-9));
  }
  CHECK(fine.removed_mm3 > 0);
}

TEST_CASE("volume error against the grid spacing, from a 120th to a tenth of the diameter") {
  // The automatic grid ranges from d/120 to d/20 (automatic_grid_spacing): finer for short
  // programs, coarser for long ones; d/10 is as coarse as --grid is sensible.
  // bench/grid_accuracy.sh prints the table; the bounds here hold with room to spare.
  struct Case {
    const char* name;
    std::map<int, Tool> tools;
    ProgramBuilder program;
    Box3 stock;
    double want;
  };
  std::vector<Case> cases;
  {
    const double R = 5, depth = 4, L = 50;
    ProgramBuilder p;
    p.tool(1).feed_rate(300).rapid(0, 0, 5).feed(0, 0, -depth).feed(L, 0, -depth).rapid(L, 0, 5);
    cases.push_back({"slot with a plunge, 10 mm flat",
                     {{1, flat_end_mill(1, 2 * R)}},
                     p,
                     {-20, -20, -10, 80, 20, 0},
                     kPi * R * R * depth + 2 * R * L * depth});
  }
  {
    const double R = 3, Rc = 15, depth = 2;
    ProgramBuilder p;
    p.tool(1).feed_rate(600).rapid(Rc, 0, 5).feed(Rc, 0, -depth);
    p.arc(Rc, 0, -depth, 0, 0, +1).rapid(Rc, 0, 5);
    cases.push_back({"annulus, 6 mm flat",
                     {{1, flat_end_mill(1, 2 * R)}},
                     p,
                     {-25, -25, -5, 25, 25, 0},
                     kPi * ((Rc + R) * (Rc + R) - (Rc - R) * (Rc - R)) * depth});
  }
  {
    const double R = 4, L = 40;
    ProgramBuilder p;
    p.tool(1).feed_rate(300).rapid(0, 0, 5).feed(0, 0, -R).feed(L, 0, -R).rapid(L, 0, 5);
    cases.push_back({"ball groove, 8 mm ball",
                     {{1, ball_end_mill(1, 2 * R)}},
                     p,
                     {-10, -10, -8, 50, 10, 0},
                     kPi * R * R / 2 * L + 2.0 / 3.0 * kPi * R * R * R});
  }
  {
    const double R = 4, depth = 10;
    ProgramBuilder p;
    p.tool(1).feed_rate(120).rapid(0, 0, 3).feed(0, 0, -depth).rapid(0, 0, 3);
    const double cone = R / std::tan(59 * kPi / 180);
    cases.push_back({"drilled hole, 8 mm 118 deg",
                     {{1, drill(1, 2 * R, 118)}},
                     p,
                     {-10, -10, -15, 10, 10, 0},
                     kPi * R * R * (depth - cone) + kPi * R * R * cone / 3});
  }
  for (const Case& c : cases) {
    const double diameter = c.tools.begin()->second.diameter_mm;
    for (const auto& [divisor, bound] : std::vector<std::pair<double, double>>{
             {120, 2e-3}, {60, 4e-3}, {40, 6e-3}, {20, 1.2e-2}, {10, 5e-2}}) {
      const double grid = diameter / divisor;
      const RemovalResult r = run(c.program, c.tools, c.stock, EngineKind::Dexel, grid);
      const double error = relative_error(r.removed_mm3, c.want);
      report(std::string("grid accuracy | ") + c.name + " | d/" + std::to_string(int(divisor)) +
                 " | " + std::to_string(grid),
             error);
      CAPTURE(c.name);
      CAPTURE(divisor);
      CHECK(error < bound);
    }
  }
}
