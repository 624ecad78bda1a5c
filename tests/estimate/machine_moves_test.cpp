// Moves in machine coordinates (G53, G28/G30) as the machine runs them: without work offsets Z
// home is above the work, with them the moves land where the offsets put them; travel limits,
// work offsets nothing describes, and programs that set no units.
#include <doctest/doctest.h>

#include <cmath>

#include "estimate_checks.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"

using namespace ncjoule;
using namespace estimate_test;

namespace {

// A Fusion-for-Haas-like program: home Z at the start, a 1 mm deep slot at F480 with a 20 mm
// face mill positioned by high-feed G1 F5000 moves, G53 Z home between operations and at the
// end. `home` is the line the post writes for Z home.
std::string haas_program(const std::string& home) {
  return "%\nO1001 (SLOT)\n(T1 D=20. CR=0. - ZMIN=-1. - FACE MILL)\nG90 G94 G17 G40 G49 G80\n"
         "G21\n" +
         home +
         "\nT1 M6\nS6000 M3\nG54\nG0 X-20 Y0\nG43 Z15 H1\nG1 Z5 F5000\nG1 Z-1 F300\n"
         "G1 X100 F480\nG1 Z5 F5000\n" +
         home + "\nG1 X-20 Y30 F5000\nG1 Z-1 F300\nG1 X100 F480\n" + home + "\nM5\nM30\n%\n";
}

} // namespace

TEST_CASE("without work offsets, G53 Z0 and G91 G28 Z0 go up to Z home, not down to work Z0") {
  const MachineProfile machine = generic();
  for (const char* home : {"G53 G0 Z0.", "G28 G91 Z0.\nG90"}) {
    CAPTURE(home);
    const Estimate e = estimate_program(make_source("o1001.nc", haas_program(home)), machine, {});
    REQUIRE_FALSE(e.failed);
    CHECK_FALSE(warned(e, "collision"));
    CHECK_FALSE(mentioned(e, "a CAM rapids through air"));
    CHECK_FALSE(warned(e, "rated power"));
    // The default stock: its top at Z0, its bottom the passes' level Z-1; the positioning at
    // F5000 and the moves from Z home neither raise it (a stock up to Z home or Z5 would make
    // the face mill cut 6 mm deep at 5000 mm/min) nor cut. The passes clear the area between
    // them (their path's extent, Y0 to Y30): each cuts the half of its 20 mm width inside it,
    // 1 mm deep over X-20 to X100.
    REQUIRE(e.removal);
    CHECK(e.removal->stock_box.zmax == 0);
    CHECK(e.removal->stock_box.zmin == -1);
    CHECK(e.energy.removed_mm3 == doctest::Approx(2 * 120 * 10 * 1).epsilon(0.02));
  }
}

TEST_CASE("with a stock, the positioning after Z home removes nothing and the passes cut") {
  const MachineProfile machine = generic();
  EstimateOptions options;
  // The block's top is 2 mm above the program's Z0: a move sent to work Z0 would be inside it.
  options.stock = parse_stock_spec("box:-10,-10,-5,90,40,2");
  for (const char* home : {"G53 G0 Z0.", "G28 G91 Z0.\nG90"}) {
    CAPTURE(home);
    const Estimate e =
        estimate_program(make_source("o1001.nc", haas_program(home)), machine, options);
    REQUIRE(e.removal);
    CHECK_FALSE(warned(e, "collision"));
    // Each pass cuts a 3 mm deep (Z2 to Z-1), 20 mm wide track right across the 100 x 50 mm
    // block (Y-10 to 10 and Y20 to 40): 2 x 6000 mm^3. Z home taken at work Z0 would put the
    // F5000 positioning across the block 2 mm deep, and its rapid down into it.
    CHECK(e.energy.removed_mm3 == doctest::Approx(2 * 100 * 20 * 3).epsilon(0.01));
  }
}

TEST_CASE("Z home is taken above the program's highest point, and moves from it are timed") {
  const MachineProfile machine = generic();
  const Estimate g53 =
      estimate_program(make_source("a.nc", haas_program("G53 G0 Z0.")), machine, {});
  const Estimate g28 =
      estimate_program(make_source("b.nc", haas_program("G28 G91 Z0.\nG90")), machine, {});
  // The same moves: the same time.
  CHECK(g53.time_s == doctest::Approx(g28.time_s).epsilon(1e-9));
  // Z home is 100 mm above the highest point (Z15): the retracts take their share of the time.
  MachineProfile low = machine;
  low.setup.z_home_above_work_mm = 10;
  const Estimate near = estimate_program(make_source("a.nc", haas_program("G53 G0 Z0.")), low, {});
  CHECK(near.time_s < g53.time_s);
}

TEST_CASE("work offsets given: G53 goes to the machine position they put in the work") {
  MachineProfile machine = generic();
  machine.setup.work_offsets[1] = Pose{-300, -200, -400, 0, 0, 0};
  const SourceFile source =
      make_source("g53.nc", "G21 G90\nG0 X10 Y10 Z5\nG53 G0 Z-100\nG0 X20\nM30\n");
  std::vector<CanonCommand> seen;
  InterpreterOptions options;
  options.work_offsets = machine.setup.work_offsets;
  interpret(source, options, [&](const CanonCommand& c) {
    if (is_move(c.kind)) seen.push_back(c);
  });
  REQUIRE(seen.size() == 3);
  CHECK(seen[1].end.z == doctest::Approx(300)); // machine Z-100 is 300 above work Z0
  CHECK(seen[1].machine_axes == 4);
  CHECK(seen[2].end.z == doctest::Approx(300));
  CHECK(seen[2].machine_axes == 0);
}

TEST_CASE("past the travel limits, and a switch to a work offset nothing describes") {
  MachineProfile machine = generic();
  machine.setup.work_offsets[1] = Pose{-300, -200, -400, 0, 0, 0};
  machine.setup.travel =
      std::array<std::pair<double, double>, 3>{{{-500, 0}, {-400, 0}, {-500, 0}}};
  const Estimate inside =
      estimate_program(make_source("in.nc", "G21 G90\nG0 X10 Y10 Z5\nG0 X200\nM30\n"), machine, {});
  CHECK_FALSE(warned(inside, "travel"));
  const Estimate outside = estimate_program(
      make_source("out.nc", "G21 G90\nG0 X10 Y10 Z5\nG0 X350\nM30\n"), machine, {});
  CHECK(warned(outside, "past the machine's travel"));

  const MachineProfile plain = generic();
  const Estimate two = estimate_program(
      make_source("two.nc", "G21 G90\nG54\nG0 X10 Y10 Z5\nM0\nG58\nG0 X20\nM30\n"), plain, {});
  CHECK(warned(two, "switches from G54 to G58"));
  const Estimate one =
      estimate_program(make_source("one.nc", "G21 G90\nG54\nG0 X10 Y10 Z5\nM30\n"), plain, {});
  CHECK_FALSE(warned(one, "switches"));
}

TEST_CASE("a program that sets neither G20 nor G21 runs in the power-on units, with a warning") {
  MachineProfile machine = generic();
  const std::string text = "(T1 D=0.25 CR=0. - ZMIN=-0.1 - FLAT END MILL)\nT1 M6\nS5000 M3\n"
                           "G0 X0 Y0 Z0.1\nG1 Z-0.1 F10\nG1 X2 F20\nG0 Z0.1\nM30\n";
  const Estimate mm = estimate_program(make_source("p.nc", text), machine, {});
  CHECK(warned(mm, "sets neither G20 nor G21"));
  CHECK_FALSE(mm.inch);
  machine.setup.power_on_inch = true;
  const Estimate inch = estimate_program(make_source("p.nc", text), machine, {});
  CHECK(warned(inch, "taken to be inches (power_on_units"));
  CHECK(inch.inch);
  REQUIRE(inch.tools.count(1));
  CHECK(inch.tools.at(1).diameter_mm == doctest::Approx(6.35)); // the comment read in inches
  const Estimate given = estimate_program(make_source("p.nc", "G20\n" + text), machine, {});
  CHECK_FALSE(warned(given, "sets neither"));
}

TEST_CASE("without work offsets, G53 X/Y goes to the machine X/Y home the profile names") {
  // Haas/Fusion end: Z home, then the table forward (G53 X.. Y0.). Without offsets the
  // interpreter reads the machine position as a work one; xy_home_in_work_mm says where machine
  // X0 Y0 is seen from the work.
  const std::string program = haas_program("G53 G0 Z0.");
  const std::string ending =
      program.substr(0, program.rfind("M5")) + "G53 G0 X0. Y-50.\nM5\nM30\n%\n";
  MachineProfile machine = generic();
  const Estimate plain = estimate_program(make_source("a.nc", ending), machine, {});
  machine.setup.xy_home_in_work_mm = std::pair{-300.0, 200.0};
  const Estimate named = estimate_program(make_source("a.nc", ending), machine, {});
  const auto last = [](const Estimate& e) { return e.path.back(); };
  REQUIRE_FALSE(plain.path.empty());
  REQUIRE_FALSE(named.path.empty());
  CHECK(last(plain).x == doctest::Approx(0));
  CHECK(last(plain).y == doctest::Approx(-50));
  CHECK(last(named).x == doctest::Approx(-300));
  CHECK(last(named).y == doctest::Approx(150));
  // Z stays at Z home for both, and the longer traverse takes longer.
  CHECK(last(named).z == doctest::Approx(last(plain).z));
  CHECK(named.time_s > plain.time_s);
  CHECK(named.energy.removed_mm3 == plain.energy.removed_mm3);
}

TEST_CASE("without work offsets, a program longer along an axis than the machine's travel is "
          "warned about: Y18 typed for Y1.8 on a VF-2's 16 in of Y") {
  const MachineProfile vf2 =
      load_profile(std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/haas-vf2.toml");
  REQUIRE(vf2.setup.travel);
  REQUIRE(vf2.setup.work_offsets.empty());
  auto program = [](const std::string& y) {
    return "G20 G90 G17\nT1 M6\nS3000 M3\nG0 X0 Y0 Z0.1\nG1 Z-0.05 F20\nG1 X2.\nG1 " + y +
           "\nG1 X0.\nG53 G0 Z0.\nG53 G0 X0. Y0.\nM30\n";
  };
  const Estimate typo = estimate_program(make_source("typo.nc", program("Y18.")), vf2, {});
  CHECK(warned(typo, "Y reaches 18 in here and 0 in at line 4: 18 in apart, more than the "
                     "machine's Y travel of 16 in"));
  for (const Diagnostic& d : typo.diagnostics)
    if (d.message.find("Y travel") != std::string::npos) CHECK(d.line == 7);
  // The program as meant, and machine moves (G53 Z and X/Y home) count for nothing.
  const Estimate meant = estimate_program(make_source("meant.nc", program("Y1.8")), vf2, {});
  CHECK_FALSE(warned(meant, "travel"));
  // A millimetre program says it in mm; the profile with no travel checks nothing.
  const std::string mm = "G21 G90\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X800\nM30\n";
  CHECK(warned(estimate_program(make_source("mm.nc", mm), vf2, {}),
               "X reaches 800 mm here and 0 mm at line 2: 800 mm apart, more than the machine's "
               "X travel of 762 mm"));
  CHECK_FALSE(warned(estimate_program(make_source("mm.nc", mm), generic(), {}), "travel"));
}
