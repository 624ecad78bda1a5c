// Rule c, feeds to a load target, on a synthetic program over a known box stock: a heavy slot
// above the share is slowed until its predicted power is within it, a light pass is sped up by
// at most the factor, and a finishing pass and moves in air are left as they are.
#include <doctest/doctest.h>

#include <map>
#include <string>
#include <vector>

#include "ncjoule/estimate.hpp"
#include "ncjoule/optimize.hpp"
#include "ncjoule/profile.hpp"
#include "optimize_test_support.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

// A 12 mm end mill over the box 0..40 x 0..20 x -10..0 (aluminium, a 5.5 kW spindle): a full
// slot 8 mm deep at F5000 (about 8000 mm3/s, above 70% of the rating), a pass 2 mm wide and 3 mm
// deep at F1000 (far below it), a skim 0.2 mm deep (a finishing pass), and feed moves in air.
const char* kProgram = "%\n"
                       "O1000 (LOAD TEST)\n"
                       "G21 G90 G17\n"
                       "(T1 D=12. CR=0. - FLAT END MILL)\n"
                       "T1 M6\n"
                       "S8000 M3\n"
                       "G0 X-10. Y10. Z5.\n"
                       "G1 Z-8. F5000.\n" // 7: plunge in air beside the stock
                       "X50.\n"           // 8: the heavy slot
                       "G0 Z5.\n"
                       "G0 X-10. Y-4.\n"
                       "G1 Z-3. F1000.\n" // 11: plunge in air
                       "X20.\n"           // 12: the light pass, on the modal F1000
                       "X50.\n"           // 13: more of it, the same feed
                       "G0 Z5.\n"
                       "G0 X-10. Y15.\n"
                       "G1 Z-0.2 F800.\n" // 16: plunge in air
                       "X50.\n"           // 17: the skim, 0.2 mm deep
                       "G1 Z5.\n"         // 18: retract in air
                       "X60. F700.\n"     // 19: link in air
                       "G0 Z20.\n"
                       "M30\n"
                       "%\n";

constexpr const char* kStock = "box:0,0,-10,40,20,0";

EstimateOptions with_stock() {
  EstimateOptions eo;
  eo.stock = parse_stock_spec(kStock);
  return eo;
}

struct Run {
  Estimate before, after;
  LoadedPlan loaded;
  std::map<int, double> rpm; // by line
};

Run optimize_loads(const OptimizeOptions& options) {
  const SourceFile source = make_source("load.nc", kProgram);
  const Started started(source, kStock);
  Run run;
  run.before = started.before;
  run.rpm = started.start->rpm_by_line;
  run.loaded = plan_with_load_feeds(started.start->input, options, [&](const OptimizedText& text) {
    const Estimate e =
        estimate_program(make_source("load-opt.nc", text.text), machine(), with_stock());
    return mean_spindle_loads(e, run.rpm, &text.original_line);
  });
  // The check: the written program estimated again, on its own.
  run.after =
      estimate_program(make_source("load-opt.nc", run.loaded.text.text), machine(), with_stock());
  REQUIRE(run.after.removal);
  return run;
}

OptimizeOptions load_only() {
  OptimizeOptions o;
  o.air_feeds = o.rapid_links = false;
  o.load_feeds = true;
  return o;
}

} // namespace

TEST_CASE("load feeds: the heavy slot slows to the share, the light pass speeds up by the factor") {
  const Run run = optimize_loads(load_only());
  const OptimizePlan& plan = run.loaded.plan;
  const std::string& out = run.loaded.text.text;
  CAPTURE(out);
  const std::map<int, double> before = mean_spindle_loads(run.before, run.rpm);
  const std::map<int, double> after =
      mean_spindle_loads(run.after, run.rpm, &run.loaded.text.original_line);
  REQUIRE(before.count(8));
  REQUIRE(before.count(12));
  // The setting: a slot above the share, a pass far below it.
  CHECK(before.at(8) > 0.7);
  CHECK(before.at(12) < 0.7 / 1.3);

  const BlockEdit* slot = edit_on(plan, 8);
  REQUIRE(slot);
  CHECK(slot->rule == EditRule::LoadFeed);
  CHECK(slot->was_feed_mm_min == doctest::Approx(5000));
  CHECK(slot->feed_mm_min < 5000);
  // Within the share, predicted again on the written program, and not far below it.
  CAPTURE(run.loaded.passes);
  CAPTURE(run.loaded.over_share);
  CHECK(run.loaded.over_share == 0);
  CHECK(after.at(8) <= 0.7 * 1.001);
  CHECK(after.at(8) > 0.6);
  CHECK(plan.load_lowered >= 1);

  // The light pass: raised by the factor (rounded down to whole mm/min), and its second block
  // at the same feed shares the first one's F.
  const BlockEdit* light = edit_on(plan, 12);
  REQUIRE(light);
  CHECK(light->rule == EditRule::LoadFeed);
  CHECK(light->feed_mm_min == doctest::Approx(1300));
  CHECK_FALSE(light->modal_feed);
  const BlockEdit* more = edit_on(plan, 13);
  REQUIRE(more);
  CHECK(more->feed_mm_min == doctest::Approx(1300));
  CHECK(more->modal_feed);
  CHECK(after.at(12) <= 0.7);
  CHECK(after.at(12) > before.at(12));

  // The finishing skim and the moves in air (rule a is off) keep their feeds.
  for (int line : {7, 11, 16, 17, 18, 19}) {
    CAPTURE(line);
    CHECK_FALSE(edit_on(plan, line));
  }
  CHECK(plan.finishing_passes >= 1);

  const std::vector<std::string> lines = lines_of(out);
  const std::vector<int>& original = run.loaded.text.original_line;
  auto written = [&](int source_line) {
    for (std::size_t i = 0; i < original.size(); ++i)
      if (original[i] == source_line) return lines[i];
    return std::string();
  };
  char slot_text[96];
  std::snprintf(slot_text, sizeof slot_text, "X50. F%.0f. (NCJOPT LOAD F%.0f. WAS F5000.)",
                slot->feed_mm_min, slot->feed_mm_min);
  CHECK(written(8) == slot_text);
  CHECK(written(12) == "X20. F1300. (NCJOPT LOAD F1300. WAS F1000.)");
  CHECK(written(13) == "X50. (NCJOPT LOAD F1300. WAS F1000.)"); // no F of its own
  CHECK(written(17) == "X50.");
  CHECK(written(19) == "X60. F700.");
  // The slot's original F5000 is not relied on after it (the next feed move writes its own F):
  // no restore; the skim after the light pass writes its own F too.
  CHECK(out.find("(NCJOPT RESTORE)") == std::string::npos);
  CHECK(out.find("(NCJOPT LOAD - 3 CUTTING FEEDS SCALED, 1 LOWERED, 2 RAISED,") !=
        std::string::npos);
  CHECK(out.find("WITHIN 70% OF THE SPINDLE RATING") != std::string::npos);

  // The same cuts: the same volume, and the time grows only by what the slot's lower feed costs.
  CHECK(run.after.removal->removed_mm3 ==
        doctest::Approx(run.before.removal->removed_mm3).epsilon(0.005));
}

TEST_CASE("load feeds put the original F back for a block that relies on it") {
  // The light pass's second block kept as it was by a factor of 1 (only lowering): the slot
  // lowered, and the feed move after it on the modal F gets the original back.
  const std::string program = "G21 G90 G17\n"
                              "(T1 D=12. CR=0. - FLAT END MILL)\n"
                              "T1 M6\n"
                              "S8000 M3\n"
                              "G0 X-10. Y10. Z-8.\n"
                              "G1 X20. F5000.\n" // 5: half the slot, heavy
                              "G1 Z5.\n"         // 6: retract out of the slot, at F5000
                              "G0 Z20.\n"
                              "M30\n";
  const SourceFile source = make_source("load.nc", program);
  const Started started(source, kStock);
  const Estimate& before = started.before;
  OptimizeOptions options = load_only();
  options.max_feed_factor = 1;
  const OptimizePlan plan = plan_optimization(started.start->input, options);
  const BlockEdit* slot = edit_on(plan, 5);
  REQUIRE(slot);
  CHECK(slot->feed_mm_min < 5000);
  CHECK(slot->restore_feed);
  CHECK(slot->restore_feed_mm_min == doctest::Approx(5000));
  const std::string out = write_optimized(source, before.dialect, plan).text;
  CHECK(out.find("(NCJOPT LOAD F") != std::string::npos);
  CHECK(out.find("\nF5000. (NCJOPT RESTORE)\nG1 Z5.\n") != std::string::npos);
}

TEST_CASE("a lowered feed stays at least the floor's share of the programmed one") {
  OptimizeOptions options = load_only();
  options.min_feed_factor = 0.9; // the slot would need about 0.44
  const Run run = optimize_loads(options);
  const BlockEdit* slot = edit_on(run.loaded.plan, 8);
  REQUIRE(slot);
  CHECK(slot->feed_mm_min == doctest::Approx(4500));
  CHECK(run.loaded.plan.load_floored == 1);
  // Still above the share: said, after the passes allowed.
  CHECK(run.loaded.over_share == 1);
  CHECK(run.loaded.passes == 4);
  CHECK(run.loaded.text.text.find("AT MOST 1.30 AND AT LEAST 0.90 TIMES") != std::string::npos);
}

TEST_CASE("without load feeds, cutting blocks are never changed") {
  OptimizeOptions off = load_only();
  off.load_feeds = false;
  const Run run = optimize_loads(off);
  CHECK(run.loaded.plan.edits.empty());
  CHECK(run.loaded.text.text == kProgram);
  CHECK(run.loaded.passes == 1);
}
