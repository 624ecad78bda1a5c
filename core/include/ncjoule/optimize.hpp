// ncjoule: a faster program from a posted one, never touching what cuts (docs/optimize.md).
//
// The program's moves are replayed in order on a fresh dexel model of a known stock. Before each
// feed move removes anything, the space it sweeps, inflated by the tool's radius plus a margin,
// is asked whether it holds material; a move that is clear of it by that margin is changed by
// one of the rules below, each its own switch:
//  - air feeds: a clear feed move runs at the air feed (the profile's air_feed, else the
//    machine's highest feed), capped along the move by each axis's max_feed;
//  - rapid links: a clear feed move that does not descend (a retract, a link at one height)
//    becomes G0 where the rapid's own path (the dog-leg shape the planner gives the machine's
//    rapids, sampled) is clear by the margin as well. A move that descends is never a rapid;
//  - load feeds (off by default): a simple cutting block's feed is scaled so that its predicted
//    cutting power at the spindle stays within a share of the spindle's rating: lowered where the
//    original passes it, raised where it stays below, never above the programmed feed times a
//    factor or an axis's max_feed, never on a finishing pass (a cut shallower or narrower than a
//    set depth), never on a block that removes nothing.
// Only simple blocks change (G0/G1, X, Y, Z, F and N words, in the main program, run once, at a
// feed per minute); everything else is copied byte for byte. What the changes leave different in
// the modal state (a raised F, G0 in place of G1) is put back in a block of its own right after
// the changed block, where a later block relies on it (a G1 goes on the block that relies on it
// where that block is simple).
//
// The clearance of a clear move holds all along it: the tool reaches any material only after a
// margin of travel in the next (unchanged) move, so the last margin before every cut entry runs
// at the original feed, and no tool enters material differently.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "ncjoule/gcode.hpp"
#include "ncjoule/machine.hpp"
#include "ncjoule/removal.hpp"
#include "ncjoule/tool.hpp"

namespace ncjoule {

struct OptimizeOptions {
  bool air_feeds = true;   // rule a: clear feed moves at the air feed
  bool rapid_links = true; // rule b: clear retracts and links as G0
  // The clearance beyond the tool's radius (mm), and below its lowest tip Z; raised to two grid
  // cells where the grid is coarser.
  double margin_mm = 1.0;
  // The air feed (mm/min); 0: the machine's (Kinematics::air_feed_mm_s, else its highest
  // max_feed). Always capped by each axis's max_feed along the move.
  double air_feed_mm_min = 0;
  // Rule c, feeds to a load target: off by default.
  bool load_feeds = false;
  double load_share = 0.7;      // of the spindle's rating at the block's speed
  double max_feed_factor = 1.3; // a raised feed stays at most this times the programmed one
  // A lowered feed stays at least this times the programmed one: a cut that would need less is
  // one whose feeds and speeds are wrong (the estimate warns of it), and a block whose predicted
  // load does not follow its feed (a short block the accelerations hold below its feed, a load
  // the grid's columns make uneven) is not chased down to nothing.
  double min_feed_factor = 0.25;
  // A cut shallower than this (its depth below the material's top), or narrower (its removed
  // volume per length over its depth), is a finishing pass: its feed never changes (mm).
  double finish_depth_mm = 0.5;
};

enum class EditRule : std::uint8_t {
  AirFeed,   // F raised
  RapidLink, // G1 turned into G0
  RestoreG1, // a block that moved on the modal G1 after a changed block writes G1 itself
  LoadFeed,  // F scaled to the load target (rule c)
};
const char* edit_rule_name(EditRule rule); // "air", "rapid", "restore", "load"
// The rules that change a block's F.
inline bool changes_feed(EditRule rule) {
  return rule == EditRule::AirFeed || rule == EditRule::LoadFeed;
}

// One changed block.
struct BlockEdit {
  int line = 0; // 0-based source line
  EditRule rule = EditRule::AirFeed;
  double feed_mm_min = 0;       // AirFeed, LoadFeed: the new feed
  double was_feed_mm_min = 0;   // the feed the move ran at (mm/min)
  bool has_f_word = false;      // the block writes its own F
  bool has_motion_word = false; // the block writes its own G1
  // A block of its own right after this one puts back what a later block relies on: the
  // original F (restore_feed_mm_min) and/or G1.
  bool restore_feed = false;
  double restore_feed_mm_min = 0;
  bool restore_g1 = false;
  // AirFeed, LoadFeed: the block moved on the modal G1 that an earlier change turned G0: it
  // writes G1.
  bool insert_g1 = false;
  // LoadFeed: the block right before (in the order moves run) set the same feed, so this one
  // writes no F of its own, only its mark.
  bool modal_feed = false;
};

// A block's predicted spindle load (its highest cutting power at the spindle over the rating at
// its speed) when it runs at `feed_mm_min` (0: the programmed feed).
// The load goes as the feed to `exponent` near it (1: proportional; less where k_c falls as the
// chip thickens).
struct LoadAt {
  double load = 0;
  double feed_mm_min = 0;
  double exponent = 1;
};

struct OptimizePlan {
  std::vector<BlockEdit> edits;       // by line, rising
  double margin_mm = 0;               // as used (after the grid's floor)
  double air_feed_mm_min = 0;         // before each move's axis caps
  std::size_t feed_moves = 0;         // feed moves replayed
  std::size_t clear_moves = 0;        // of them, clear of the stock by the margin
  std::size_t simple_clear_moves = 0; // of those, in blocks that may change
  // Changes left out because the marked block would pass the dialect's line length.
  std::size_t too_long = 0;
  bool inch = false; // the program writes inches (its feeds in in/min)
  // Rule c, as used, and what it found.
  double load_share = 0, max_feed_factor = 0, min_feed_factor = 0, finish_depth_mm = 0;
  std::size_t load_lowered = 0, load_raised = 0;
  std::size_t load_floored = 0;     // of the lowered, held at min_feed_factor
  std::size_t finishing_passes = 0; // cutting blocks left as they are as finishing passes
};

// What the plan is made from.
struct OptimizeInput {
  const SourceFile* source = nullptr;
  Dialect dialect;
  // The program's commands as removal reads them (EstimateOptions::keep_commands), in order.
  const std::vector<CanonCommand>* commands = nullptr;
  const std::map<int, Tool>* tools = nullptr; // by the number moves carry
  const StockShape* stock = nullptr;          // the known stock, program coordinates (mm)
  GridFrame grid;                             // the grid it is modelled on
  Kinematics kinematics;                      // max feeds, rapid shape and rates
  // Rule c: each line's predicted spindle load (from the estimate's LineSummary::spindle_load);
  // a line not in it is not scaled.
  const std::map<int, LoadAt>* loads = nullptr;
};

// The changes, by source line. Throws std::invalid_argument when the input is incomplete.
OptimizePlan plan_optimization(const OptimizeInput& input, const OptimizeOptions& options = {});

// The program with the plan applied: every line not changed copied byte for byte; each changed
// block carries a mark comment in the dialect's comment syntax ("(NCJOPT AIR F5000. WAS F500.)",
// "(NCJOPT RAPID WAS G1)"), the restore blocks one of their own ("(NCJOPT RESTORE)"), and a
// header after the program's leading lines lists the changes and their rules. Numbers are in the
// program's units (plan.inch: in/min), always with a decimal point. ncjoule strip leaves the marks.
struct OptimizedText {
  std::string text;
  std::size_t changed_blocks = 0;
  std::size_t restore_blocks = 0;
  // For each line of `text`, the 0-based line of the original it is (-1: a header or restore
  // line optimize added).
  std::vector<int> original_line;
};
OptimizedText write_optimized(const SourceFile& source, const Dialect& dialect,
                              const OptimizePlan& plan);

struct Estimate;

// Each line's predicted spindle load in `estimate`, as rule c reads it: its cutting power at the
// spindle, averaged over the line's time (cutting energy times the cutting efficiency over its
// time), over the rating at its speed (`rpm_by_line`, the speed its moves ran at). The mean, not
// LineSummary::spindle_load, the peak: the peak of a step's removal rate on the grid jumps where
// the tool crosses a column's edge, and does not follow the feed. Keyed by the original's lines
// through `original_line` where given (OptimizedText::original_line); lines that cut nothing
// are left out.
std::map<int, double> mean_spindle_loads(const Estimate& estimate,
                                         const std::map<int, double>& rpm_by_line,
                                         const std::vector<int>* original_line = nullptr);
// The spindle speed each line's moves ran at (the last move's, rpm; 0: spindle off).
std::map<int, double> spindle_rpm_by_line(const std::vector<CanonCommand>& commands);

// What a plan starts from, made from a program's estimate on its known stock (`before`, with its
// removal) and the commands that estimate kept (EstimateOptions::keep_commands): the model of
// the stock box, each line's spindle speed and its load at the programmed feed (rule c), and
// the input, pointing to them and to `source`, `commands` and `before`'s tools, which must
// outlive it. Held by pointer, since the input points into it.
struct OptimizeStart {
  std::unique_ptr<StockShape> stock;
  std::map<int, double> rpm_by_line;
  std::map<int, LoadAt> loads;
  OptimizeInput input;
};
std::unique_ptr<OptimizeStart> optimize_start(const SourceFile& source, const Estimate& before,
                                              const std::vector<CanonCommand>& commands,
                                              const Kinematics& kinematics);

// Rule c with the prediction in the loop: the plan from `loads` (each line's predicted load at
// its programmed feed), written, and the written text's loads asked of `loads_of` (by the
// original's lines, through OptimizedText::original_line); a scaled block still above the share
// (the cutting term need not be proportional to the feed: Kienzle's k_c(h) falls as the chip
// thickens) is scaled again from the load it had, with the exponent its last two loads show, up
// to `passes` times in all. Without
// options.load_feeds: plan_optimization and write_optimized once.
struct LoadedPlan {
  OptimizePlan plan;
  OptimizedText text;
  int passes = 0;
  std::size_t over_share = 0; // scaled blocks still above the share after the last pass
};
using LoadsOf = std::function<std::map<int, double>(const OptimizedText&)>;
LoadedPlan plan_with_load_feeds(OptimizeInput input, const OptimizeOptions& options,
                                const LoadsOf& loads_of, int passes = 4);

// The mark every line optimize writes carries ("NCJOPT"): distinct from annotate's "NCJ ..."
// comments, which strip removes.
inline constexpr const char* kOptimizeMark = "NCJOPT";

} // namespace ncjoule
