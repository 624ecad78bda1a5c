// The HTML report: one page, self-contained (inline CSS, inline SVG, a short inline script), that
// a planner can mail around and open offline.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "html_assets.hpp"
#include "html_measured.hpp"
#include "html_optimized.hpp"
#include "ncjoule/duration.hpp"
#include "ncjoule/report.hpp"
#include "svg_chart.hpp"

namespace ncjoule {
namespace {

using report_detail::BarRow;
using report_detail::BarSegment;
using report_detail::ChartLine;
using report_detail::ChartMarker;
using report_detail::format_number;
using report_detail::html_escaped;

// Enough points for a 1000-unit-wide chart at any zoom a screen gives; peaks survive (min/max).
constexpr std::size_t kMaxChartPoints = 2000;

std::string base_name(const std::string& path) {
  const std::string name = std::filesystem::path(path).filename().string();
  return name.empty() ? path : name;
}

std::string duration_text(double s) {
  if (s < 60) return format_number(s, 1) + " s";
  if (s >= 3.6e12) return huge_hours(s / 3600) + " h";
  return report_detail::clock_label(s) + (s >= 3600 ? " h" : " min");
}

std::string kpi(const std::string& label, const std::string& value, const std::string& extra) {
  return "<div class=\"kpi\"><div class=\"label\">" + label + "</div><div class=\"value\">" +
         value + "</div><div class=\"extra\">" + extra + "</div></div>";
}

std::string signed_text(double value, int decimals, const std::string& unit) {
  if (std::abs(value) < 0.5 * std::pow(10.0, -decimals)) return "&mdash;";
  const std::string cls = value > 0 ? "up" : "down";
  return "<span class=\"" + cls + "\">" + (value > 0 ? "+" : "") + format_number(value, decimals) +
         (unit.empty() ? "" : " " + unit) + "</span>";
}

std::vector<BarSegment> component_segments(const ComponentValues& values) {
  std::vector<BarSegment> segments;
  for (std::size_t c = 0; c < kPowerComponentCount; ++c)
    segments.push_back({std::string(component_name(PowerComponent(c))),
                        report_detail::component_color(PowerComponent(c)), values[c]});
  return segments;
}

// Volumes in the program's units: in^3 (and in^3/min, J/in^3) for an inch program, as its
// programmer reads them; mm^3 otherwise.
struct VolumeUnits {
  double per_mm3 = 1; // the unit's value of one mm^3
  int decimals = 0;
  std::string unit = "mm&sup3;", rate_unit = "mm&sup3;/s", rate_text = "mm\u00b3/s";
  double rate_per_mm3_s = 1; // the rate unit's value of one mm^3/s
};

VolumeUnits volume_units(bool inch) {
  if (!inch) return {};
  return {1 / kMm3PerIn3, 3, "in&sup3;", "in&sup3;/min", "in\u00b3/min", 60 / kMm3PerIn3};
}

// Where a price came from, in words: the profile, the command line, a user config's section.
std::string price_source(const std::string& from) {
  if (from.empty() || from == "profile") return "the machine profile's";
  return "from " + html_escaped(from);
}

std::string kpi_cards(const Estimate& e) {
  const EnergyResult& en = e.energy;
  // On a guessed stock, the figures it sets carry a "guessed" badge and their range.
  const GuessedFigures g = guessed_figures(e);
  const std::string badge = g.guessed ? " <span class=\"guessed\" title=\"on a guessed stock: "
                                        "give the stock to know it\">guessed</span>"
                                      : "";
  auto range = [&](const GuessedFigures::Range& r, double scale, int decimals,
                   const std::string& unit) {
    return "<br>guessed stock: " + format_number(r.low * scale, decimals) + " to " +
           format_number(r.high * scale, decimals) + " " + unit;
  };
  std::string html = "<div class=\"kpis\">";
  const VolumeUnits v = volume_units(e.inch);
  html += kpi("Cycle time", duration_text(e.time_s), format_number(e.time_s, 1) + " s");
  html += kpi("Electricity used" + badge, format_number(en.energy_j / 3.6e6, 4) + " kWh",
              format_number(en.energy_j / 1000, 1) + " kJ" +
                  (g.guessed ? range(g.energy_j, 1 / 3.6e6, 4, "kWh") : ""));
  html +=
      kpi("Material removed" + badge,
          format_number(en.removed_mm3 * v.per_mm3, v.decimals) + " " + v.unit,
          "energy per volume " + format_number(en.sec_j_mm3 / v.per_mm3, e.inch ? 0 : 2) + " J/" +
              v.unit + (g.guessed ? range(g.removed_mm3, v.per_mm3, v.decimals, v.unit) : ""));
  html += kpi("Power drawn" + badge, format_number(en.mean_power_w, 0) + " W",
              "on average; at most " + format_number(en.peak_power_w, 0) + " W" +
                  (g.guessed ? range(g.peak_power_w, 1, 0, "W peak") : ""));
  html += kpi("CO&#8322; emitted" + badge, format_number(en.co2_kg * 1000, 1) + " g",
              format_number(en.co2_kg, 4) + " kg");
  const std::string currency = html_escaped(en.currency);
  const double kwh = en.energy_j / 3.6e6;
  std::string how = "electricity";
  if (kwh > 0)
    how += " at " + format_number(en.electricity_cost / kwh, 3) + " " + currency + "/kWh";
  how += " (" + price_source(en.price_from) + ")";
  if (en.machine_rate_per_hour > 0)
    how += ", machine time at " + format_number(en.machine_rate_per_hour, 2) + " " + currency +
           "/h (" + price_source(en.rate_from) + ")";
  html += kpi("Cost of the run" + badge, format_number(en.cost, 4) + " " + currency, how);
  return html + "</div>";
}

std::string operations_table(const std::vector<OperationSummary>& ops, const Estimate& e) {
  const VolumeUnits v = volume_units(e.inch);
  std::string html = "<table><thead><tr><th class=\"name\">Operation</th><th>Tool</th>"
                     "<th>Line</th><th>Start</th><th>Time</th><th>Air cut</th>"
                     "<th>Removed " +
                     v.unit +
                     "</th>"
                     "<th>Energy kJ</th><th>Share</th><th>J/" +
                     v.unit + "</th></tr></thead><tbody>";
  for (const OperationSummary& op : ops) {
    const double share = e.energy.energy_j > 0 ? 100 * op.energy_j / e.energy.energy_j : 0;
    html += "<tr><td class=\"name\">" + html_escaped(op.name) + "</td><td>" +
            (op.tool > 0 ? "T" + std::to_string(op.tool) : "&mdash;") + "</td><td>" +
            (op.line >= 0 ? std::to_string(op.line + 1) : "&mdash;") + "</td><td>" +
            report_detail::clock_label(op.start_s) + "</td><td>" + duration_text(op.time_s) +
            "</td><td>" + (e.removal ? duration_text(op.time.air_cut_s) : "&mdash;") + "</td><td>" +
            format_number(op.removed_mm3 * v.per_mm3, v.decimals) + "</td><td>" +
            format_number(op.energy_j / 1000, 2) + "</td><td>" + format_number(share, 1) +
            "%</td><td>" +
            (op.removed_mm3 > 0
                 ? format_number(op.energy_j / (op.removed_mm3 * v.per_mm3), e.inch ? 0 : 2)
                 : "&mdash;") +
            "</td></tr>";
  }
  return html + "</tbody></table>";
}

std::string program_section(const ReportProgram& p, const MachineProfile& machine,
                            std::size_t index) {
  const Estimate& e = *p.estimate;
  const std::string id = "p" + std::to_string(index + 1);
  const std::vector<OperationSummary>& ops = e.operations;
  const ProgramSeries& series = e.series;
  std::vector<ChartMarker> markers;
  for (const OperationSummary& op : ops)
    if (op.line >= 0) markers.push_back({op.start_s, op.name});

  std::string html =
      "<section class=\"program\" id=\"" + id + "\"><h2>" + html_escaped(base_name(e.file)) +
      "</h2><div class=\"path\">" + html_escaped(e.file) + " &middot; " +
      html_escaped(e.removal ? e.removal->stock_description : "stock not simulated") + "</div>";
  html += kpi_cards(e);
  html += report_detail::svg_operation_timeline(id + "-timeline", ops, e.time_s);
  const std::string color = report_detail::program_color(index);
  if (p.measured) html += report_detail::measured_section(id, *p.measured, ops, color);
  html += report_detail::svg_toolpath(id + "-xy", "Toolpath from above (XY), feed moves by power",
                                      e.path, report_detail::PathView::XY, e.inch);
  html += report_detail::svg_toolpath(id + "-xz", "Toolpath from the front (XZ)", e.path,
                                      report_detail::PathView::XZ, e.inch);
  html += report_detail::svg_time_chart(
      id + "-power", "Power over time", "W",
      {{base_name(e.file), color, downsample_min_max(series.power_w, kMaxChartPoints)}}, markers,
      e.time_s);
  const VolumeUnits v = volume_units(e.inch);
  Series mrr = downsample_min_max(series.mrr_mm3_s, kMaxChartPoints);
  for (auto& value : mrr.value)
    value *= v.rate_per_mm3_s;
  html += report_detail::svg_time_chart(id + "-mrr", "Material removal rate over time", v.rate_text,
                                        {{base_name(e.file), "#e03131", mrr}}, markers, e.time_s);

  std::vector<BarRow> op_rows;
  for (const OperationSummary& op : ops)
    op_rows.push_back({op.name, component_segments(op.components_j)});
  html += report_detail::svg_bar_chart(id + "-operations", "Energy per operation, by component",
                                       "kJ", op_rows, 1000, true);
  html += operations_table(ops, e);
  if (p.source) html += report_detail::optimized_blocks_section(*p.source);

  std::vector<BarRow> component_rows;
  for (BarSegment& s : component_segments(e.energy.components_j))
    if (s.value > 0) component_rows.push_back({s.name, {s}});
  html += report_detail::svg_bar_chart(id + "-components", "Energy per component", "kJ",
                                       component_rows, 1000, false);
  std::size_t warnings = 0;
  for (const Diagnostic& d : e.diagnostics)
    warnings += d.severity != Severity::Note;
  if (warnings > 0) {
    // The first few in full (a spindle asked for more than its rating, a fitted model used
    // outside its range, a start inside the stock, ...), the rest counted.
    constexpr std::size_t kShown = 20;
    html +=
        "<p class=\"note\">" + std::to_string(warnings) + " warning(s) while estimating:</p><ul>";
    std::size_t shown = 0;
    for (const Diagnostic& d : e.diagnostics) {
      if (d.severity == Severity::Note) continue;
      if (shown++ == kShown) break;
      html += "<li class=\"note\">" + report_detail::html_escaped(format_diagnostic(d)) + "</li>";
    }
    html += "</ul>";
    if (warnings > kShown)
      html += "<p class=\"note\">and " + std::to_string(warnings - kShown) +
              " more; <code>ncjoule estimate</code> prints them all.</p>";
  }
  return html + "</section>";
}

std::string comparison_section(const std::vector<ReportProgram>& programs,
                               const MachineProfile& machine) {
  std::vector<ProgramTotals> totals;
  for (const ReportProgram& p : programs)
    totals.push_back(program_totals(*p.estimate));
  const std::vector<RankedProgram> ranked = rank_programs(totals);
  const std::string currency = ranked.empty() ? "" : html_escaped(ranked.front().totals.currency);

  std::string html = "<section id=\"comparison\"><h2>Comparison</h2><div class=\"path\">" +
                     std::to_string(programs.size()) +
                     " alternatives on the same machine, least energy first</div>";
  const bool inch = std::all_of(ranked.begin(), ranked.end(),
                                [](const RankedProgram& r) { return r.totals.inch; });
  const VolumeUnits v = volume_units(inch);
  html += "<table><thead><tr><th>#</th><th class=\"name\">Program</th><th>Time</th>"
          "<th>Energy kJ</th><th>vs best</th><th>Peak kW</th><th>Removed " +
          v.unit + "</th><th>J/" + v.unit +
          "</th>"
          "<th>CO&#8322; g</th><th>Cost " +
          currency + "</th><th>Time vs best</th></tr></thead><tbody>";
  for (const RankedProgram& r : ranked) {
    const ProgramTotals& t = r.totals;
    html += std::string("<tr") + (r.rank == 1 ? " class=\"best\"" : "") + "><td>" +
            std::to_string(r.rank) + "</td><td class=\"name\">" + html_escaped(base_name(t.file)) +
            "</td><td>" + duration_text(t.time_s) + "</td><td>" +
            format_number(t.energy_j / 1000, 2) + "</td><td>" +
            (r.rank == 1 ? std::string("best")
                         : signed_text(r.energy_diff_j / 1000, 2, "kJ") + " (" +
                               signed_text(r.energy_diff_pct, 1, "%") + ")") +
            "</td><td>" + format_number(t.peak_power_w / 1000, 2) + "</td><td>" +
            format_number(t.removed_mm3 * v.per_mm3, v.decimals) + "</td><td>" +
            format_number(t.sec_j_mm3 / v.per_mm3, inch ? 0 : 2) + "</td><td>" +
            format_number(t.co2_kg * 1000, 1) + "</td><td>" + format_number(t.cost, 4) +
            "</td><td>" +
            (r.rank == 1 || std::abs(r.time_diff_s) < 0.05
                 ? std::string(r.rank == 1 ? "&mdash;" : "same")
                 : signed_text(r.time_diff_s, 1, "s") + " (" +
                       signed_text(r.time_diff_pct, 1, "%") + ")") +
            "</td></tr>";
  }
  html += "</tbody></table>";

  // Component by component: where the difference comes from.
  html += "<h3>Energy by component (kJ), difference to the best</h3><table><thead><tr>"
          "<th class=\"name\">Component</th>";
  for (const RankedProgram& r : ranked)
    html += "<th>" + html_escaped(base_name(r.totals.file)) + "</th>";
  html += "</tr></thead><tbody>";
  for (std::size_t c = 0; c < kPowerComponentCount; ++c) {
    bool any = false;
    for (const RankedProgram& r : ranked)
      any = any || r.totals.components_j[c] != 0;
    if (!any) continue;
    html += "<tr><td class=\"name\"><span class=\"swatch\" style=\"background:" +
            report_detail::component_color(PowerComponent(c)) + "\"></span>" +
            std::string(component_name(PowerComponent(c))) + "</td>";
    for (const RankedProgram& r : ranked)
      html += "<td>" + format_number(r.totals.components_j[c] / 1000, 2) +
              (r.rank == 1 ? std::string()
                           : " (" + signed_text(r.component_diff_j[c] / 1000, 2, "") + ")") +
              "</td>";
    html += "</tr>";
  }
  html += "</tbody></table><ul class=\"why\">";
  for (const RankedProgram& r : ranked)
    if (r.rank > 1)
      html += "<li><b>" + html_escaped(base_name(r.totals.file)) + "</b> uses " +
              format_number(r.energy_diff_j / 1000, 2) + " kJ more than <b>" +
              html_escaped(base_name(ranked.front().totals.file)) +
              "</b>: " + format_number(std::abs(r.time_diff_s), 1) + " s " +
              (r.time_diff_s >= 0 ? "longer" : "shorter") +
              [&] {
                const std::string why =
                    explain_time_difference(r.totals.time, ranked.front().totals.time,
                                            r.totals.removal && ranked.front().totals.removal);
                return why.empty() ? std::string() : " (" + html_escaped(why) + ")";
              }() +
              ", at most " + format_number(r.totals.peak_power_w / 1000, 2) +
              " kW; its energy in " + html_escaped(explain_difference(r)) + ".</li>";
  html += "</ul>";

  std::vector<BarRow> rows;
  for (const RankedProgram& r : ranked)
    rows.push_back({base_name(r.totals.file), component_segments(r.totals.components_j)});
  html += report_detail::svg_bar_chart("comparison-components", "Energy per program, by component",
                                       "kJ", rows, 1000, true);

  std::vector<ChartLine> lines;
  double t_end = 0;
  for (std::size_t i = 0; i < programs.size(); ++i) {
    const Estimate& e = *programs[i].estimate;
    lines.push_back({base_name(e.file), report_detail::program_color(i),
                     downsample_min_max(e.series.power_w, kMaxChartPoints)});
    t_end = std::max(t_end, e.time_s);
  }
  html += report_detail::svg_time_chart("comparison-power", "Power over time, all programs", "W",
                                        lines, {}, t_end);
  return html + "</section>";
}

} // namespace

std::string html_report(const std::vector<ReportProgram>& programs, const MachineProfile& machine) {
  std::string names;
  for (const ReportProgram& p : programs)
    names += (names.empty() ? "" : ", ") + base_name(p.estimate->file);
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
                     "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
                     "<title>ncjoule report: " +
                     html_escaped(names) + "</title><style>" + report_detail::report_css() +
                     "</style></head><body>\n";
  const std::string model =
      programs.empty() ? std::string() : programs.front().estimate->energy.model_description;
  html += "<header class=\"top\"><span class=\"brand\">ncjoule</span><h1>Time and energy: " +
          html_escaped(names) + "</h1><div class=\"sub\">Machine: " + html_escaped(machine.name) +
          " &middot; " + html_escaped(model) + "</div></header>\n<main>\n";
  bool measured = false;
  for (const ReportProgram& p : programs)
    measured = measured || p.measured != nullptr;
  if (programs.size() > 1) html += comparison_section(programs, machine) + "\n";
  for (std::size_t i = 0; i < programs.size(); ++i)
    html += program_section(programs[i], machine, i) + "\n";
  html += "</main><footer>Predicted by ncjoule from the programs and the machine profile " +
          html_escaped(machine.source_path) +
          ". Energy is split by component (tare, coolant, spindle, each axis, cutting, tool "
          "change); charts show at most " +
          std::to_string(kMaxChartPoints) +
          " points per line, keeping each interval's lowest and highest value." +
          (measured ? " Measured: the controller's log of the runs, read as <code>ncjoule "
                      "check-log</code> reads it; the predicted line is at the overrides the run "
                      "of median time was logged at."
                    : "") +
          "</footer>\n";
  html += std::string("<script>") + report_detail::report_script() + "</script>\n</body></html>\n";
  return html;
}

} // namespace ncjoule
