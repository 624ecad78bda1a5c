// ncjoule stage 6: reports. The results of an estimate as JSON (docs/json.md), CSV per block and
// a self-contained HTML page (docs/report.md); the split of a program into operations; the
// ranking of alternatives. Everything here builds strings: writing files is the caller's job.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "ncjoule/estimate.hpp"
#include "ncjoule/machine.hpp"

namespace ncjoule {

// ---------------------------------------------------------------------------------------------
// Operations: what runs from one tool change to the next.
// ---------------------------------------------------------------------------------------------

struct OperationSummary {
  // The comment a CAM post writes for the operation: the nearest comment-only line above the
  // tool change (looking up over lines that do not move the machine: M5, M9, T2, blank lines,
  // and not into the header's tool list), else the first comment on the tool-change line, else
  // the first comment-only line below it before the first move, else "T" and the tool number.
  // What runs before the first tool change is "before first tool change"; a program without
  // tool changes is one operation named "program".
  std::string name;
  int tool = 0;       // tool loaded at the start (0: none)
  int line = -1;      // 0-based line of the tool change (-1: before any tool change)
  double start_s = 0; // when it first starts
  double time_s = 0;  // over every run of it (a tool change in a subprogram called twice)
  double energy_j = 0;
  double removed_mm3 = 0;
  double co2_kg = 0; // the program's factors applied to this operation's energy
  double cost = 0;
  ComponentValues components_j{};
};

// The operations of an estimate in the order they first run. Time, energy and volume are summed
// over every command from a tool change to the next in the order the commands run, so a
// subprogram counts where it is called; the operations add up to the program's totals.
std::vector<OperationSummary> operations(const SourceFile& source, const Estimate& estimate);

// ---------------------------------------------------------------------------------------------
// JSON and CSV
// ---------------------------------------------------------------------------------------------

// The whole estimate as one JSON document; `indent` as nlohmann::json::dump (-1: one line).
// This form has no `operations` (it needs the source text for their names).
std::string estimate_json(const Estimate& estimate, const MachineProfile& machine, int indent = 1);
// The same with `operations` (docs/json.md).
std::string estimate_json(const Estimate& estimate, const SourceFile& source,
                          const MachineProfile& machine, int indent = 1);

// One CSV row per block (LineSummary), with a header row; columns in docs/report.md. Numbers are
// written in the shortest form that reads back to the same double.
std::string estimate_csv(const Estimate& estimate, const SourceFile& source);

// ---------------------------------------------------------------------------------------------
// Comparing alternatives
// ---------------------------------------------------------------------------------------------

struct ProgramTotals {
  std::string file;
  double time_s = 0;
  double energy_j = 0;
  double removed_mm3 = 0;
  double sec_j_mm3 = 0;
  double co2_kg = 0;
  double cost = 0;
  std::string currency;
  ComponentValues components_j{};
};
ProgramTotals program_totals(const Estimate& estimate);

struct RankedProgram {
  int rank = 0; // 1 = least energy
  ProgramTotals totals;
  // Differences to the best (rank 1): this minus best; percentages of the best's value (0 when
  // the best's value is 0).
  double time_diff_s = 0, time_diff_pct = 0;
  double energy_diff_j = 0, energy_diff_pct = 0;
  double cost_diff = 0, co2_diff_kg = 0;
  ComponentValues component_diff_j{};
};

// Ranks by energy, least first (ties: shorter time, then file name).
std::vector<RankedProgram> rank_programs(std::vector<ProgramTotals> programs);

// Why a program costs more (or less) than the best: the components whose energy differs most,
// largest difference first, e.g. "axis_y +30.1 kJ, axis_x -20.4 kJ, cutting +2.0 kJ". Empty for
// the best itself.
std::string explain_difference(const RankedProgram& ranked, std::size_t max_components = 3);

// The comparison as JSON (docs/report.md).
std::string comparison_json(const std::vector<RankedProgram>& ranked, const MachineProfile& machine,
                            int indent = 1);

// ---------------------------------------------------------------------------------------------
// Time series and the HTML report
// ---------------------------------------------------------------------------------------------

struct Series {
  std::vector<double> t_s;
  std::vector<double> value;
};

// Machine power (W) and material removal rate (mm^3/s) over time, from the operating trace:
// two points per trace segment (its start and its end), so steps stay steps.
struct ProgramSeries {
  Series power_w;
  Series mrr_mm3_s;
};
ProgramSeries program_series(const Estimate& estimate, const MachineProfile& machine);

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
