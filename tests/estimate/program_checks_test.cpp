// What the estimate says of a program's geometry: a program posted for a machine whose +Z points
// into the work (its removal mirrored), arcs that turn the long way round (G2 and G3 swapped by
// a post), and a rotary axis that 3-axis removal cannot follow.
#include <doctest/doctest.h>

#include <cmath>

#include "estimate_checks.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"

using namespace ncjoule;
using namespace estimate_test;

namespace {

// Two passes of a 6 mm slot, 1.5 and 3 mm deep, with rapids at the clearance `up` mm from the
// top: `z` is +1 for a standard machine, -1 for one whose +Z points into the work (Estlcam's
// "Scale z=-1" writes the same program with every Z negated).
std::string two_pass_slot(double z, double up = 5) {
  char text[512];
  std::snprintf(text, sizeof text,
                "G21 G90 G17\n(T1 D=6. CR=0. - ZMIN=-3. - FLAT END MILL)\nT1 M6\nS8000 M3\n"
                "G0 Z%g\nG0 X-10 Y0\nG1 Z%g F100\nG1 X60 F600\nG0 Z%g\nG0 X-10\nG1 Z%g F100\n"
                "G1 X60 F600\nG0 Z%g\nM5\nM30\n",
                z * up, -z * 1.5, z * up, -z * 3, z * up);
  return text;
}

} // namespace

TEST_CASE("a program posted for a machine whose +Z points into the work") {
  const MachineProfile machine = generic();
  const Estimate up = estimate_program(make_source("up.nc", two_pass_slot(1)), machine, {});
  const Estimate down = estimate_program(make_source("down.nc", two_pass_slot(-1)), machine, {});
  REQUIRE(up.removal);
  REQUIRE(down.removal);
  CHECK_FALSE(warned(up, "every rapid across XY runs below the cuts"));
  CHECK(warned(down, "every rapid across XY runs below the cuts"));
  CHECK_FALSE(warned(down, "collision"));
  CHECK_FALSE(mentioned(down, "a CAM rapids through air")); // no rapid enters the default stock
  // The mirrored program removes what its twin does (the second pass: 1.5 mm of a 6 mm slot
  // over the default stock's 76 mm), in the same time.
  CHECK(up.energy.removed_mm3 > 100);
  CHECK(down.energy.removed_mm3 == doctest::Approx(up.energy.removed_mm3).epsilon(1e-9));
  CHECK(down.time_s == doctest::Approx(up.time_s).epsilon(1e-12));
  CHECK(down.removal->stock_description.find("Z mirrored") != std::string::npos);

  SUBCASE("a stock given in the program's coordinates") {
    EstimateOptions up_stock, down_stock;
    up_stock.stock = parse_stock_spec("box:-20,-10,-10,80,10,0");
    down_stock.stock = parse_stock_spec("box:-20,-10,0,80,10,10");
    const Estimate a = estimate_program(make_source("up.nc", two_pass_slot(1)), machine, up_stock);
    const Estimate b =
        estimate_program(make_source("down.nc", two_pass_slot(-1)), machine, down_stock);
    // A 6 mm slot 3 mm deep from X-10 to X60, in two passes, inside the stock.
    CHECK(a.energy.removed_mm3 > 1000);
    CHECK(b.energy.removed_mm3 == doctest::Approx(a.energy.removed_mm3).epsilon(1e-9));
    CHECK_FALSE(warned(b, "collision"));
  }
  SUBCASE("the profile says which way Z points") {
    MachineProfile told = machine;
    told.kinematics.z_positive = ZDirection::Up;
    const Estimate as_up = estimate_program(make_source("down.nc", two_pass_slot(-1)), told, {});
    CHECK_FALSE(warned(as_up, "every rapid across XY runs below the cuts"));
    CHECK(as_up.energy.removed_mm3 != doctest::Approx(up.energy.removed_mm3));
    told.kinematics.z_positive = ZDirection::Down;
    const Estimate as_down = estimate_program(make_source("down.nc", two_pass_slot(-1)), told, {});
    CHECK_FALSE(warned(as_down, "every rapid across XY runs below the cuts")); // no guess said
    CHECK(as_down.energy.removed_mm3 == doctest::Approx(up.energy.removed_mm3).epsilon(1e-9));
  }
  SUBCASE("a rapid across XY above a cut is a standard program") {
    // Rapids at Z-5 but one crossing at Z2, past the first cut at Z1.5 of a Z-down program:
    // either way Z points, some rapid crosses the cuts; nothing is guessed.
    std::string mixed = two_pass_slot(-1);
    mixed.replace(mixed.find("G0 X-10\n"), 8, "G0 Z2\nG0 X-10\n");
    const Estimate e = estimate_program(make_source("mixed.nc", mixed), machine, {});
    CHECK_FALSE(warned(e, "every rapid across XY runs below the cuts"));
  }
}

TEST_CASE("arcs that turn the long way round: G2 and G3 swapped by the post") {
  const MachineProfile machine = generic();
  // Twelve quarter circles of radius 10 around X0 Y0, then the same written the other way: a
  // post that swaps X and Y without swapping G2/G3 writes each as a three-quarter turn.
  std::string quarters = "G21 G90 G17\nG0 X10 Y0 Z1\nG1 Z-1 F100\nF600\n";
  std::string swapped = quarters;
  const char* ends[] = {"X0 Y10", "X-10 Y0", "X0 Y-10", "X10 Y0"};
  for (int k = 0; k < 12; ++k) {
    const std::string end = ends[k % 4];
    const std::string centre = k % 4 == 0   ? "I-10 J0"
                               : k % 4 == 1 ? "I0 J-10"
                               : k % 4 == 2 ? "I10 J0"
                                            : "I0 J10";
    quarters += "G3 " + end + " " + centre + "\n";
    swapped += "G2 " + end + " " + centre + "\n";
  }
  quarters += "G0 Z1\nM30\n";
  swapped += "G0 Z1\nM30\n";
  EstimateOptions options;
  options.simulate_removal = false;
  const Estimate good = estimate_program(make_source("good.nc", quarters), machine, options);
  const Estimate bad = estimate_program(make_source("bad.nc", swapped), machine, options);
  CHECK_FALSE(warned(good, "G2 and G3 look swapped"));
  CHECK(warned(bad, "G2 and G3 look swapped"));
  // The controller runs the long way: three times the path, and about three times the time.
  CHECK(bad.time_s > 2.5 * good.time_s);

  SUBCASE("whole circles and a few long arcs are meant") {
    std::string circles = "G21 G90 G17\nG0 X10 Y0 Z1\nG1 Z-1 F100\nF600\n";
    for (int k = 0; k < 12; ++k)
      circles += "G2 X10 Y0 I-10 J0\n";
    circles += "G3 X0 Y-10 I-10 J0\nG0 Z1\nM30\n"; // one three-quarter turn among whole circles
    const Estimate e = estimate_program(make_source("circles.nc", circles), machine, options);
    CHECK_FALSE(warned(e, "G2 and G3 look swapped"));
  }
}

TEST_CASE("a program that turns a rotary axis: removal is labelled an approximation") {
  const MachineProfile machine = generic();
  const std::string flat = "G21 G90 G17\n(T1 D=6. CR=0. - ZMIN=-3. - FLAT END MILL)\nT1 M6\n"
                           "S8000 M3\nG0 X-10 Y0 Z5\nG1 Z-1 F100\nG1 X60 F600\nG0 Z5\n";
  EstimateOptions options;
  options.stock = parse_stock_spec("box:-20,-10,-10,80,10,0");
  const Estimate three_axis =
      estimate_program(make_source("flat.nc", flat + "M30\n"), machine, options);
  CHECK_FALSE(warned(three_axis, "rotary axis"));
  // Turning while it cuts (4-axis): the stock does not turn in the model.
  const Estimate four_axis = estimate_program(
      make_source("b.nc", flat + "G1 Z-1 F100\nG1 B180 X-10 F600\nG0 Z5\nM30\n"), machine, options);
  CHECK(warned(four_axis, "the program turns a rotary axis (A/B/C) here"));
  for (const Diagnostic& d : four_axis.diagnostics)
    if (d.message.find("rotary axis (A/B/C) here") != std::string::npos) CHECK(d.line == 10);
  // Turned half round between cuts (3+1 indexing), the same cut again: the other side of the
  // part, a setup of its own with its own stock (setups_test.cpp), said by its reason.
  const Estimate indexed = estimate_program(
      make_source("c.nc", flat + "G0 B180\nG1 Z-1 F100\nG1 X-10 F600\nG0 Z5\nM30\n"), machine,
      options);
  REQUIRE(indexed.setups.size() == 2);
  CHECK(indexed.setups[1].reason == "the part turned: B180 (a rotary index)");
}

TEST_CASE("a program no dialect is named for is timed as its first pass read it") {
  // Nothing names a control: what only LinuxCNC refuses is warned of and run (a G28 with a
  // bare axis letter, an M0 with the operator's prompt after it). The blocks timed are the
  // blocks read, in the estimate's second pass as in its first.
  const MachineProfile machine = generic();
  const Estimate e = estimate_program(
      make_source("lenient.nc", "G21 G90\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X10\nG28 Z\n"
                                "M0 Turn ON spindle\nG0 X20\nM2\n"),
      machine, {});
  REQUIRE_FALSE(e.failed);
  CHECK(e.dialect_origin == DialectOrigin::Default);
  CHECK(warned(e, "word 'Z' has no number after it"));
  auto line = [&](int number) { // 1-based
    for (const LineSummary& l : e.lines)
      if (l.line + 1 == number) return l;
    FAIL("no summary of line " << number);
    return LineSummary{};
  };
  const LineSummary home = line(5); // G28 Z: a rapid to the home position
  CHECK(home.kind == LineKind::Rapid);
  CHECK(home.commands >= 1);
  CHECK(home.time_s > 0);
  CHECK(line(6).kind == LineKind::ProgramStop);
  CHECK(line(6).commands == 1);
}
