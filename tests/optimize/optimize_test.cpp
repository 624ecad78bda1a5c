// The optimizer on a synthetic program over a known box stock: which feed moves it finds clear,
// what it writes for them, what it puts back, and what it never touches.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "block_rewrite.hpp"
#include "ncjoule/annotate.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/optimize.hpp"
#include "ncjoule/profile.hpp"
#include "optimize_test_support.hpp"
#include "simple_block.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

// A 6 mm end mill over the box 0..40 x 0..20 x -10..0: plunges and links outside it in air, one
// cut across it at Z-2 and one back at Z-3.
const char* kProgram = "%\n"
                       "O1000 (AIR TEST)\n"
                       "G21 G90 G17\n"
                       "(T1 D=6. CR=0. - FLAT END MILL)\n"
                       "T1 M6\n"
                       "S8000 M3\n"
                       "G0 X-10. Y10. Z5.\n"
                       "G1 Z-2. F300.\n" // 7: plunge in air beside the stock
                       "X45.\n"          // 8: the cut, on the modal G1 and F300
                       "G1 Z5.\n"        // 9: retract in air
                       "X50. F1000.\n"   // 10: link at Z5
                       "Y12.\n"          // 11: link at Z5, on the modal F1000
                       "G1 Z-3. F200.\n" // 12: plunge in air
                       "X-10.\n"         // 13: the cut back
                       "G0 Z5.\n"
                       "M30\n"
                       "%\n";

struct Run {
  OptimizePlan plan;
  OptimizedText out;
  Estimate before;
};

Run optimize_text(const std::string& text, const OptimizeOptions& options = {}) {
  const SourceFile source = make_source("air.nc", text);
  const Started started(source, "box:0,0,-10,40,20,0");
  Run run;
  run.before = started.before;
  run.plan = plan_optimization(started.start->input, options);
  run.out = write_optimized(source, run.before.dialect, run.plan);
  return run;
}

// The optimized text without its header and its restore blocks: the original's lines, changed
// or not, in order.
std::vector<std::string> body_of(const std::string& text) {
  std::vector<std::string> out;
  for (const std::string& line : lines_of(text))
    if (line.rfind("(NCJOPT", 0) != 0 && line.find("(NCJOPT RESTORE)") == std::string::npos)
      out.push_back(line);
  return out;
}

} // namespace

TEST_CASE("moves in air are changed, cuts are not, and modal F and G1 are put back") {
  const Run run = optimize_text(kProgram);
  const std::string& out = run.out.text;
  CAPTURE(out);
  // Plunges beside the stock (descending: never rapids) run at the air feed.
  const BlockEdit* plunge = edit_on(run.plan, 7);
  REQUIRE(plunge);
  CHECK(plunge->rule == EditRule::AirFeed);
  CHECK(plunge->feed_mm_min > 300);
  CHECK(plunge->was_feed_mm_min == doctest::Approx(300));
  // The cut that relies on the plunge's F300 gets it back right after the plunge.
  CHECK(plunge->restore_feed);
  CHECK(plunge->restore_feed_mm_min == doctest::Approx(300));
  // The retract and the links at Z5 become rapids; the link on the modal G1 after them needs G1
  // back only where a later feed move relies on it (the plunge at line 12 writes its own G1).
  for (int line : {9, 10, 11}) {
    CAPTURE(line);
    REQUIRE(edit_on(run.plan, line));
    CHECK(edit_on(run.plan, line)->rule == EditRule::RapidLink);
    CHECK_FALSE(edit_on(run.plan, line)->restore_g1);
  }
  REQUIRE(edit_on(run.plan, 12));
  CHECK(edit_on(run.plan, 12)->rule == EditRule::AirFeed);
  // The cut back relies on the plunge's own F200, which the plunge no longer writes.
  CHECK(edit_on(run.plan, 12)->restore_feed);
  CHECK(edit_on(run.plan, 12)->restore_feed_mm_min == doctest::Approx(200));
  // The cuts are never changed.
  CHECK_FALSE(edit_on(run.plan, 8));
  CHECK_FALSE(edit_on(run.plan, 13));

  const std::vector<std::string> lines = lines_of(out);
  const std::vector<std::string> original = lines_of(kProgram);
  // The leading % and O-number line stay first; the header follows them.
  CHECK(lines[0] == "%");
  CHECK(lines[1] == "O1000 (AIR TEST)");
  CHECK(lines[2].rfind("(NCJOPT OPTIMIZED COPY", 0) == 0);
  // Every original line is there, in order; those not changed byte for byte.
  const std::vector<std::string> body = body_of(out);
  REQUIRE(body.size() == original.size());
  for (std::size_t i = 0; i < original.size(); ++i) {
    CAPTURE(i);
    if (edit_on(run.plan, int(i)))
      CHECK(body[i].find("(NCJOPT ") != std::string::npos);
    else
      CHECK(body[i] == original[i]);
  }
  CHECK(body[7] == "G1 Z-2. F" + optimize_detail::format_feed(plunge->feed_mm_min, false) +
                       " (NCJOPT AIR F" + optimize_detail::format_feed(plunge->feed_mm_min, false) +
                       " WAS F300.)");
  CHECK(body[9] == "G0 Z5. (NCJOPT RAPID WAS G1)");
  CHECK(body[10] == "G0 X50. F1000. (NCJOPT RAPID WAS G1)");
  CHECK(body[11] == "G0 Y12. (NCJOPT RAPID WAS G1)");
  // The restore block comes right after the plunge.
  const std::size_t plunge_at =
      std::size_t(std::find(lines.begin(), lines.end(), body[7]) - lines.begin());
  REQUIRE(plunge_at + 1 < lines.size());
  CHECK(lines[plunge_at + 1] == "F300. (NCJOPT RESTORE)");
  CHECK(run.out.changed_blocks == run.plan.edits.size());
  CHECK(run.out.restore_blocks == 2);
}

TEST_CASE("a block that moved on the modal G1 after a G1 turned G0 writes G1 itself") {
  // Modal G1 throughout: the retract and the link become rapids; the plunge beside the stock
  // after them runs at the air feed and writes G1; the ramp into the stock writes G1 as well.
  const std::string text = "G21 G90\n(T1 D=6. CR=0. - FLAT END MILL)\nT1 M6\nS8000 M3\n"
                           "G0 X-10 Y10 Z5\nG1 Z-2 F300\nX45\nZ5\nX-10\nZ-3\nX45\nZ5\n"
                           "X-10\nX20 Z-1\nG0 Z5\nM30\n";
  const Run run = optimize_text(text);
  CAPTURE(run.out.text);
  const std::vector<std::string> body = body_of(run.out.text);
  CHECK(body[7] == "G0 Z5 (NCJOPT RAPID WAS G1)");
  CHECK(body[8] == "G0 X-10 (NCJOPT RAPID WAS G1)");
  REQUIRE(edit_on(run.plan, 9));
  CHECK(edit_on(run.plan, 9)->insert_g1);
  CHECK(body[9].rfind("G1 Z-3 F", 0) == 0);
  CHECK(body[10] == "X45"); // the cut: as it was (its F300 comes back after line 9)
  CHECK(body[13] == "G1 X20 Z-1 (NCJOPT RESTORE G1)");
  REQUIRE(edit_on(run.plan, 13));
  CHECK(edit_on(run.plan, 13)->rule == EditRule::RestoreG1);
  // No G1 alone: every restore of G1 sits on the block that relies on it.
  CHECK(run.out.text.find("\nG1 (NCJOPT RESTORE)") == std::string::npos);
  CHECK(run.out.text.find("F300. (NCJOPT RESTORE)") != std::string::npos);
}

TEST_CASE("the optimized program removes the same volume, faster, with no new collision") {
  const Run run = optimize_text(kProgram);
  const SourceFile after_source = make_source("air-opt.nc", run.out.text);
  EstimateOptions eo;
  eo.stock = parse_stock_spec("box:0,0,-10,40,20,0");
  const Estimate after = estimate_program(after_source, machine(), eo);
  REQUIRE(after.removal);
  CHECK(after.removal->removed_mm3 ==
        doctest::Approx(run.before.removal->removed_mm3).epsilon(0.005));
  CHECK(run.before.removal->removed_mm3 > 800); // two cuts across 40 mm of it
  CHECK(after.time_s < run.before.time_s);
  CHECK(after.time.air_cut_s < run.before.time.air_cut_s);
  for (const Diagnostic& d : after.diagnostics)
    CHECK(d.message.find("collision") == std::string::npos);
}

TEST_CASE("each rule is its own switch") {
  OptimizeOptions no_rapids;
  no_rapids.rapid_links = false;
  const Run air_only = optimize_text(kProgram, no_rapids);
  REQUIRE_FALSE(air_only.plan.edits.empty());
  for (const BlockEdit& e : air_only.plan.edits)
    CHECK(e.rule == EditRule::AirFeed);
  // Without rapids, the link at line 10 (F1000) still gets the air feed.
  CHECK(edit_on(air_only.plan, 10));
  OptimizeOptions neither;
  neither.rapid_links = neither.air_feeds = false;
  const Run none = optimize_text(kProgram, neither);
  CHECK(none.plan.edits.empty());
  CHECK(none.out.text == kProgram); // nothing changed: the same bytes, no header
}

TEST_CASE("a move that passes near the stock within the margin is left as it is") {
  // The link at Z0.5 over the stock's top (Z0): clear of the tool, not of the margin.
  const std::string text = "G21 G90\n(T1 D=6. CR=0. - FLAT END MILL)\nT1 M6\nS8000 M3\n"
                           "G0 X-10 Y10 Z5\nG1 Z0.5 F300\nG1 X50 F1000\nG1 Z-2 F300\n"
                           "G1 X-10 F600\nG0 Z5\nM30\n";
  const Run run = optimize_text(text);
  CAPTURE(run.out.text);
  CHECK_FALSE(edit_on(run.plan, 6)); // over the top by 0.5 mm < margin 1 mm
  CHECK(edit_on(run.plan, 5));       // the plunge to Z0.5 beside the stock is clear
  // With a margin of 0.4 mm the link is clear: a rapid (it does not descend).
  OptimizeOptions small;
  small.margin_mm = 0.4;
  const Run near = optimize_text(text, small);
  REQUIRE(edit_on(near.plan, 6));
  CHECK(edit_on(near.plan, 6)->rule == EditRule::RapidLink);
}

TEST_CASE("material the program removed earlier is air for later moves") {
  // Facing the whole top 2 mm down (passes along X, step-overs beside the stock), then a link at
  // Z-0.5 across where it was: clear only because the facing passes took the material away (the
  // stock's top was Z0).
  const std::string text = "G21 G90\n(T1 D=6. CR=0. - FLAT END MILL)\nT1 M6\nS8000 M3\n"
                           "G0 X-5 Y-3 Z5\nG1 Z-2 F300\n"
                           "G1 X45 F600\nG1 Y1\nG1 X-5\nG1 Y5\nG1 X45\nG1 Y9\nG1 X-5\n"
                           "G1 Y13\nG1 X45\nG1 Y17\nG1 X-5\nG1 Y21\nG1 X45\nG1 Y24\n"
                           "G1 Z-0.5 F300\nG1 X-5 Y-4 F600\nG0 Z5\nM30\n";
  const Run run = optimize_text(text);
  CAPTURE(run.out.text);
  const int link = 21; // G1 X-5 Y-4 at Z-0.5, over the faced area
  REQUIRE(edit_on(run.plan, link));
  CHECK(edit_on(run.plan, link)->rule == EditRule::RapidLink);
  for (int line = 6; line <= 18; line += 2) // the facing passes cut
    CHECK_FALSE(edit_on(run.plan, line));
  for (int line = 7; line <= 19; line += 2) { // the step-overs run 2 mm beside the stock
    REQUIRE(edit_on(run.plan, line));
    CHECK(edit_on(run.plan, line)->rule == EditRule::RapidLink);
  }
  // The same link before any facing would cut: left as it is.
  const std::string early = "G21 G90\n(T1 D=6. CR=0. - FLAT END MILL)\nT1 M6\nS8000 M3\n"
                            "G0 X45 Y24 Z5\nG1 Z-0.5 F300\nG1 X-5 Y-4 F600\nG0 Z5\nM30\n";
  const Run first = optimize_text(early);
  CHECK(edit_on(first.plan, 5));       // the plunge beside the stock
  CHECK_FALSE(edit_on(first.plan, 6)); // the link through it
}

TEST_CASE("blocks that are not simple are never changed") {
  const Dialect linuxcnc = *find_dialect("linuxcnc");
  CHECK(optimize_detail::read_simple_block("G1 X10 F500 (note)", linuxcnc));
  CHECK(optimize_detail::read_simple_block("N20 g01 x1.5 y-.5", linuxcnc));
  CHECK_FALSE(optimize_detail::read_simple_block("G1 X[10+2]", linuxcnc));
  CHECK_FALSE(optimize_detail::read_simple_block("G1 X#1", linuxcnc));
  CHECK_FALSE(optimize_detail::read_simple_block("G1 X10 M8", linuxcnc));
  CHECK_FALSE(optimize_detail::read_simple_block("G91 G1 X10", linuxcnc));
  CHECK_FALSE(optimize_detail::read_simple_block("/G1 X10", linuxcnc));
  CHECK_FALSE(optimize_detail::read_simple_block("G1 X10 X20", linuxcnc));
  CHECK_FALSE(optimize_detail::read_simple_block("(only a comment)", linuxcnc));
  CHECK(optimize_detail::writes_motion_word("G02 X1 Y1 I1 J0", linuxcnc));
  CHECK_FALSE(optimize_detail::writes_motion_word("G81 X1 Y1 Z-1 R1", linuxcnc));
  CHECK_FALSE(optimize_detail::writes_motion_word("X1 Y1", linuxcnc));
}

TEST_CASE("changed blocks are written in the program's units and the dialect's form") {
  const Dialect fanuc = *find_dialect("fanuc");
  const Dialect grbl = *find_dialect("grbl");
  BlockEdit air;
  air.rule = EditRule::AirFeed;
  air.feed_mm_min = 5000;
  air.was_feed_mm_min = 25.4 * 20;
  // Inches: in/min, with the decimal point the Fanuc family needs.
  CHECK(optimize_detail::rewrite_block("N10 G01 X1. F20.", fanuc, air, true) ==
        "N10 G01 X1. F196.8504 (NCJOPT AIR F196.8504 WAS F20.)");
  CHECK(optimize_detail::format_feed(5000, false) == "5000.");
  // A ';' comment runs to the line's end: the mark goes before an existing one.
  BlockEdit rapid;
  rapid.rule = EditRule::RapidLink;
  CHECK(optimize_detail::rewrite_block("G1 Z5 ; up", grbl, rapid, false) ==
        (grbl.paren_comments ? "G0 Z5 (NCJOPT RAPID WAS G1) ; up"
                             : "G0 Z5 ;NCJOPT RAPID WAS G1 ; up"));
  CHECK(optimize_detail::rewrite_block("N5 Z5", fanuc, rapid, false) ==
        "N5 G0 Z5 (NCJOPT RAPID WAS G1)");
  CHECK(optimize_detail::rewrite_block("G01 Z5", fanuc, rapid, false) ==
        "G00 Z5 (NCJOPT RAPID WAS G1)");
  // Past the dialect's line length: not changed.
  Dialect short_lines = fanuc;
  short_lines.max_line_length = 20;
  CHECK_FALSE(optimize_detail::rewrite_block("G01 Z5", short_lines, rapid, false));
}

TEST_CASE("strip leaves the optimizer's marks: the program is different") {
  const Run run = optimize_text(kProgram);
  REQUIRE(run.out.changed_blocks > 0);
  CHECK(strip(run.out.text) == run.out.text);
}

TEST_CASE("the dexel engine says where material lies above a height near a segment") {
  const Box3 box{0, 0, -10, 40, 20, 0};
  const std::unique_ptr<StockShape> stock = make_box_stock(box, "box");
  const GridFrame grid = make_grid(box, 0.5);
  const std::unique_ptr<RemovalEngine> engine =
      make_removal_engine(EngineKind::Dexel, *stock, grid);
  // Beside the stock by 5 mm: clear within 4 mm, not within 6 mm.
  CHECK(engine->material_above({-5, 0, 0}, {-5, 20, 0}, 4, -20) == false);
  CHECK(engine->material_above({-5, 0, 0}, {-5, 20, 0}, 6, -20) == true);
  // Over it: clear above its top, not below it.
  CHECK(engine->material_above({10, 10, 2}, {30, 10, 2}, 4, 0.5) == false);
  CHECK(engine->material_above({10, 10, 2}, {30, 10, 2}, 4, -0.5) == true);
  // A diagonal passing the corner (40, 20) at sqrt(2) * 3.5 = 4.95 mm.
  CHECK(engine->material_above({47, 20, 0}, {40, 27, 0}, 4.5, -20) == false);
  CHECK(engine->material_above({47, 20, 0}, {40, 27, 0}, 5.5, -20) == true);
  // What a step removes is gone for the question.
  engine->remove_step(Tool{1, ToolShape::FlatEndMill, 10}, {-10, 10, -3}, {50, 10, -3});
  CHECK(engine->material_above({-5, 10, -1}, {45, 10, -1}, 1, -2) == false);
  CHECK(engine->material_above({-5, 10, -1}, {45, 10, -1}, 1, -4) == true);
  // The voxel engine does not answer.
  const std::unique_ptr<RemovalEngine> voxel =
      make_removal_engine(EngineKind::Voxel, *stock, make_grid(box, 2));
  CHECK_FALSE(voxel->material_above({-5, 0, 0}, {-5, 20, 0}, 4, -20).has_value());
}
