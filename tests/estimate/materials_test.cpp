// Plausible cutting energy on any job: the workpiece materials and their published ranges, the
// fitted ranges of a machine's fit, the spindle's rating, and a program that starts inside its
// stock.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "estimate_checks.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"

using namespace ncjoule;
using namespace estimate_test;

namespace {

MachineProfile profile(const std::string& name) {
  return load_profile(std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/" + name);
}

// The standard slot: a 6 mm flat end mill, full width, 3 mm deep, 60 mm long at F600 and the
// given spindle speed, in a box whose top is Z0.
std::string slot(double rpm, double feed_mm_min = 600) {
  char text[512];
  std::snprintf(text, sizeof text,
                "G21 G90 G17\n(T1 D=6. CR=0. - ZMIN=-3. - FLAT END MILL)\nT1 M6\nS%.0f M3\n"
                "G0 X-10 Y0 Z5\nG0 Z-3\nG1 X60 F%.0f\nG0 Z5\nM5\nM30\n",
                rpm, feed_mm_min);
  return text;
}

Estimate run(const std::string& program, const MachineProfile& machine,
             const std::string& material = "") {
  EstimateOptions options;
  options.stock = parse_stock_spec("box:0,-10,-10,50,10,0");
  options.material = material;
  return estimate_program(make_source("slot.ngc", program), machine, options);
}

// Energy of the cutting component per mm^3 removed: what the material tables give.
double cutting_sec(const Estimate& e) {
  return e.energy.components_j[std::size_t(PowerComponent::Cutting)] / e.energy.removed_mm3;
}

} // namespace

TEST_CASE("every material: a typical value inside its published range, found by its aliases") {
  REQUIRE(materials().size() >= 12);
  for (const Material& m : materials()) {
    CAPTURE(m.name);
    CHECK(m.kc_min_j_mm3 > 0);
    CHECK(m.kc_min_j_mm3 <= m.kc_j_mm3);
    CHECK(m.kc_j_mm3 <= m.kc_max_j_mm3);
    CHECK_FALSE(m.source.empty());
    CHECK(find_material(m.name)->name == m.name);
    for (const std::string& alias : m.aliases)
      CHECK(find_material(alias)->name == m.name);
  }
  CHECK(find_material("Aluminium Alloy")->name == "aluminium-alloy");
  CHECK(find_material("6061")->name == "aluminium-alloy");
  CHECK_FALSE(find_material("unobtainium"));
  // The typical value is Kienzle's k_c at a 0.05 mm chip: ISCAR's 800 N/mm^2 and 0.25 for
  // wrought aluminium give 800 * 0.05^-0.25 = 1692 N/mm^2; mild steel (1350, 0.21) 2532.
  CHECK(find_material("aluminium")->kc_j_mm3 == doctest::Approx(1.6918).epsilon(1e-3));
  CHECK(find_material("mild-steel")->kc_j_mm3 == doctest::Approx(2.532).epsilon(1e-3));
  // Harder to cut, more energy: stainless and titanium above mild steel at every chip, wood and
  // plastics far below aluminium.
  for (double h : {0.01, 0.05, 0.1, 0.3}) {
    CAPTURE(h);
    const double mild = find_material("mild-steel")->kc_at(h);
    CHECK(find_material("stainless-steel")->kc_at(h) > mild);
    CHECK(find_material("titanium-alloy")->kc_at(h) > mild);
    CHECK(find_material("alloy-steel")->kc_at(h) > mild);
    CHECK(find_material("mdf")->kc_at(h) < 0.2 * find_material("aluminium")->kc_at(h));
  }
}

TEST_CASE("generic profile, every material: the slot's cutting SEC lies in its published range") {
  const MachineProfile generic = profile("generic-3axis.toml");
  REQUIRE(generic.power.cutting_term == CuttingTerm::Material);
  for (const Material& m : materials()) {
    CAPTURE(m.name);
    const Estimate e = run(slot(8000), generic, m.name);
    REQUIRE(e.energy.removed_mm3 == doctest::Approx(6 * 3 * 50).epsilon(0.01));
    // Power drawn for cutting: k_c at the edge over the drive's efficiency; at the edge it is
    // inside the material's range whatever the spindle speed.
    const double at_edge = cutting_sec(e) * generic.power.cutting_efficiency;
    CHECK(at_edge >= m.kc_min_j_mm3 * (1 - 1e-6));
    CHECK(at_edge <= m.kc_max_j_mm3 * (1 + 1e-6));
    CHECK(e.power.material == m.name);
  }
  // The default material is aluminium; at 10,000 rpm it stays an aluminium number (the fitted
  // Zhou term gave 20-27 J/mm^3 there): F600 with 3 flutes is 0.02 mm a tooth, a 0.0127 mm mean
  // chip, k_c = 800 * 0.0127^-0.25 = 2.38 J/mm^3 at the edge, 2.98 drawn at 80% (within 1%: the
  // entry into the stock, at less than the full width, has its own mean chip).
  const Estimate high = run(slot(10000), generic);
  CHECK(high.power.material == "aluminium-alloy");
  CHECK(cutting_sec(high) ==
        doctest::Approx(800e-3 * std::pow(0.02 * 2 / M_PI, -0.25) / 0.8).epsilon(1e-2));
  CHECK(high.energy.peak_power_w < 5000);
}

TEST_CASE("fitted profiles: the slot inside the fitted range, a warning outside it") {
  const MachineProfile zhou = profile("zhou2017-anziani2025.toml");
  REQUIRE(zhou.power.zhou.fitted_rpm_max == 2100);
  // 150 mm/min: 45 mm^3/s, inside the fit's 3-48 mm^3/s.
  const Estimate inside = run(slot(1300, 150), zhou);
  // c3 * 1300^c4 = 2.7 J/mm^3: a metal's figure (0.3 to 9 in the tables).
  CHECK(cutting_sec(inside) > 0.3);
  CHECK(cutting_sec(inside) < 9);
  CHECK_FALSE(warned(inside, "fitted on"));
  const Estimate outside = run(slot(8000), zhou);
  CHECK(warned(outside, "fitted on 500-2100 rpm"));
  CHECK(warned(outside, "3.8x outside"));
  // Its idle line c1 + c2*n was fitted on the same speeds: the spindle's power is extrapolated
  // too, and said with how far (8000 / 2100 = 3.8x); inside the range, nothing.
  CHECK(warned(outside, "the idle spindle line c1 + c2*n was fitted at 500-2100 rpm"));
  CHECK(warned(outside, "8000-8000 rpm (3.8x above)"));
  CHECK_FALSE(warned(inside, "idle spindle line"));
  // A material does not replace a machine's fit; asking for one says so.
  const Estimate asked = run(slot(1300, 150), zhou, "brass");
  CHECK(warned(asked, "not used"));
  CHECK(cutting_sec(asked) == doctest::Approx(cutting_sec(inside)));

  // Pavanaskar's Haas: its cutting term is what Table 4.1's cuts in aluminium 6061 drew above the
  // move lines, per mm^3; drawn, it lies in Kalpakjian & Schmid's unit power for aluminium
  // alloys, 0.4-1.1 W s/mm^3 at the motor (Table 21.2). Kienzle with ISCAR's constants is higher
  // (1.1 J/mm^3 at the edge even for a 0.3 mm chip): the sources for aluminium differ that much.
  const MachineProfile haas = profile("haas-vf0-pavanaskar2014.toml");
  const Estimate pav = run(slot(5500), haas);
  CHECK(cutting_sec(pav) > 0.4);
  CHECK(cutting_sec(pav) < 1.1);
  CHECK(cutting_sec(pav) == doctest::Approx(0.6132 / 0.8).epsilon(1e-6));
  // The machine's own 6061 is its default; a handbook material replaces it when asked for.
  const Estimate handbook = run(slot(5500), haas, "aluminium-alloy");
  CHECK_FALSE(warned(handbook, "not used"));
  CHECK(cutting_sec(handbook) > 1.5 * cutting_sec(pav));
}

TEST_CASE("a cut asking the spindle for more than its rating is flagged on its block") {
  MachineProfile small = profile("generic-3axis.toml");
  small.power.spindle_rated_w = 200; // a hobby spindle
  const Estimate e = run(slot(8000), small, "mild-steel");
  CHECK(warned(e, "more than its rated power"));
  CHECK(warned(e, "the CAM feeds and speeds are wrong"));
  CHECK_FALSE(warned(e, "the stock is guessed"));
  // Without a stock, the box of the cuts is a guess, and a guess that overloads the spindle is
  // the likelier thing to be wrong (rest machining): the block is listed as a place where the
  // guess is wrong, and its cutting is left out of the peak power.
  EstimateOptions no_stock;
  no_stock.material = "mild-steel";
  const Estimate guessed = estimate_program(
      make_source("two-levels.ngc", "G21 G90 G17\n(T1 D=6. CR=0. - ZMIN=-3. - FLAT END MILL)\n"
                                    "T1 M6\nS8000 M3\nG0 X-10 Y0 Z5\nG0 Z0\nG1 X60 F600\n"
                                    "G0 Z5\nG0 X-10\nG0 Z-3\nG1 X60\nG0 Z5\nM5\nM30\n"),
      small, no_stock);
  REQUIRE(guessed.removal);
  CHECK(guessed.energy.removed_mm3 > 1000); // the second pass: 70 x 6 x 3 mm, less its ends
  CHECK(warned(guessed, "the guessed stock is wrong where 1 block(s) would ask the spindle for "
                        "more than its rated power (the first at line 11"));
  CHECK_FALSE(warned(guessed, "the CAM feeds and speeds are wrong"));
  const StockGuessRange& range = guessed.stock_guess;
  CHECK(range.guessed);
  CHECK(range.overload_blocks == 1);
  CHECK(range.first_overload_line == 10); // 0-based: the pass at Z-3
  CHECK(range.worst_load > 1);
  // The peak printed is the machine's without that cut; the guess's own is kept beside it.
  CHECK(guessed.energy.peak_power_w < range.peak_power_guess_w);
  CHECK(guessed.energy.peak_power_w == doctest::Approx(range.peak_power_floor_w));
  const GuessedFigures figures = guessed_figures(guessed);
  CHECK(figures.removed_mm3.low == 0);
  CHECK(figures.removed_mm3.high == guessed.energy.removed_mm3);
  CHECK(figures.energy_j.high - figures.energy_j.low ==
        doctest::Approx(guessed.energy.components_j[std::size_t(PowerComponent::Cutting)]));
  bool flagged = false;
  for (const LineSummary& b : e.lines)
    flagged |= b.line == 6 && b.spindle_load > 1;
  CHECK(flagged);
  // A curve: rated power against speed, interpolated, ends held.
  PowerConstants p;
  p.spindle_power_curve = {{1000, 1000}, {5000, 5000}};
  CHECK(rated_spindle_power_w(p, 3000) == doctest::Approx(3000));
  CHECK(rated_spindle_power_w(p, 500) == doctest::Approx(1000));
  CHECK(rated_spindle_power_w(p, 9000) == doctest::Approx(5000));
}

TEST_CASE("a program whose first move starts inside the stock is warned about") {
  const MachineProfile generic = profile("generic-3axis.toml");
  // The stock's top is at Z5 here. The assumed start (0,0,0, before the program sets a
  // position) is inside it, but that is not where the spindle is: no warning.
  EstimateOptions options;
  options.stock = parse_stock_spec("box:-20,-20,-10,80,20,5");
  const Estimate e = estimate_program(make_source("inside.ngc", slot(8000)), generic, options);
  CHECK_FALSE(warned(e, "starts inside the stock"));
  CHECK_FALSE(warned(run(slot(8000), generic), "starts inside the stock"));
  // A program that itself puts the tool in the material before its first move is warned about.
  const Estimate inside = estimate_program(
      make_source("inside.ngc", "G21 G90 G17\n(T1 D=6. CR=0. - ZMIN=-3. - FLAT END MILL)\n"
                                "T1 M6\nS8000 M3\nG0 X-10 Y0 Z0\nG1 X60 F600\nG0 Z10\nM30\n"),
      generic, options);
  CHECK(warned(inside, "starts inside the stock"));
}

TEST_CASE("the first rapid from the assumed start removes nothing (G0 X Y before the first Z)") {
  const MachineProfile generic = profile("generic-3axis.toml");
  EstimateOptions options;
  options.stock = parse_stock_spec("box:10,0,-13,220,60,5");
  // A Fusion personal-use program: T1 without M6, then "G0 X Y" while Z is still the assumed 0,
  // crossing the stock, then Z10 above it. Neither rapid is a collision.
  const Estimate e = estimate_program(
      make_source("fusion.nc", "(T1  D=2.7 CR=0 - ZMIN=-13.3 - flat end mill)\nG90 G94\nG17\n"
                               "G21\nT1\nS5000 M3\nG54\nG0 X215.075 Y34.73\nZ10\n"
                               "G1 Z-3.95 F250\nG0 Z10\nM30\n"),
      generic, options);
  CHECK_FALSE(warned(e, "collision"));
  REQUIRE(e.removal);
  // What the plunge removes: the 2.7 mm circle from Z5 down to Z-3.95.
  const double plunge = 3.14159265 * 1.35 * 1.35 * 8.95;
  CHECK(e.energy.removed_mm3 == doctest::Approx(plunge).epsilon(0.1));
}

TEST_CASE("with flutes known, a material with Kienzle's constants corrects for chip thickness") {
  MachineProfile generic = profile("generic-3axis.toml");
  Material steel;
  steel.name = "test-steel";
  steel.kc11_n_mm2 = 1800;
  steel.mc = 0.25;
  steel.kc_j_mm3 = 1e-3 * 1800 * std::pow(0.1, -0.25); // at 0.1 mm
  steel.kc_min_j_mm3 = steel.kc_max_j_mm3 = steel.kc_j_mm3;
  steel.source = "test";
  generic.power.profile_material = steel;
  generic.power.material = "test-steel";
  EstimateOptions options;
  options.stock = parse_stock_spec("box:0,-10,-10,50,10,0");
  // 600 mm/min at 1000 rpm with 2 flutes: 0.3 mm per tooth; with the flutes not given, a 6 mm
  // end mill is taken to have 3 (0.2 mm per tooth). The thicker chip takes less energy per
  // mm^3: (0.3 / 0.2)^-0.25 = 0.904.
  const std::string program = slot(1000);
  const Estimate plain = estimate_program(make_source("s.ngc", program), generic, options);
  Tool t1;
  t1.number = 1;
  t1.diameter_mm = 6;
  t1.flutes = 2;
  t1.description = "flat end mill, 2 flutes";
  options.tools[1] = t1;
  const Estimate corrected = estimate_program(make_source("s.ngc", program), generic, options);
  CHECK(cutting_sec(corrected) / cutting_sec(plain) ==
        doctest::Approx(std::pow(1.5, -0.25)).epsilon(1e-3));
}

TEST_CASE("material removed with the spindle stopped is said, and counted at a known speed") {
  // A 6 mm slot 2 mm deep and 50 mm long in aluminium at 9000 rpm, F800, 3 flutes: 0.0296 mm
  // a tooth, a 0.0189 mm mean chip; Kienzle's k_c there over the 0.8 efficiency, per mm^3.
  const auto program = [](const std::string& spindle) {
    return "G21 G90\n(T1 D=6. CR=0. - ZMIN=-2. - FLAT END MILL)\nT1 M6\n" + spindle +
           "G0 X0 Y0 Z5\nG1 Z-2 F300\nG1 X50 F800\nG0 Z5\nM2\n";
  };
  EstimateOptions options;
  options.stock = parse_stock_spec("box:-10,-10,-5,60,10,0");
  auto cutting_j = [](const Estimate& e) {
    return e.energy.components_j[static_cast<std::size_t>(PowerComponent::Cutting)];
  };
  auto spindle_j = [](const Estimate& e) {
    return e.energy.components_j[static_cast<std::size_t>(PowerComponent::Spindle)];
  };
  MachineProfile machine = generic();
  const Estimate running =
      estimate_program(make_source("a.nc", program("S9000 M3\n")), machine, options);
  REQUIRE(running.energy.removed_mm3 > 0);
  CHECK_FALSE(warned(running, "spindle stopped"));
  const double expected_cut = running.energy.removed_mm3 *
                              find_material("aluminium")->kc_at(800.0 / 9000 / 3 * 2 / M_PI) / 0.8;
  // (The plunge's 57 mm^3 at F300 have a thinner chip, a higher k_c: about 2.5% more.)
  CHECK(cutting_j(running) == doctest::Approx(expected_cut).epsilon(0.04));
  CHECK(cutting_j(running) > expected_cut);
  // No M3 and no S: the cut is said, and its energy is not counted.
  const Estimate bare = estimate_program(make_source("b.nc", program("")), machine, options);
  CHECK(warned(bare, "spindle stopped (no M3/M4 and no S) here and in 1 more moves"));
  CHECK(warned(bare, "NOT counted"));
  CHECK(cutting_j(bare) == 0);
  // M3 at S0: both are there, and the warning says so (not "no M3/M4 and no S").
  const Estimate s0 = estimate_program(make_source("s0.nc", program("S0 M3\n")), machine, options);
  CHECK(warned(s0, "spindle on at S0 (M3/M4 with a speed of 0) here and in 1 more moves"));
  CHECK(warned(s0, "NOT counted (give the speed with an S word before the cut)"));
  CHECK_FALSE(warned(s0, "no M3/M4 and no S"));
  CHECK(cutting_j(s0) == 0);
  // S without M3: counted at the program's speed.
  const Estimate s_only =
      estimate_program(make_source("c.nc", program("S9000\n")), machine, options);
  CHECK(warned(s_only, "counted as turning at 9000 rpm (the program's last S)"));
  CHECK(cutting_j(s_only) == doctest::Approx(cutting_j(running)).epsilon(1e-6));
  // A hand spindle the profile describes: its speed, spindle power only while it cuts.
  machine.power.hand_spindle_rpm = 9000;
  const Estimate hand = estimate_program(make_source("d.nc", program("")), machine, options);
  CHECK(warned(hand, "counted as turning at 9000 rpm (the profile's hand_spindle_rpm)"));
  CHECK(cutting_j(hand) == doctest::Approx(cutting_j(running)).epsilon(1e-6));
  CHECK(spindle_j(hand) > 0);
  CHECK(spindle_j(hand) < spindle_j(running)); // not while it positions
}

TEST_CASE("Kienzle hand calculations: a slot in 6061 and a side cut in C45") {
  // Hand calculations (Sandvik's milling formulas with ISCAR's k_c1.1 and m_c, 0 deg rake):
  // (a) a 10 mm 3-flute end mill slotting 5 mm deep in 6061 at 8000 rpm, 0.05 mm a tooth:
  //     v_f = 1200 mm/min, h_m = 0.6366 * 0.05 = 0.03183 mm, k_c = 800 * h_m^-0.25 = 1894 N/mm^2,
  //     P_c = 5 * 10 * 1200 * 1894 / 60e6 = 1.894 kW at the edge.
  // (b) a 12 mm 4-flute end mill, a 2 mm wide side cut 10 mm deep in C45 at 2000 rpm, 0.05 mm a
  //     tooth: h_m = 0.05 * 2 (2/12) / arccos(1 - 2 (2/12)) = 0.01982 mm, k_c = 1500 *
  //     h_m^-0.22 = 3554 N/mm^2, P_c = 10 * 2 * 400 * 3554 / 60e6 = 0.474 kW.
  // The radial engagement comes from removal (each step's volume over its depth of cut and its
  // length), so (b) gets the side cut's thinner chip; taken as a slot it would come out 10% low.
  const MachineProfile generic = profile("generic-3axis.toml");
  auto edge_power_kw = [&](const std::string& program, const std::string& stock,
                           const std::string& material, double mrr_mm3_s, double diameter,
                           int flutes) {
    EstimateOptions options;
    options.stock = parse_stock_spec(stock);
    options.material = material;
    Tool tool;
    tool.number = 1;
    tool.diameter_mm = diameter;
    tool.flutes = flutes;
    options.tools[1] = tool;
    const Estimate e = estimate_program(make_source("k.ngc", program), generic, options);
    REQUIRE(e.energy.removed_mm3 > 0);
    // k_c at the edge (J/mm^3) times the nominal removal rate.
    return cutting_sec(e) * generic.power.cutting_efficiency * mrr_mm3_s / 1000;
  };
  const double slot_kw = edge_power_kw(
      "G21 G90\n(T1 D=10. CR=0. - ZMIN=-5. - FLAT END MILL)\nT1 M6\nS8000 M3\nG0 X-10 Y0 Z5\n"
      "G0 Z-5\nG1 X100 F1200\nG0 Z5\nM30\n",
      "box:0,-20,-20,100,20,0", "6061", 5 * 10 * 1200 / 60.0, 10, 3);
  MESSAGE("slot in 6061: " << slot_kw << " kW at the edge, hand 1.894 kW");
  CHECK(slot_kw == doctest::Approx(1.894).epsilon(0.02));
  const double side_kw =
      edge_power_kw("G21 G90\n(T1 D=12. CR=0. - ZMIN=-10. - FLAT END MILL)\nT1 M6\nS2000 M3\n"
                    "G0 X-10 Y4 Z5\nG0 Z-10\nG1 X100 F400\nG0 Z5\nM30\n",
                    "box:0,-20,-20,100,0,0", "c45", 10 * 2 * 400 / 60.0, 12, 4);
  MESSAGE("side cut in C45: " << side_kw << " kW at the edge, hand 0.474 kW");
  CHECK(side_kw == doctest::Approx(0.474).epsilon(0.02));
  // Against a slot's chip at the same feed per tooth: h = 0.0318 mm, k_c = 3202 N/mm^2, 0.427 kW.
  CHECK(side_kw > 0.44);
}

TEST_CASE("the radial engagement comes from removal: volume over depth of cut and length") {
  // A 12 mm end mill 10 mm deep with 2 mm of its width in the stock (Y4: its edge at Y-2), then
  // at Y0 with 6 mm in it, of which the first pass took 2: a_e is 2 mm, then 4 mm.
  const std::string program = "G21 G90\n(T1 D=12. CR=0. - ZMIN=-10. - FLAT END MILL)\nT1 M6\n"
                              "S2000 M3\nG0 X-10 Y4 Z5\nG0 Z-10\nG1 X100 F400\nG0 Z5\n"
                              "G0 X-10 Y0\nG0 Z-10\nG1 X100\nG0 Z5\nM30\n";
  EstimateOptions options;
  options.stock = parse_stock_spec("box:0,-20,-20,100,0,0");
  options.keep_trace = true;
  const Estimate e =
      estimate_program(make_source("side.ngc", program), profile("generic-3axis.toml"), options);
  // The radial widths while the pass on 0-based line `line` cuts.
  auto widths_on_line = [&](int line) {
    const auto l = std::find_if(e.lines.begin(), e.lines.end(),
                                [&](const LineSummary& s) { return s.line == line; });
    REQUIRE(l != e.lines.end());
    std::vector<double> w;
    for (const OperatingSegment& s : e.trace)
      if (s.t0_s >= l->start_s && s.t1_s <= l->end_s && s.start.mrr_mm3_s > 0)
        w.push_back(s.start.radial_width_mm);
    return w;
  };
  const auto first = widths_on_line(6), second = widths_on_line(10);
  REQUIRE(first.size() > 100);
  REQUIRE(second.size() > 100);
  // The steady middle of each pass.
  CHECK(first[first.size() / 2] == doctest::Approx(2).epsilon(0.03));
  CHECK(second[second.size() / 2] == doctest::Approx(4).epsilon(0.03));
  CHECK(mean_chip_thickness_mm(0.05, 12, 12) == doctest::Approx(0.05 * 2 / M_PI));
  CHECK(mean_chip_thickness_mm(0.05, 2, 12) == doctest::Approx(0.01982).epsilon(1e-3));
  CHECK(mean_chip_thickness_mm(0.05, 0, 12) == doctest::Approx(0.05 * 2 / M_PI)); // not known
}
