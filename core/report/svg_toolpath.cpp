// The toolpath views (XY, XZ) and the operation timeline of the HTML report, as inline SVG.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ncjoule/duration.hpp"
#include "svg_chart.hpp"

namespace ncjoule::report_detail {
namespace {

constexpr double kWidth = 1000;
constexpr double kMargin = 12;
constexpr double kMaxHeight = 560;

// Low to high power: dark blue, blue, teal, green, yellow, orange, red.
constexpr const char* kScale[] = {"#253494", "#2c7fb8", "#41b6c4", "#7fcdbb",
                                  "#fecc5c", "#fd8d3c", "#e31a1c"};
constexpr int kSteps = sizeof kScale / sizeof kScale[0];

std::string scale_color(double value, double low, double high) {
  if (!(high > low)) return kScale[kSteps - 1];
  const int k = int(std::floor((value - low) / (high - low) * kSteps));
  return kScale[std::clamp(k, 0, kSteps - 1)];
}

std::string power_text(double w) {
  return w >= 1000 ? format_number(w / 1000, 2) + " kW" : format_number(w, 0) + " W";
}

// A removal rate as the program's programmer reads it: mm^3/s, or in^3/min in an inch program.
std::string removal_rate_text(double mm3_s, bool inch) {
  return inch ? format_number(mm3_s * 60 / kMm3PerIn3, 2) + " in\u00b3/min"
              : format_number(mm3_s, 1) + " mm\u00b3/s";
}

} // namespace

std::string svg_toolpath(const std::string& id, const std::string& title,
                         const std::vector<PathPoint>& path, PathView view, bool inch) {
  std::string html = "<figure class=\"chart toolpath\" id=\"" + id + "\"><figcaption>" +
                     html_escaped(title) + "</figcaption>";
  if (path.size() < 2) return html + "<p class=\"note\">No moves to draw.</p></figure>";
  auto horizontal = [](const PathPoint& p) { return double(p.x); };
  auto vertical = [view](const PathPoint& p) { return double(view == PathView::XY ? p.y : p.z); };
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  double low = INFINITY, high = -INFINITY;
  for (const PathPoint& p : path) {
    x0 = std::min(x0, horizontal(p)), x1 = std::max(x1, horizontal(p));
    y0 = std::min(y0, vertical(p)), y1 = std::max(y1, vertical(p));
    if (!p.rapid) low = std::min(low, double(p.power_w)), high = std::max(high, double(p.power_w));
  }
  if (!std::isfinite(low)) low = high = 0;
  // One scale for both directions, so circles stay round; the height follows the part's shape.
  const double span_x = std::max(x1 - x0, 1e-6), span_y = std::max(y1 - y0, 1e-6);
  const double scale =
      std::min((kWidth - 2 * kMargin) / span_x, (kMaxHeight - 2 * kMargin) / span_y);
  const double height = span_y * scale + 2 * kMargin;
  auto sx = [&](const PathPoint& p) { return svg_coord(kMargin + (horizontal(p) - x0) * scale); };
  auto sy = [&](const PathPoint& p) {
    return svg_coord(height - kMargin - (vertical(p) - y0) * scale);
  };

  html += "<svg class=\"toolpath-view\" viewBox=\"0 0 " + svg_coord(kWidth) + " " +
          svg_coord(height) + "\" role=\"img\" aria-label=\"" + html_escaped(title) + "\">";
  html += "<rect class=\"frame\" x=\"0\" y=\"0\" width=\"" + svg_coord(kWidth) + "\" height=\"" +
          svg_coord(height) + "\"/>";
  // One <path> per run of consecutive segments drawn alike (rapids, or feed moves in one colour
  // of the scale), with one tooltip naming the lines it covers: a path element and a tooltip
  // per sampled point made a program of a few thousand blocks several megabytes; this keeps it
  // under one. Points that land where the previous one did (at the drawing's resolution) add
  // nothing and are left out.
  for (std::size_t k = 1; k < path.size();) {
    const PathPoint& a = path[k - 1];
    const PathPoint& first = path[k];
    const std::string color = first.rapid ? "" : scale_color(first.power_w, low, high);
    std::string last_x = sx(first), last_y = sy(first);
    std::string d = "M" + sx(a) + " " + sy(a) + "L" + last_x + " " + last_y;
    int first_line = first.line, last_line = first.line;
    double power_low = first.power_w, power_high = first.power_w, mrr = first.mrr_mm3_s;
    std::size_t end = k + 1;
    for (; end < path.size(); ++end) {
      const PathPoint& b = path[end];
      if (b.rapid != first.rapid || (!b.rapid && scale_color(b.power_w, low, high) != color)) break;
      first_line = std::min(first_line, b.line);
      last_line = std::max(last_line, b.line);
      power_low = std::min(power_low, double(b.power_w));
      power_high = std::max(power_high, double(b.power_w));
      mrr = std::max(mrr, double(b.mrr_mm3_s));
      std::string x = sx(b), y = sy(b);
      if (x == last_x && y == last_y) continue;
      d += " " + x + " " + y; // further points of the L command
      last_x = std::move(x), last_y = std::move(y);
    }
    const std::string lines = first_line == last_line ? "line " + std::to_string(first_line + 1)
                                                      : "lines " + std::to_string(first_line + 1) +
                                                            "-" + std::to_string(last_line + 1);
    const std::string power =
        power_text(power_low) + (power_text(power_high) != power_text(power_low)
                                     ? " to " + power_text(power_high)
                                     : std::string());
    const std::string tip =
        lines + (first.rapid ? ": rapid" : ": feed") + ", " + power +
        (mrr > 0 ? ", MRR up to " + removal_rate_text(mrr, inch) : std::string());
    html += first.rapid ? "<path class=\"rapid\" data-line=\"" + std::to_string(first_line + 1) +
                              "\" d=\"" + d + "\"><title>" + html_escaped(tip) + "</title></path>"
                        : "<path class=\"feed\" data-line=\"" + std::to_string(first_line + 1) +
                              "\" stroke=\"" + color + "\" d=\"" + d + "\"><title>" +
                              html_escaped(tip) + "</title></path>";
    k = end;
  }
  html += "</svg><div class=\"legend scale\"><span>feed power " + power_text(low) + "</span>";
  for (const char* color : kScale)
    html += "<i style=\"background:" + std::string(color) + "\"></i>";
  html += "<span>" + power_text(high) + "</span><span class=\"rapid-key\">- - rapid</span></div>";
  return html + "</figure>";
}

std::string svg_operation_timeline(const std::string& id,
                                   const std::vector<OperationSummary>& operations,
                                   double total_s) {
  constexpr double kHeight = 56, kBarY = 8, kBarHeight = 28;
  std::string html = "<figure class=\"chart timeline\" id=\"" + id +
                     "\"><figcaption>Operations over time</figcaption>";
  html += "<svg class=\"timeline-view\" viewBox=\"0 0 " + svg_coord(kWidth) + " " +
          svg_coord(kHeight) + "\" role=\"img\" aria-label=\"Operations over time\">";
  const double end = total_s > 0 ? total_s : 1;
  for (std::size_t k = 0; k < operations.size(); ++k) {
    const OperationSummary& op = operations[k];
    const double x = kWidth * op.start_s / end;
    const double w = std::max(kWidth * op.time_s / end, 1.0);
    const std::string tip = op.name + (op.tool > 0 ? " (T" + std::to_string(op.tool) + ")" : "") +
                            ": from " + clock_label(op.start_s) + ", " + duration_words(op.time_s) +
                            ", " + format_number(op.energy_j / 1000, 2) + " kJ";
    html += "<rect class=\"op\" x=\"" + svg_coord(x) + "\" y=\"" + svg_coord(kBarY) +
            "\" width=\"" + svg_coord(w) + "\" height=\"" + svg_coord(kBarHeight) + "\" fill=\"" +
            program_color(k) + "\"><title>" + html_escaped(tip) + "</title></rect>";
    if (w > 60)
      html += "<text class=\"op-label\" x=\"" + svg_coord(x + 4) + "\" y=\"" +
              svg_coord(kBarY + kBarHeight / 2 + 4) + "\">" + html_escaped(op.name) + "</text>";
  }
  html += "<text class=\"time start\" x=\"2\" y=\"" + svg_coord(kHeight - 4) + "\">0:00</text>";
  html += "<text class=\"time end\" x=\"" + svg_coord(kWidth - 2) + "\" y=\"" +
          svg_coord(kHeight - 4) + "\">" + clock_label(total_s) + "</text>";
  return html + "</svg></figure>";
}

} // namespace ncjoule::report_detail
