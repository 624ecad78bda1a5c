// Stock: the --stock text, STL files (binary and ASCII), the default box.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "fixture.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

} // namespace

TEST_CASE("stock specifications") {
  std::vector<Diagnostic> problems;
  auto box = parse_stock_spec("box:-10,-5,-20,100,50.5,0", &problems);
  REQUIRE(box);
  CHECK(box->kind == StockSpec::Kind::Box);
  CHECK(box->box.xmin == -10);
  CHECK(box->box.ymax == 50.5);
  CHECK(box->box.zmax == 0);
  auto stl = parse_stock_spec("parts/Blank.STL");
  REQUIRE(stl);
  CHECK(stl->kind == StockSpec::Kind::Stl);
  CHECK(stl->stl_path == "parts/Blank.STL");
  CHECK(parse_stock_spec("")->kind == StockSpec::Kind::Default);
  CHECK(problems.empty());
  CHECK_FALSE(parse_stock_spec("box:1,2,3", &problems));
  REQUIRE(problems.size() == 1);
  CHECK(problems[0].message.find("six numbers") != std::string::npos);
  CHECK_FALSE(parse_stock_spec("box:0,0,0,-1,1,1", &problems));
  CHECK_FALSE(parse_stock_spec("cube", &problems));
  CHECK(problems.size() == 3);
  for (const Diagnostic& d : problems)
    CHECK(d.severity == Severity::Error);
}

TEST_CASE("a stock written in a file is reported at the line and column of the bad number") {
  // `stock = "box:0,0,0,1,1,x"` in a config file: the value starts at column 10 of line 3.
  std::vector<Diagnostic> problems;
  CHECK_FALSE(parse_stock_spec("box:0,0,0,1,1,x", &problems, {"config.toml", 3, 10}));
  REQUIRE(problems.size() == 1);
  CHECK(problems[0].file == "config.toml");
  CHECK(problems[0].line == 3);
  CHECK(problems[0].column == 10 + 14); // the 'x'
  CHECK(format_diagnostic(problems[0]) ==
        "config.toml:3:24: error: stock box value 'x' is not a number (with an "
        "optional unit: mm, in)");
  // From the command line: named by the option, no line.
  problems.clear();
  CHECK_FALSE(parse_stock_spec("cube", &problems, {"--stock 'cube'"}));
  REQUIRE(problems.size() == 1);
  CHECK(format_diagnostic(problems[0]).rfind("--stock 'cube': error: stock 'cube' is neither", 0) ==
        0);
}

TEST_CASE("STL stock, binary and ASCII") {
  const std::string dir = temp_dir();
  const Box3 cube{2, 3, -6, 12, 23, -1}; // 10 x 20 x 5
  const TriangleMesh mesh = box_mesh(cube);
  const std::string binary = dir + "/cube_binary.stl", ascii = dir + "/cube_ascii.stl";
  write_file(binary, binary_stl(mesh));
  write_file(ascii, ascii_stl(mesh));

  for (const std::string& path : {binary, ascii}) {
    CAPTURE(path);
    std::vector<Diagnostic> problems;
    const auto read = read_stl(path, problems);
    REQUIRE(read);
    CHECK(read->triangles.size() == 12);
    const Box3 b = read->bounds();
    CHECK(b.xmin == 2);
    CHECK(b.zmax == -1);

    // A 4 mm end mill plunging 2 mm into the top of the cube.
    const std::map<int, Tool> tools{{1, flat_end_mill(1, 4)}};
    ProgramBuilder p;
    p.tool(1).feed_rate(100).rapid(7, 13, 5).feed(7, 13, -3).rapid(7, 13, 5);
    const auto spec = parse_stock_spec(path);
    REQUIRE(spec);
    const RemovalResult r =
        simulate_removal(p.commands(), constant_speed_timeline(p.commands(), 0.05), tools, *spec);
    CHECK(r.diagnostics.empty());
    CHECK(r.stock_description.find("STL") != std::string::npos);
    CHECK(r.stock_volume_mm3 == doctest::Approx(1000).epsilon(1e-9));
    CHECK(r.removed_mm3 == doctest::Approx(std::numbers::pi * 4 * 2).epsilon(2e-3));
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("STL stock with a gap: columns hold two intervals") {
  TriangleMesh two = box_mesh({0, 0, 0, 10, 10, 2});
  const TriangleMesh top = box_mesh({0, 0, 3, 10, 10, 5});
  two.triangles.insert(two.triangles.end(), top.triangles.begin(), top.triangles.end());
  std::vector<Diagnostic> problems;
  const auto mesh = parse_stl(ascii_stl(two), "two.stl", problems);
  REQUIRE(mesh);
  const auto stock = make_mesh_stock(*mesh, "two slabs");
  const Tool t = flat_end_mill(1, 4);
  for (EngineKind kind : {EngineKind::Dexel, EngineKind::Voxel}) {
    CAPTURE(engine_name(kind));
    auto engine = make_removal_engine(kind, *stock, make_grid(stock->bounds(), 0.05));
    CHECK(engine->material_volume_mm3() == doctest::Approx(400).epsilon(1e-9));
    const double area = std::numbers::pi * 4;
    // Into the upper slab only, then through the gap into the lower one.
    const double v1 = engine->remove_step(t, {5, 5, 6}, {5, 5, 3.5});
    CHECK(v1 == doctest::Approx(area * 1.5).epsilon(3e-3));
    const double v2 = engine->remove_step(t, {5, 5, 3.5}, {5, 5, 1});
    CHECK(v2 == doctest::Approx(area * 1.5).epsilon(3e-3)); // 0.5 of the top slab, 1 of the bottom
  }
}

TEST_CASE("default stock: bounding box of the cutting moves") {
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 6)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(300).rapid(-50, -50, 20).rapid(0, 0, 1).feed(0, 0, -1).feed(40, 0, -1);
  p.feed(40, 0, -3).arc(40, 20, -3, 40, 10, +1).rapid(40, 20, 20);
  const Timeline tl = constant_speed_timeline(p.commands(), 0.1);
  const auto box = default_stock_box(p.commands(), tl, tools);
  REQUIRE(box);
  CHECK(box->xmin == doctest::Approx(-3));
  CHECK(box->xmax == doctest::Approx(40 + 10 + 3)); // the arc bulges to x = 50
  CHECK(box->ymin == doctest::Approx(-3));
  CHECK(box->ymax == doctest::Approx(23));
  CHECK(box->zmin == -3);
  CHECK(box->zmax == -1); // the highest level move; the plunge from Z1 and rapids do not count

  const RemovalResult r = simulate_removal(p.commands(), tl, tools, StockSpec{});
  CHECK(r.stock_description.find("guessed") != std::string::npos);
  CHECK(r.stock_description.find("top: Z0") != std::string::npos);
  CHECK(r.removed_mm3 > 0);

  ProgramBuilder air;
  air.tool(1).rapid(0, 0, 5).rapid(10, 0, 5);
  const RemovalResult none = simulate_removal(
      air.commands(), constant_speed_timeline(air.commands(), 0.1), tools, StockSpec{});
  CHECK(none.removed_mm3 == 0);
  REQUIRE(none.diagnostics.size() == 1);
  CHECK(none.diagnostics[0].severity == Severity::Warning);
}

TEST_CASE("default stock: a ramp down to the only cutting level starts at the stock's top") {
  // BlenderCAM's helix entry: from Z0 down to Z-5 while travelling in XY, then every level move
  // at Z-5. Level moves alone give a stock of no height (nothing removed).
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 6)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(300).rapid(0, 0, 10).feed(0, 0, 0).feed(10, 0, -2.5).feed(0, 0, -5);
  p.feed(40, 0, -5).feed(40, 20, -5).rapid(40, 20, 10);
  const Timeline tl = constant_speed_timeline(p.commands(), 0.1);
  const auto box = default_stock_box(p.commands(), tl, tools);
  REQUIRE(box);
  CHECK(box->zmax == 0);
  CHECK(box->zmin == -5);
  const RemovalResult r = simulate_removal(p.commands(), tl, tools, StockSpec{});
  CHECK(r.removed_mm3 > 0);
}

TEST_CASE("default stock: feed plunges from a clearance plane do not raise its top") {
  // Two slots, at Z-2 and Z-4, each entered by a feed plunge from the clearance plane Z10;
  // between them the tool crosses at the retract plane Z2 by rapid. A top at the clearance
  // plane would put the rapid at Z2 inside the stock (a false collision) and count the plunges'
  // way through 12 mm of air as cutting.
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 6)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(300).rapid(0, 0, 10).feed(0, 0, -2).feed(40, 0, -2).rapid(40, 0, 2);
  p.rapid(0, 0, 2).rapid(0, 0, 10).feed(0, 0, -4).feed(40, 0, -4).rapid(40, 0, 10);
  const Timeline tl = constant_speed_timeline(p.commands(), 0.1);
  const auto box = default_stock_box(p.commands(), tl, tools);
  REQUIRE(box);
  CHECK(box->zmax == -2);
  CHECK(box->zmin == -4);

  // The guess: the top at Z0 (every cut runs below it), the slots cut 2 mm deep each, in a
  // stock as wide as their grooves (lines: the tool's edge, not its centre, is within it).
  const RemovalResult r = simulate_removal(p.commands(), tl, tools, StockSpec{});
  for (const Diagnostic& d : r.diagnostics)
    CHECK_MESSAGE(d.severity == Severity::Note, d.message);
  for (const CommandRemoval& c : r.commands)
    CHECK_FALSE(c.collision);
  const double layer = (40 * 6 + std::numbers::pi * 9) * 2; // a 2 mm layer of one groove
  CHECK(r.stock_volume_mm3 == doctest::Approx(46 * 6 * 4).epsilon(1e-9));
  CHECK(r.removed_mm3 == doctest::Approx(2 * layer).epsilon(2e-3));
  // The first slot (its plunge and its pass) removes the top layer; the rapid at Z2 runs above.
  CHECK(r.commands[1].removed_mm3 + r.commands[2].removed_mm3 ==
        doctest::Approx(layer).epsilon(2e-3));
}

TEST_CASE("default stock: positioning at a high feed does not raise its top or widen it") {
  // Fusion's "high feed" between passes: G1 F5000 at the retract plane Z5 and out to X200,
  // where the tool cuts at F480. Taken as cuts, the stock's top would be Z5 and every pass a
  // 5 mm deep slot, and the stock would reach X200.
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 6)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(5000).rapid(0, 0, 15).feed(0, 0, 5).feed(200, 0, 5).feed(0, 10, 5);
  p.feed_rate(480).feed(0, 10, -1).feed(40, 10, -1).feed(40, 20, -2).feed(0, 20, -2);
  p.feed_rate(5000).feed(0, 20, 5).feed(200, 40, 5);
  StockExtent extent;
  for (const CanonCommand& c : p.commands())
    extent.add(c);
  const auto box = extent.box(tools);
  REQUIRE(box);
  CHECK(box->zmax == -1); // the highest level the tool cuts at
  CHECK(box->zmin == -2);
  CHECK(box->xmax == doctest::Approx(43)); // not X200 + 3
  CHECK(box->ymax == doctest::Approx(23));
  CHECK(extent.positioning_moves() == 3);
}

TEST_CASE("default stock: level feed moves at the first plunge's height are positioning") {
  // A post that writes no G0 (personal-use Fusion, MPCNC-style): the tool crosses at the
  // clearance plane Z15 at the cutting feed, plunges from there, and cuts at Z-1.
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 6)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(1000).feed(0, 0, 15).feed(100, 50, 15).feed(10, 10, 15);
  p.feed(10, 10, -1).feed(50, 10, -1).feed(50, 30, -1).feed(50, 30, 15).feed(0, 0, 15);
  StockExtent extent;
  for (const CanonCommand& c : p.commands())
    extent.add(c);
  const auto box = extent.box(tools);
  REQUIRE(box);
  CHECK(box->zmax == -1);
  CHECK(box->xmax == doctest::Approx(53));
  CHECK(extent.positioning_moves() == 3);
  // A program of level cuts at one feed with no plunge keeps them all (nothing to tell them by).
  ProgramBuilder flat;
  flat.tool(1).feed_rate(1000).rapid(0, 0, -1).feed(40, 0, -1).feed(40, 20, -1);
  StockExtent flat_extent;
  for (const CanonCommand& c : flat.commands())
    flat_extent.add(c);
  CHECK(flat_extent.positioning_moves() == 0);
}

TEST_CASE("default stock: up, across at the cutting feed, down is a link, not a cut") {
  // Personal-use Fusion: every move at the cutting feed. After a pass at Z2 the tool rises to
  // its retract height Z20, crosses there and comes down for the next pass; the first plunge
  // started higher (Z30), so the plunge's height alone does not tell the link from a cut.
  const std::map<int, Tool> tools{{1, flat_end_mill(1, 6)}};
  ProgramBuilder p;
  p.tool(1).feed_rate(1000).rapid(0, 0, 30).feed(0, 0, 20).feed(0, 0, 2).feed(40, 0, 2);
  p.feed(40, 0, 20).feed(40, 30, 20).feed(0, 30, 20).feed(0, 30, 4).feed(40, 30, 4);
  StockExtent extent;
  for (const CanonCommand& c : p.commands())
    extent.add(c);
  auto box = extent.box(tools);
  REQUIRE(box);
  CHECK(box->zmax == 4); // the highest pass, not the retract height
  CHECK(extent.positioning_moves() == 2);
  // A waterline stepping up (rise, a pass at the new height, rise again) cuts at every height.
  ProgramBuilder up;
  up.tool(1).feed_rate(1000).rapid(0, 0, 30).feed(0, 0, -4).feed(40, 0, -4).feed(40, 0, -2);
  up.feed(0, 0, -2).feed(0, 0, 0).feed(40, 0, 0).feed(40, 0, 10);
  StockExtent waterline;
  for (const CanonCommand& c : up.commands())
    waterline.add(c);
  box = waterline.box(tools);
  REQUIRE(box);
  CHECK(box->zmax == 0);
  CHECK(waterline.positioning_moves() == 0);
  // A rapid down beside the part between the rise and the pass: the pass cuts in from the side.
  ProgramBuilder side;
  side.tool(1).feed_rate(1000).rapid(-10, 0, 30).feed(-10, 0, -3).feed(40, 0, -3);
  side.feed(40, 0, 5).rapid(-10, 20, 5).rapid(-10, 20, -1).feed(40, 20, -1).feed(40, 20, -3);
  StockExtent side_extent;
  for (const CanonCommand& c : side.commands())
    side_extent.add(c);
  box = side_extent.box(tools);
  REQUIRE(box);
  CHECK(box->zmax == -1);
}

TEST_CASE("a bad STL is a diagnostic naming the file and, in ASCII, the line") {
  std::vector<Diagnostic> problems;
  const std::string text = "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                           "vertex 1 0 nan\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n";
  CHECK_FALSE(parse_stl(text, "nan.stl", problems));
  REQUIRE(problems.size() == 1);
  CHECK(problems[0].severity == Severity::Error);
  CHECK(problems[0].file == "nan.stl");
  CHECK(problems[0].line == 5);
  CHECK(problems[0].message.find("finite") != std::string::npos);
  problems.clear();
  CHECK_FALSE(read_stl("no/such/file.stl", problems));
  REQUIRE(problems.size() == 1);
  CHECK(problems[0].file == "no/such/file.stl");
}

TEST_CASE("an STL's crossings count in its memory: stacked shells need more than a solid") {
  // One square as two triangles, seen from above: a vertical line meets one triangle.
  auto square = [](double z) {
    const double corners[2][3][3] = {{{0, 0, z}, {10, 0, z}, {10, 10, z}},
                                     {{0, 0, z}, {10, 10, z}, {0, 10, z}}};
    std::vector<Triangle> t(2);
    for (int k = 0; k < 2; ++k)
      for (int v = 0; v < 3; ++v)
        for (int c = 0; c < 3; ++c)
          t[k].v[v][c] = corners[k][v][c];
    return t;
  };
  TriangleMesh slab; // top and bottom: a closed slab's two crossings per column
  for (double z : {0.0, -5.0})
    for (const Triangle& t : square(z))
      slab.triangles.push_back(t);
  CHECK(slab.crossings_per_column() == doctest::Approx(2));
  TriangleMesh stacked; // forty layers over the same square, as a 4 KB ASCII STL can hold
  for (int k = 0; k < 40; ++k)
    for (const Triangle& t : square(-k))
      stacked.triangles.push_back(t);
  CHECK(stacked.crossings_per_column() == doctest::Approx(40));

  const GridFrame grid = make_grid(stacked.bounds(), 0.01); // a million columns
  const std::size_t box = estimated_removal_memory(EngineKind::Dexel, grid, StockSpec::Kind::Box);
  const std::size_t solid =
      estimated_removal_memory(EngineKind::Dexel, grid, StockSpec::Kind::Stl, 2);
  const std::size_t layers =
      estimated_removal_memory(EngineKind::Dexel, grid, StockSpec::Kind::Stl, 40);
  CHECK(solid > box);
  // Each of the 40 crossings of a million columns is 16 bytes in an array that may be twice its
  // size, and half an interval: 1.6 GB at least.
  CHECK(layers > std::size_t(40) * 1'000'000 * 40);
  CHECK(estimated_removal_memory(EngineKind::Voxel, grid, StockSpec::Kind::Stl, 40) >
        std::size_t(40) * 1'000'000 * 40);
}

TEST_CASE("a stock wider than any machine is refused before a grid is tried, naming its size") {
  for (const char* spec :
       {"box:0,0,-10,200000,10,0", "box:-1e300,-1e300,-1e300,1e300,1e300,1e300"}) {
    CAPTURE(spec);
    std::vector<Diagnostic> problems;
    const auto stock = parse_stock_spec(spec, &problems);
    REQUIRE(stock);
    StockExtent extent;
    const RemovalSimulator sim(*stock, extent, {}, RemovalOptions{});
    CHECK_FALSE(sim.ready());
    bool said = false;
    for (const Diagnostic& d : sim.summary().diagnostics)
      said = said || (d.severity == Severity::Error &&
                      d.message.find("more than any machine's travel") != std::string::npos &&
                      d.message.find("units") != std::string::npos);
    CHECK(said);
  }
}

TEST_CASE("stock values may carry a unit: without one they follow the program's units") {
  CHECK(parse_length("12.5")->first == 12.5);
  CHECK(parse_length("12.5")->second == LengthUnit::Program);
  CHECK(parse_length("-1in")->second == LengthUnit::Inch);
  CHECK(parse_length("-1in")->first == -1);
  CHECK(parse_length(" 2 inch ")->second == LengthUnit::Inch);
  CHECK(parse_length("0.5\"")->second == LengthUnit::Inch);
  CHECK(parse_length("25.4MM")->second == LengthUnit::Mm);
  CHECK_FALSE(parse_length("in"));
  CHECK_FALSE(parse_length("3cm"));

  const auto unitless = parse_stock_spec("box:0,0,-1,4,3,0");
  REQUIRE(unitless);
  CHECK(unitless->follows_program_units());
  CHECK(unitless->in_mm(true).box.xmax == doctest::Approx(101.6)); // an inch program's stock
  CHECK(unitless->in_mm(false).box.xmax == 4);
  const auto inches = parse_stock_spec("box:0,0,-1in,4in,3in,0");
  REQUIRE(inches);
  CHECK_FALSE(inches->follows_program_units()); // 0 has no unit, but 0 in any unit is 0
  CHECK(inches->in_mm(false).box.zmin == doctest::Approx(-25.4));
  // A box written in two units is checked in one: 1 in is above 20 mm.
  CHECK(parse_stock_spec("box:0,0,-20mm,1in,1in,0"));
  std::vector<Diagnostic> problems;
  CHECK_FALSE(parse_stock_spec("box:0,0,-1in,20mm,30mm,-30mm", &problems)); // top below bottom
  // A job file's units apply to values without one.
  const auto job = parse_stock_spec("box:0,0,-1,4,3,0", nullptr, {}, LengthUnit::Inch);
  REQUIRE(job);
  CHECK_FALSE(job->follows_program_units());
  CHECK(job->in_mm(false).box.ymax == doctest::Approx(76.2));
}

TEST_CASE("a stock 25.4 times too small or away from the cuts is said to be a unit mix-up") {
  const Box3 cuts{0, 0, -10, 100, 60, 0};
  // An inch program's stock typed in mm under the old rule, read in inches: 25.4 times too big.
  const auto mm_typed = parse_stock_spec("box:0,0,-20,100,60,0");
  REQUIRE(mm_typed);
  const std::string big = stock_mismatch(mm_typed->in_mm(true).box, cuts, *mm_typed, true);
  CHECK(big.find("25.4 times larger") != std::string::npos);
  CHECK(big.find("inches, G20") != std::string::npos);
  // Inches typed for a mm program: 25.4 times too small.
  const auto inch_typed = parse_stock_spec("box:0,0,-0.8,4,2.4,0");
  REQUIRE(inch_typed);
  const std::string small = stock_mismatch(inch_typed->in_mm(false).box, cuts, *inch_typed, false);
  CHECK(small.find("25 times smaller") != std::string::npos);
  // The right stock, and one a little larger: nothing said.
  CHECK(stock_mismatch(Box3{-5, -5, -20, 105, 65, 0}, cuts, *mm_typed, false).empty());
  CHECK(stock_mismatch(Box3{0, 0, -10, 400, 240, 0}, cuts, *mm_typed, false).empty());
  // Beside the cuts: a stock for another work offset, or its numbers in the wrong place.
  const auto units = parse_stock_spec("box:0,0,-1in,4in,3in,0");
  REQUIRE(units);
  const std::string beside = stock_mismatch(Box3{200, 0, -10, 300, 60, 0}, cuts, *units, false);
  CHECK(beside.find("beside the program's cuts") != std::string::npos);
  CHECK(beside.find("another work offset") != std::string::npos);
}
