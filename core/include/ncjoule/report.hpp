// ncjoule stage 6: reports. The results of an estimate as JSON (docs/json.md), CSV per block and
// a self-contained HTML page (docs/report.md), and the ranking of alternatives. JSON and CSV are
// written to a stream as they are made, block by block (a million-block program needs no
// document in memory); the HTML page is a string.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/estimate.hpp"
#include "ncjoule/machine.hpp"

namespace ncjoule {

// ---------------------------------------------------------------------------------------------
// JSON and CSV
// ---------------------------------------------------------------------------------------------

// The whole estimate as one JSON document (docs/json.md), written to `out` as it is made;
// `indent` spaces per level (0: one line).
void write_estimate_json(std::ostream& out, const Estimate& estimate, const MachineProfile& machine,
                         int indent = 1);
std::string estimate_json(const Estimate& estimate, const MachineProfile& machine, int indent = 1);
// The same document made for large programs (docs/json.md, "Compact form"): no indentation, and
// "blocks" as {"columns": [names], "rows": [[values], ...]} with each row on a line of its own,
// the numbers the same as write_estimate_json's, byte for byte.
void write_estimate_json_compact(std::ostream& out, const Estimate& estimate,
                                 const MachineProfile& machine);

// One CSV row per block (LineSummary), with a header row; columns in docs/report.md. Numbers are
// written in the shortest form that reads back to the same value.
void write_estimate_csv(std::ostream& out, const Estimate& estimate);
std::string estimate_csv(const Estimate& estimate);

// ---------------------------------------------------------------------------------------------
// Comparing alternatives
// ---------------------------------------------------------------------------------------------

// One operation of a program, as compare matches it with the same-named one of another.
struct OperationTotals {
  std::string name;
  double time_s = 0;
  double energy_j = 0;
  double cost = 0;
  TimeSplit time; // what its time is spent on
};

struct ProgramTotals {
  std::string file;
  double time_s = 0;
  double energy_j = 0;
  double removed_mm3 = 0;
  double sec_j_mm3 = 0;
  double co2_kg = 0;
  double cost = 0;         // electricity plus machine time (EnergyResult::cost)
  double machine_cost = 0; // the machine-hour rate's part of it
  std::string currency;
  ComponentValues components_j{};
  std::vector<OperationTotals> operations;
  double air_cut_s = 0;       // feed moves that remove nothing
  bool volumes_known = false; // removal simulated with every tool described
  std::size_t setups = 1;     // clampings of the part (Estimate::setups)
  bool stock_guessed = false; // a setup's stock is the box of its own cuts, not one given
  GuessedFigures guess;       // the range of the figures that guess sets
  double peak_power_w = 0;
  bool inch = false;    // the program is in inches (Estimate::inch)
  TimeSplit time;       // what the time is spent on (Estimate::time)
  bool removal = false; // removal simulated: cutting and air cutting told apart
};
ProgramTotals program_totals(const Estimate& estimate);

// What alternatives are ranked by: the least energy, the shortest time or the lowest cost
// (electricity plus machine time) first.
enum class RankBy : std::uint8_t { Energy, Time, Cost };
std::optional<RankBy> parse_rank_by(std::string_view text); // "energy", "time", "cost"
std::string_view rank_by_name(RankBy by);

struct RankedProgram {
  int rank = 0; // 1 = best by the ranking's measure
  ProgramTotals totals;
  // Differences to the best (rank 1): this minus best; percentages of the best's value (0 when
  // the best's value is 0).
  double time_diff_s = 0, time_diff_pct = 0;
  double energy_diff_j = 0, energy_diff_pct = 0;
  double cost_diff = 0, co2_diff_kg = 0;
  ComponentValues component_diff_j{};
};

// Ranks by `by`, least first (ties: the other of energy and time, then file name).
std::vector<RankedProgram> rank_programs(std::vector<ProgramTotals> programs,
                                         RankBy by = RankBy::Energy);

// Why a program costs more (or less) than the best: the components whose energy differs most,
// largest difference first, e.g. "axis_y +30.1 kJ, axis_x -20.4 kJ, cutting +2.0 kJ". Empty for
// the best itself.
std::string explain_difference(const RankedProgram& ranked, std::size_t max_components = 3);
// The same by operation: the operations (matched with the best's by name) whose time, energy
// or cost (by `by`) differs most, each with the cause in time where its time differs, e.g.
// "2D Adaptive1 +54.8 kJ (cutting +25.0 s, air cutting +5.0 s), Drill1 (only here) +12.3 kJ".
// Empty for the best itself.
std::string explain_by_operation(const RankedProgram& ranked, const RankedProgram& best, RankBy by,
                                 std::size_t max_operations = 3);

// A difference in time by what it is spent on, largest first, e.g. "cutting +25.0 s, air
// cutting +5.0 s" (`here` minus `best`; parts under 0.05 s left out; feed moves as one part
// when removal told cutting from air cutting in neither). Empty when nothing differs.
std::string explain_time_difference(const TimeSplit& here, const TimeSplit& best, bool removal,
                                    std::size_t max_parts = 3);

// The comparison as JSON (docs/report.md).
// What makes a ranking doubtful: alternatives that remove different volumes (not the same part,
// or not the same stock), or whose volumes are not known. Empty when there is nothing to say.
std::vector<std::string> comparison_warnings(const std::vector<RankedProgram>& ranked);

std::string comparison_json(const std::vector<RankedProgram>& ranked, const MachineProfile& machine,
                            int indent = 1, RankBy by = RankBy::Energy);

// ---------------------------------------------------------------------------------------------
// Time series and the HTML report
// ---------------------------------------------------------------------------------------------

// At most `max_points` points (at least 4): the time range is cut into max_points / 2 equal
// buckets and each keeps its lowest and highest point, in time order, so peaks and dips survive.
// Series that are already short enough come back unchanged.
Series downsample_min_max(const Series& series, std::size_t max_points);

// What a machine's controller log measured for a program (ncjoule report --log), set over the
// prediction: the figures `ncjoule check-log` prints, and the line each run had reached over time.
// Times in s from the run's start (the cycle start).
struct MeasuredOverlay {
  struct Figure { // one row of measured against predicted
    std::string name;
    int tool = 0;                              // operations: the tool (0: none)
    int line = 0;                              // 1-based line where it starts
    double median_s = 0, min_s = 0, max_s = 0; // over the usable runs
    std::size_t runs = 0;
    double predicted_s = 0; // at the overrides the runs were logged at
  };
  struct Run {         // one run of the program the logs hold
    std::string start; // when it started, as the log stamps it
    double time_s = 0;
    std::string ended;
    bool usable = false;
    std::string why; // why not usable
  };
  struct Progress { // the line a run had reached over time
    std::string name;
    Series lines;
    bool median = false; // the usable run of median time: drawn over the others
  };
  std::size_t usable_runs = 0;
  Figure total;                   // the whole program
  std::vector<Figure> operations; // as `ncjoule check-log` prints them
  std::vector<Figure> worst_blocks;
  std::vector<Run> runs;
  Series predicted;               // the line reached over time as predicted for the median run
  std::vector<Progress> measured; // the usable runs, the median one first
  std::string logs;               // the log files read, for the caption
};

struct ReportProgram {
  const SourceFile* source = nullptr;
  const Estimate* estimate = nullptr;
  const MeasuredOverlay* measured = nullptr; // when a log was given
};

// One self-contained HTML page (inline CSS, inline SVG charts, a few lines of inline script for
// tooltips; no external URL): totals, power and MRR over time, energy per operation and per
// component, and the comparison when there are several programs; with a program's `measured`,
// the line reached over time as measured over the predicted one, and the measured-against-
// predicted tables.
std::string html_report(const std::vector<ReportProgram>& programs, const MachineProfile& machine);

} // namespace ncjoule
