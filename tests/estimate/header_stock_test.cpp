// Stocks a program's header states over several lines or as code: Vectric's Material Size block
// (as Vectric's posts write it, with its origin lines), Sinumerik's WORKPIECE blank (as Siemens'
// example and Fusion 360's 840D post write it), each named by kind and line.
#include <doctest/doctest.h>

#include "cam_stock.hpp"
#include "estimate_checks.hpp"
#include "ncjoule/estimate.hpp"

using namespace ncjoule;
using namespace estimate_test;
using estimate_detail::stock_from_cam_comments;

namespace {

const Dialect& linuxcnc() {
  return *find_dialect("linuxcnc");
}
const Dialect& siemens() {
  return *find_dialect("siemens");
}

// A Vectric "Mach2/3"-style header: the block's title, its sizes on the next line, its origins.
std::string vectric_header(const std::string& z_origin, const std::string& xy_origin) {
  return "( pocket )\n( File created: Monday June 01 2026 - 10:00 AM)\n( for Mach2/3 from Vectric "
         ")\n"
         "( Material Size)\n( X= 300.000, Y= 200.000, Z= 18.000)\n( Z Origin for Material  = " +
         z_origin + ")\n( XY Origin for Material = " + xy_origin +
         ")\n(Toolpaths used in this file:)\n(Pocket 1)\nG00G21G17G90G40G49G80\nG0 Z5\n";
}

} // namespace

TEST_CASE("Vectric's Material Size block: the size on the next line, placed by its origins") {
  auto at = [](const std::string& z, const std::string& xy) {
    return stock_from_cam_comments(make_source("v.nc", vectric_header(z, xy)), linuxcnc());
  };
  auto s = at("Material Surface", "Bottom Left Corner");
  REQUIRE(s);
  CHECK(s->from == "vectric");
  CHECK(s->origin == "Vectric Material Size block, lines 4-7");
  CHECK_FALSE(s->size_only);
  CHECK(s->box.xmin == 0);
  CHECK(s->box.xmax == 300);
  CHECK(s->box.ymax == 200);
  CHECK(s->box.zmin == -18);
  CHECK(s->box.zmax == 0);
  CHECK(s->box_units[0] == LengthUnit::Program); // a Vectric post writes the program's units
  s = at("Machine Bed", "Center");
  REQUIRE(s);
  CHECK(s->box.xmin == -150);
  CHECK(s->box.ymax == 100);
  CHECK(s->box.zmin == 0);
  CHECK(s->box.zmax == 18);
  s = at("Material Surface", "Top Right Corner");
  REQUIRE(s);
  CHECK(s->box.xmax == 0);
  CHECK(s->box.ymin == -200);
  // Origins it does not know leave the size to be placed where the cuts fit it.
  s = at("Somewhere", "Bottom Left Corner");
  REQUIRE(s);
  CHECK(s->size_only);
  CHECK(s->box.xmax == 300);
}

TEST_CASE("Vectric's one-line Material Size and its variants, and what is not a size") {
  auto one = [](const std::string& header) {
    return stock_from_cam_comments(make_source("v.nc", header + "G0 Z5\n"), linuxcnc());
  };
  auto s = one("( Material Size: X= 12.000, Y= 8.000, Z= 0.750)\n( Z Origin for Material  = "
               "Material Surface)\n( XY Origin for Material = Bottom Left Corner)\n");
  REQUIRE(s);
  CHECK(s->box.xmax == 12);
  CHECK(s->box.zmin == -0.75);
  CHECK(s->origin == "Vectric Material Size block, lines 1-3");
  // RapidChange's spacing, and the IMF post's ";Material Size: X=... x Y=... x Z=...".
  s = one("( Material Size)\n( X= 457.200, Y= 304.800 ,Z= 19.050)\n");
  REQUIRE(s);
  CHECK(s->size_only);
  CHECK(s->box.zmax == doctest::Approx(19.05));
  s = stock_from_cam_comments(make_source("v.nc", ";Material Size: X=600 x Y=300 x Z=19\nG0 Z5\n"),
                              siemens());
  REQUIRE(s);
  CHECK(s->box.xmax == 600);
  CHECK(s->box.ymax == 300);
  for (const char* not_one :
       {"( Material Size)\n( X= 48.5, Y= 96.5)\n",
        "( Material Size)\n(Toolpaths used in this file:)\n( X= 1, Y= 2, Z= 3)\n",
        "( Material Size: X= 0, Y= 8, Z= 1)\n", "( X= 1, Y= 2, Z= 3)\n"}) {
    CAPTURE(std::string(not_one));
    CHECK_FALSE(one(not_one));
  }
}

TEST_CASE(
    "Sinumerik WORKPIECE: a BOX by two corners or a corner and lengths, a RECTANGLE centred") {
  auto blank = [](const std::string& line) {
    std::vector<Diagnostic> problems;
    auto s = stock_from_cam_comments(
        make_source("w.mpf", "; blank\nN10 G17 G90 G71\n" + line + "\nN30 T1 D1\n"), siemens(),
        1000, &problems);
    CHECK(problems.empty());
    return s;
  };
  // Siemens' own example: corners (0, 0) and (100, 100) absolute, Z from 0 down to -50.
  auto s = blank("N20 WORKPIECE(,\"\",,\"BOX\",112,0,-50,-80,0,0,100,100)");
  REQUIRE(s);
  CHECK(s->from == "sinumerik-workpiece");
  CHECK(s->origin == "WORKPIECE at line 3");
  CHECK(s->box.xmin == 0);
  CHECK(s->box.xmax == 100);
  CHECK(s->box.zmin == -50);
  CHECK(s->box.zmax == 0);
  // Fusion 360's 840D post: the upper corner first.
  s = blank("N20 WORKPIECE(,,,\"BOX\",112,0.5,-20,80,60,40,-60,-40)");
  REQUIRE(s);
  CHECK(s->box.xmin == -60);
  CHECK(s->box.xmax == 60);
  CHECK(s->box.ymin == -40);
  CHECK(s->box.zmin == -20);
  CHECK(s->box.zmax == 0.5);
  // No bits: Z1 and the second corner measured from Z0 and the first.
  s = blank("WORKPIECE(,\"\",,\"BOX\",0,2,-30,-80,-2,-2,184,170) ; allowance 2");
  REQUIRE(s);
  CHECK(s->box.xmin == -2);
  CHECK(s->box.xmax == 182);
  CHECK(s->box.ymax == 168);
  CHECK(s->box.zmin == -28);
  CHECK(s->box.zmax == 2);
  s = blank("WORKPIECE(,\"\",,\"RECTANGLE\",0,0,-12,0,80,50)");
  REQUIRE(s);
  CHECK(s->box.xmin == -40);
  CHECK(s->box.ymax == 25);
  CHECK(s->box.zmin == -12);
  // A blank in a comment is not one.
  CHECK_FALSE(blank("; WORKPIECE(,\"\",,\"BOX\",112,0,-50,-80,0,0,100,100)"));
}

TEST_CASE("a WORKPIECE that cannot be used is a warning at its line and column, never a stock") {
  for (const auto& [line, says] : std::vector<std::pair<std::string, std::string>>{
           {"N20 WORKPIECE(,\"\",,\"CYLINDER\",0,0,-50,-80,60)", "\"cylinder\" is not modelled"},
           {"N20 WORKPIECE(,\"\",,\"BOX\",112,0,-50", "not closed"},
           {"N20 WORKPIECE(,\"\",,\"BOX\",112,0,-50,-80,0,0)", "needs 12 arguments"},
           {"N20 WORKPIECE(,\"\",,\"BOX\",112,0,-50,-80,0,zero,100,100)", "'zero' is not a number"},
           {"N20 WORKPIECE(,\"\",,\"BOX\",112,0,0,-80,0,0,100,100)", "no volume"},
           {"N20 WORKPIECE()", "no blank type"}}) {
    CAPTURE(line);
    std::vector<Diagnostic> problems;
    const auto s = stock_from_cam_comments(make_source("w.mpf", "N10 G17\n" + line + "\n"),
                                           siemens(), 1000, &problems);
    CHECK_FALSE(s);
    REQUIRE(problems.size() == 1);
    CHECK(problems[0].severity == Severity::Warning);
    CHECK(problems[0].file == "w.mpf");
    CHECK(problems[0].line == 2);
    CHECK(problems[0].column == 5);
    CHECK(problems[0].message.find(says) != std::string::npos);
  }
}

TEST_CASE("a header stock is named in the estimate: its kind and where it is written") {
  const std::string program = vectric_header("Material Surface", "Bottom Left Corner") +
                              "(T1 D=6. CR=0. - FLAT END MILL)\nT1 M6\nS10000 M3\nG0 X10 Y10\n"
                              "G1 Z-2 F300\nG1 X100 F1200\nG1 Z-4\nG1 X10\nG0 Z5\nM5\nM30\n";
  const Estimate e = estimate_program(make_source("v.nc", program), generic(), {});
  REQUIRE(e.setups.size() == 1);
  CHECK(e.setups[0].stock_source == StockSource::Program);
  CHECK(e.setups[0].stock_from == "vectric");
  CHECK(e.setups[0].stock_origin == "Vectric Material Size block, lines 4-7");
  REQUIRE(e.setups[0].stock_box);
  CHECK(e.setups[0].stock_box->xmax == doctest::Approx(300));
  // A stock the options give comes first, named as they name it.
  EstimateOptions given;
  given.stock = parse_stock_spec("box:0,0,-5,120,20,0");
  given.stock->from = "option";
  const Estimate g = estimate_program(make_source("v.nc", program), generic(), given);
  CHECK(g.setups[0].stock_from == "option");
  CHECK(g.setups[0].stock_source == StockSource::Given);
  // Without a stock: guessed from the cuts.
  const Estimate none =
      estimate_program(make_source("n.nc", program.substr(program.find("(T1"))), generic(), {});
  CHECK(none.setups[0].stock_from == "guess");
}
