// Programs that machine a part in two clampings: each setup cuts a stock of its own, found from a
// stop followed by another work offset, a probe or a comment naming the setup; a stop alone
// (M1 between operations) starts none.
#include <doctest/doctest.h>

#include <cmath>

#include "cam_stock.hpp"
#include "estimate_checks.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"

using namespace ncjoule;
using namespace estimate_test;

namespace {

// A 6 mm end mill pockets 40 x 20 x 3 mm in two passes, starting at X0 Y0 and returning up.
std::string pocket() {
  std::string s = "G0 Z5\nG0 X3 Y3\n";
  for (const char* z : {"-1.5", "-3"}) {
    s += std::string("G1 Z") + z + " F200\n";
    for (double y = 3; y <= 17.01; y += 4.5) {
      char b[96];
      std::snprintf(b, sizeof b, "G1 X3 Y%.2f F600\nG1 X37 Y%.2f\n", y, y);
      s += b;
    }
    s += "G0 Z5\nG0 X3 Y3\n";
  }
  return s;
}

// The same pocket on both sides of a part: the top in G54, then `between`, then the other side.
std::string two_sides(const std::string& between) {
  return "G21 G90 G17\n(T1 D=6. CR=0. - FLAT END MILL)\nT1 M6\nS8000 M3\nG54\n" + pocket() +
         "M5\n" + between + "\nS8000 M3\n" + pocket() + "M5\nM30\n";
}

} // namespace

TEST_CASE("a stop, then another work offset, starts a second setup with its own stock") {
  const Estimate e = estimate_program(make_source("flip.nc", two_sides("M0\nG55")), generic(), {});
  REQUIRE_FALSE(e.failed);
  REQUIRE(e.setups.size() == 2);
  CHECK(e.setups[1].reason.find("M0") != std::string::npos);
  CHECK(e.setups[1].reason.find("G55") != std::string::npos);
  // Each side removes its guessed stock: the top at Z0, the outline the passes' extent (X3 to
  // X37, Y3 to Y16.5: an area's passes run to the stock's edge), 3 mm deep: 1377 mm^3.
  CHECK(e.setups[0].removed_mm3 == doctest::Approx(34 * 13.5 * 3).epsilon(1e-3));
  CHECK(e.setups[1].removed_mm3 == doctest::Approx(e.setups[0].removed_mm3).epsilon(0.01));
  CHECK(e.energy.removed_mm3 ==
        doctest::Approx(e.setups[0].removed_mm3 + e.setups[1].removed_mm3).epsilon(1e-6));
  CHECK(e.setups[0].time_s + e.setups[1].time_s == doctest::Approx(e.time_s).epsilon(1e-6));
  CHECK(e.setups[0].energy_j + e.setups[1].energy_j ==
        doctest::Approx(e.energy.energy_j).epsilon(1e-6));
}

TEST_CASE("one stock for both sides would leave the second nothing to cut") {
  // The same program with an M1 only: one setup, the second pocket cuts air.
  const Estimate one = estimate_program(make_source("m1.nc", two_sides("M1")), generic(), {});
  const Estimate two =
      estimate_program(make_source("flip.nc", two_sides("M0\nG55")), generic(), {});
  REQUIRE(one.setups.size() == 1);
  REQUIRE(two.setups.size() == 2);
  CHECK(two.energy.removed_mm3 == doctest::Approx(2 * one.energy.removed_mm3).epsilon(0.01));
}

TEST_CASE("a comment naming the side after a stop starts a setup, and so does a probe") {
  for (const std::string between :
       {"M0\n(FLIP PART)", "M1 (TURN PART OVER)", "M0\nG38.2 Z-10 F100"}) {
    CAPTURE(between);
    const Estimate e = estimate_program(make_source("p.nc", two_sides(between)), generic(), {});
    REQUIRE_FALSE(e.failed);
    CHECK(e.setups.size() == 2);
  }
  // A work offset change without a stop is another fixture on the table, not a new clamping of
  // the same part: one setup (its stock is the box of all cuts).
  const Estimate e = estimate_program(make_source("p.nc", two_sides("G55")), generic(), {});
  CHECK(e.setups.size() == 1);
}

TEST_CASE("a job's stock per setup: the second given, the first from the cuts") {
  EstimateOptions options;
  // The second side's block is 10 mm taller than the pockets: its top face is cut too.
  options.setup_stocks.push_back(parse_stock_spec("box:0,0,-10,40,20,0"));
  const Estimate e =
      estimate_program(make_source("flip.nc", two_sides("M0\nG55")), generic(), options);
  REQUIRE(e.setups.size() == 2);
  CHECK(e.setups[0].stock_source == StockSource::Guessed);
  CHECK(e.setups[1].stock_source == StockSource::Given);
  CHECK(e.setups[1].stock.find("box") != std::string::npos);
  CHECK(e.setups[1].removed_mm3 > e.setups[0].removed_mm3 * 0.9);
}

TEST_CASE("CAM comments' stock corners: Carbide Create's and the spelt-out form") {
  using estimate_detail::stock_corner_of_comment;
  const auto low = stock_corner_of_comment("stockMin:-150.00mm, -100.00mm, -8.00mm");
  REQUIRE(low);
  CHECK_FALSE(low->is_max);
  CHECK(low->xyz[2].first == -8);
  CHECK(low->xyz[2].second == LengthUnit::Mm);
  const auto high = stock_corner_of_comment(" STOCK MAX = 4, 3, 0 ");
  REQUIRE(high);
  CHECK(high->is_max);
  CHECK(high->xyz[0].second == LengthUnit::Program);
  for (const char* not_one : {"STOCK 4.125 x 3.625 x 1.000", "stockMin:1,2", "stockMin:1,2,3,4",
                              "stock min is 1,2,3", "Stock is 30mm diameter Acetal Rod"}) {
    CAPTURE(std::string(not_one));
    CHECK_FALSE(stock_corner_of_comment(not_one));
  }
}

TEST_CASE("CAM comments' whole stocks: STOCK/BLOCK and a size alone, placed where the cuts fit") {
  using estimate_detail::stock_box_of_comment;
  // Carbide Create's APT line: 300 x 200 x 8 with the work origin 150, 100, 8 from the stock's
  // low corner: the same box as its stockMin/stockMax lines.
  const auto block = stock_box_of_comment("STOCK/BLOCK,300.00, 200.00, 8.00,150.00, 100.00, 8.00");
  REQUIRE(block);
  CHECK_FALSE(block->size_only);
  CHECK(block->box.xmin == -150);
  CHECK(block->box.ymax == 100);
  CHECK(block->box.zmin == -8);
  CHECK(block->box.zmax == 0);
  const auto size = stock_box_of_comment("STOCK 4.125 x 3.625 x 1.000 ");
  REQUIRE(size);
  CHECK(size->size_only);
  CHECK(size->box.xmax == 4.125);
  CHECK(size->box_units[0] == LengthUnit::Program);
  CHECK(stock_box_of_comment("STOCK SIZE: 100 X 60 X 20mm"));
  for (const char* not_one : {"Stock is 30mm diameter Acetal Rod", "STOCK 4 x 3",
                              "stock/block,1,2,3", "STOCK 0 x 3 x 1"}) {
    CAPTURE(std::string(not_one));
    CHECK_FALSE(stock_box_of_comment(not_one));
  }
  // Placement: 100 x 60 x 20 around cuts at X 5-95 (from 0), Y -25-25 (centred), below Z0.
  std::string how;
  const Box3 sized{0, 0, 0, 100, 60, 20};
  Box3 at = place_sized_stock(sized, Box3{5, -25, -10, 95, 25, 0}, how);
  CHECK(at.xmin == 0);
  CHECK(at.ymin == -30);
  CHECK(at.zmin == -20);
  CHECK(at.zmax == 0);
  CHECK(how == "X from 0, Y centred, top at Z0");
  // Cuts to the left of X0 and all above Z0 (the origin on the table): up to 0, bottom at Z0.
  at = place_sized_stock(sized, Box3{-90, 2, 5, -10, 50, 20}, how);
  CHECK(at.xmax == 0);
  CHECK(at.zmin == 0);
  CHECK(how == "X up to 0, Y from 0, bottom at Z0");
  // The estimate reads it, says where it came from and how it is placed.
  const std::string program = "%\nO2001\n(STOCK 100 x 60 x 20)\nG21 G90\n"
                              "(T1 D=10. CR=0. - ZMIN=-2. - FLAT END MILL)\nT1 M6\nS8000 M3\n"
                              "G0 X10 Y10 Z5\nG1 Z-2 F200\nG1 X90 F800\nG0 Z5\nM30\n%\n";
  const Estimate e = estimate_program(make_source("o2001.nc", program), generic(), {});
  REQUIRE(e.removal);
  CHECK(e.removal->stock_source == StockSource::Program);
  CHECK(e.removal->stock_description.find("placed where the cuts fit it: X from 0, Y from 0, top "
                                          "at Z0") != std::string::npos);
  // A 10 mm slot 2 mm deep from X10 to X90 (plunge included): 80 x 10 x 2 + the half-disc ends.
  CHECK(e.energy.removed_mm3 == doctest::Approx(80 * 10 * 2 + 3.14159265 * 25 * 2).epsilon(0.03));
}

TEST_CASE("G41 in control offsets the contour, in wear (job or profile) it runs as programmed") {
  // A 40 x 40 square contour with G41 D1, the 10 mm tool described in a comment: in control the
  // tool runs a radius outside. rs274 (a tool table with this tool) gives the path: entry 26.7,
  // sides 37.9 + 3 x 40, three corner arcs 3 x 7.85, exit 25 mm = 233.2 mm, against 216.6 mm as
  // programmed: 16.6 mm more, 3.3 s at F300.
  const std::string program =
      "G21 G90 G17 G94\n(T1 D=10. CR=0. - FLAT END MILL)\nT1 M6\nS6000 M3\nG0 X-20 Y-20 Z5\n"
      "G1 Z-1 F100\nG41 D1 G1 X0 Y0 F300\nG1 Y40\nG1 X40\nG1 Y0\nG1 X0\nG40 G1 X-20 Y-20\n"
      "G0 Z5\nM30\n";
  EstimateOptions plain;
  plain.simulate_removal = false;
  const Estimate control = estimate_program(make_source("c.nc", program), generic(), plain);
  EstimateOptions wear = plain;
  wear.cutter_compensation = CutterCompMode::Wear;
  const Estimate as_wear = estimate_program(make_source("c.nc", program), generic(), wear);
  MachineProfile shop = generic();
  shop.setup.cutter_compensation = CutterCompMode::Wear;
  const Estimate shop_wear = estimate_program(make_source("c.nc", program), shop, plain);
  REQUIRE_FALSE(control.failed);
  CHECK(as_wear.time.cutting_s() == doctest::Approx(shop_wear.time.cutting_s()));
  CHECK(control.time.cutting_s() - as_wear.time.cutting_s() > 3.0);
  CHECK(control.time.cutting_s() - as_wear.time.cutting_s() < 3.6);
  // A job's control wins over the profile's wear.
  EstimateOptions job_control = plain;
  job_control.cutter_compensation = CutterCompMode::Control;
  const Estimate forced = estimate_program(make_source("c.nc", program), shop, job_control);
  CHECK(forced.time.cutting_s() == doctest::Approx(control.time.cutting_s()));
}

TEST_CASE("a rotary index after cutting (G0 A180) starts a setup, 4-axis cutting does not") {
  const Estimate e =
      estimate_program(make_source("index.nc", two_sides("G0 Z20\nG0 A180")), generic(), {});
  REQUIRE_FALSE(e.failed);
  REQUIRE(e.setups.size() == 2);
  CHECK(e.setups[1].reason == "the part turned: A180 (a rotary index)");
  // Each side removes its own pocket from its own stock, as with a flip.
  CHECK(e.setups[0].removed_mm3 > 1100);
  CHECK(e.setups[1].removed_mm3 == doctest::Approx(e.setups[0].removed_mm3).epsilon(0.01));
  // Turning before anything is cut (the part's first side) and turning while feeding start none.
  CHECK(estimate_program(make_source("first.nc", "G0 A90\n" + two_sides("G0 Z20")), generic(), {})
            .setups.size() == 1);
  CHECK(estimate_program(make_source("wrap.nc", two_sides("G1 A180 F500")), generic(), {})
            .setups.size() == 1);
}
