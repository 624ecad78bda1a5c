// What the machine's log measured, over the prediction: the line each run had reached over time
// on the same axes as the predicted one, and the figures `ncjoule check-log` prints as tables.
// Every measured and predicted time is also in a data attribute at full precision, so that a
// reader (or a test) can take the numbers from the page without parsing the shown ones.
#include "html_measured.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "svg_chart.hpp"

namespace ncjoule::report_detail {
namespace {

// Enough points for a 1000-unit-wide chart (as the other time charts).
constexpr std::size_t kMaxPoints = 2000;
const char* const kMeasuredColor = "#e8590c";

std::string exact(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string error_cell(double predicted_s, double measured_s) {
  if (!(measured_s > 0)) return "<td>&mdash;</td>";
  const double pct = 100 * (predicted_s - measured_s) / measured_s;
  // Off by 5% or more either way is marked: too long a prediction is as wrong as too short.
  const std::string cls = std::abs(pct) < 5 ? "" : " class=\"off\"";
  return "<td" + cls + ">" + (pct > 0 ? "+" : "") + format_number(pct, 1) + "%</td>";
}

std::string range_text(const MeasuredOverlay::Figure& f) {
  if (f.runs <= 1 || std::abs(f.max_s - f.min_s) < 0.05) return "&mdash;";
  return format_number(f.min_s, 1) + "&ndash;" + format_number(f.max_s, 1);
}

// One row of measured against predicted: the data attributes carry the exact figures.
std::string figure_row(const MeasuredOverlay::Figure& f, const std::string& cells) {
  return "<tr data-measured-s=\"" + exact(f.median_s) + "\" data-measured-min-s=\"" +
         exact(f.min_s) + "\" data-measured-max-s=\"" + exact(f.max_s) + "\" data-predicted-s=\"" +
         exact(f.predicted_s) + "\">" + cells + "<td>" + format_number(f.median_s, 1) +
         "</td><td>" + range_text(f) + "</td><td>" + format_number(f.predicted_s, 1) + "</td>" +
         error_cell(f.predicted_s, f.median_s) + "</tr>";
}

std::string runs_table(const MeasuredOverlay& m) {
  std::string html = "<table class=\"runs\"><thead><tr><th>Run</th><th class=\"name\">Start</th>"
                     "<th>Time s</th><th>Ended</th><th class=\"name\">Usable</th></tr></thead>"
                     "<tbody>";
  for (std::size_t k = 0; k < m.runs.size(); ++k) {
    const MeasuredOverlay::Run& r = m.runs[k];
    html += "<tr><td>" + std::to_string(k + 1) + "</td><td class=\"name\">" +
            html_escaped(r.start) + "</td><td>" + format_number(r.time_s, 1) + "</td><td>" +
            html_escaped(r.ended) + "</td><td class=\"name\">" +
            (r.usable ? std::string("usable") : "not usable: " + html_escaped(r.why)) +
            "</td></tr>";
  }
  return html + "</tbody></table>";
}

std::string operations_table(const MeasuredOverlay& m) {
  std::string html =
      "<table class=\"measured-operations\"><thead><tr><th class=\"name\">Operation</th>"
      "<th>Tool</th><th>Line</th><th>Measured s</th><th>Range s</th><th>Predicted s</th>"
      "<th>Error</th></tr></thead><tbody>";
  for (const MeasuredOverlay::Figure& op : m.operations)
    html += figure_row(op, "<td class=\"name\">" + html_escaped(op.name) + "</td><td>" +
                               (op.tool > 0 ? "T" + std::to_string(op.tool) : "&mdash;") +
                               "</td><td>" + std::to_string(op.line) + "</td>");
  html += "</tbody><tfoot>" +
          figure_row(m.total, "<td class=\"name\">Program</td><td></td><td></td>") + "</tfoot>";
  return html + "</table>";
}

std::string worst_blocks_table(const MeasuredOverlay& m) {
  std::string html = "<table class=\"measured-blocks\"><thead><tr><th class=\"name\">Lines: "
                     "the line that takes the most</th><th>Measured s</th><th>Range s</th>"
                     "<th>Predicted s</th><th>Error</th></tr></thead><tbody>";
  for (const MeasuredOverlay::Figure& b : m.worst_blocks)
    html += figure_row(b, "<td class=\"name\"><code>" + html_escaped(b.name) + "</code></td>");
  return html + "</tbody></table>";
}

} // namespace

std::string measured_section(const std::string& id, const MeasuredOverlay& m,
                             const std::vector<OperationSummary>& operations,
                             const std::string& predicted_color) {
  std::string html = "<div class=\"measured\"><h3>Measured on the machine</h3>";
  html += "<div class=\"path\">from " + html_escaped(m.logs) + "</div>";
  if (m.runs.empty())
    return html + "<p class=\"note\">The logs hold no run of this program.</p></div>";
  html += runs_table(m);
  if (m.usable_runs == 0)
    return html + "<p class=\"note\">No run is usable (see why above): nothing to compare.</p>" +
           "</div>";
  html += "<p class=\"note\">" + std::to_string(m.usable_runs) + " usable run" +
          (m.usable_runs > 1 ? "s" : "") + ": measured " + format_number(m.total.median_s, 1) +
          " s" + (m.usable_runs > 1 ? " (median)" : "") + ", predicted " +
          format_number(m.total.predicted_s, 1) + " s at the overrides they ran at.</p>";

  std::vector<ChartLine> lines;
  double t_end = 0;
  auto add = [&](const std::string& name, const std::string& color, const Series& s, bool faint) {
    lines.push_back({name, color, downsample_min_max(s, kMaxPoints), faint});
    if (!s.t_s.empty()) t_end = std::max(t_end, s.t_s.back());
  };
  add("predicted", predicted_color, m.predicted, false);
  // The other usable runs under the median one, faint, under one name in the legend.
  for (const MeasuredOverlay::Progress& p : m.measured)
    if (!p.median) add("other usable runs", kMeasuredColor, p.lines, true);
  for (const MeasuredOverlay::Progress& p : m.measured)
    if (p.median) add(p.name, kMeasuredColor, p.lines, false);
  std::vector<ChartMarker> markers;
  for (const OperationSummary& op : operations)
    if (op.line >= 0 && operations.size() > 1) markers.push_back({op.start_s, op.name});
  html += svg_time_chart(id + "-progress", "Line reached over time, measured and predicted", "line",
                         lines, markers, t_end);
  html += "<h3>By operation, measured (median of the usable runs) against predicted</h3>";
  html += operations_table(m);
  if (!m.worst_blocks.empty()) {
    html += "<h3>Worst blocks: stretches of 0.5 s or more as the log shows them</h3>";
    html += worst_blocks_table(m);
  }
  return html + "</div>";
}

} // namespace ncjoule::report_detail
