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
  bool inch = false;          // the program is in inches (Estimate::inch)
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
// or cost (by `by`) differs most, e.g. "2D Adaptive1 +41.0 s, Drill1 only here +12.3 s".
// Empty for the best itself.
std::string explain_by_operation(const RankedProgram& ranked, const RankedProgram& best, RankBy by,
                                 std::size_t max_operations = 3);

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

struct ReportProgram {
  const SourceFile* source = nullptr;
  const Estimate* estimate = nullptr;
};

// One self-contained HTML page (inline CSS, inline SVG charts, a few lines of inline script for
// tooltips; no external URL): totals, power and MRR over time, energy per operation and per
// component, and the comparison when there are several programs.
std::string html_report(const std::vector<ReportProgram>& programs, const MachineProfile& machine);

} // namespace ncjoule
