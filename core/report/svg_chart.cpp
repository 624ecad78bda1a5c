// Inline SVG charts: value over time, and horizontal stacked bars.
#include "svg_chart.hpp"

#include "ncjoule/duration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace ncjoule::report_detail {
namespace {

// The drawing area of a time chart, in viewBox units.
constexpr double kWidth = 1000, kHeight = 300;
constexpr double kLeft = 70, kRight = 20, kTop = 28, kBottom = 42;

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string coord(double v) {
  return svg_coord(v);
}

// "Nice" tick spacing: 1, 2 or 5 times a power of ten, giving about `count` ticks over `range`.
double tick_step(double range, int count) {
  if (!(range > 0)) return 1;
  const double raw = range / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * power >= raw) return m * power;
  return 10 * power;
}

// Ticks for a time axis: in seconds below two minutes, else on whole minutes (1, 2, 5, 10, 15,
// 30, 60) so the clock labels come out round.
double time_tick_step(double range) {
  if (range <= 120) return tick_step(range, 8);
  for (double minutes : {1.0, 2.0, 5.0, 10.0, 15.0, 30.0, 60.0, 120.0, 240.0})
    if (range / (60 * minutes) <= 10) return 60 * minutes;
  return tick_step(range, 8);
}

std::string time_tick_label(double t, double step) {
  if (step < 60) return format_number(t, step < 1 ? 1 : 0) + " s";
  return clock_label(t);
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "0";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') out += '\\';
    if (static_cast<unsigned char>(ch) < 0x20) continue;
    out += ch;
  }
  return out + '"';
}

} // namespace

std::string svg_coord(double v) {
  return fixed(v, 1);
}

std::string html_escaped(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char ch : text) {
    switch (ch) {
    case '&':
      out += "&amp;";
      break;
    case '<':
      out += "&lt;";
      break;
    case '>':
      out += "&gt;";
      break;
    case '"':
      out += "&quot;";
      break;
    case '\'':
      out += "&#39;";
      break;
    default:
      out += ch;
    }
  }
  return out;
}

std::string format_number(double value, int decimals) {
  std::string digits = fixed(std::abs(value), decimals);
  const auto point = digits.find('.');
  std::string whole = digits.substr(0, point);
  const std::string rest = point == std::string::npos ? "" : digits.substr(point);
  std::string grouped;
  for (std::size_t i = 0; i < whole.size(); ++i) {
    if (i > 0 && (whole.size() - i) % 3 == 0) grouped += "\u2009"; // thin space
    grouped += whole[i];
  }
  const bool negative = value < 0 && std::stod(digits) != 0;
  return (negative ? "\u2212" : "") + grouped + rest;
}

std::string clock_label(double seconds) {
  const std::string text = duration_clock(seconds);
  return text.back() == 'h' ? text.substr(0, text.size() - 2) : text; // callers add the unit
}

std::string component_color(PowerComponent component) {
  switch (component) {
  case PowerComponent::Tare:
    return "#94a3b8";
  case PowerComponent::Coolant:
    return "#22b8cf";
  case PowerComponent::Spindle:
    return "#3b5bdb";
  case PowerComponent::AxisX:
    return "#f08c00";
  case PowerComponent::AxisY:
    return "#0ca678";
  case PowerComponent::AxisZ:
    return "#d6336c";
  case PowerComponent::Cutting:
    return "#e03131";
  case PowerComponent::ToolChange:
    return "#7048e8";
  }
  return "#495057";
}

std::string program_color(std::size_t index) {
  static const char* colors[] = {"#1c7ed6", "#e8590c", "#2f9e44", "#ae3ec9",
                                 "#c2255c", "#0c8599", "#5c940d", "#495057"};
  return colors[index % (sizeof colors / sizeof colors[0])];
}

std::string svg_time_chart(const std::string& id, const std::string& title, const std::string& unit,
                           const std::vector<ChartLine>& lines,
                           const std::vector<ChartMarker>& markers, double t_end_s) {
  double v_max = 0;
  for (const ChartLine& l : lines)
    for (double v : l.points.value)
      v_max = std::max(v_max, v);
  const double t_end = t_end_s > 0 ? t_end_s : 1;
  const double v_step = tick_step(v_max > 0 ? v_max : 1, 5);
  const double v_top = std::max(v_step, std::ceil(v_max * 1.05 / v_step) * v_step);
  const double plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
  auto x_of = [&](double t) { return kLeft + plot_w * std::clamp(t / t_end, 0.0, 1.0); };
  auto y_of = [&](double v) { return kTop + plot_h * (1 - std::clamp(v / v_top, 0.0, 1.0)); };

  std::string svg;
  svg += "<figure class=\"chart\" id=\"" + id + "\"><figcaption>" + html_escaped(title) +
         "</figcaption>";
  if (lines.size() > 1) {
    svg += "<div class=\"legend\">";
    std::set<std::string> named;
    for (const ChartLine& l : lines)
      if (named.insert(l.name).second)
        svg += "<span><i style=\"background:" + l.color + (l.faint ? ";opacity:.4" : "") +
               "\"></i>" + html_escaped(l.name) + "</span>";
    svg += "</div>";
  }
  // The tooltip script reads the points back from data-series.
  std::string data = "[";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const ChartLine& l = lines[i];
    data += (i ? "," : "") + std::string("{\"name\":") + json_string(l.name) +
            ",\"color\":" + json_string(l.color) + (l.faint ? ",\"faint\":true" : "") + ",\"t\":[";
    for (std::size_t k = 0; k < l.points.t_s.size(); ++k)
      data += (k ? "," : "") + json_number(l.points.t_s[k]);
    data += "],\"v\":[";
    for (std::size_t k = 0; k < l.points.value.size(); ++k)
      data += (k ? "," : "") + json_number(l.points.value[k]);
    data += "]}";
  }
  data += "]";
  svg += "<svg class=\"time-chart\" viewBox=\"0 0 " + coord(kWidth) + " " + coord(kHeight) +
         "\" preserveAspectRatio=\"xMidYMid meet\" role=\"img\" aria-label=\"" +
         html_escaped(title) + "\" data-unit=\"" + html_escaped(unit) + "\" data-t-end=\"" +
         json_number(t_end) + "\" data-v-top=\"" + json_number(v_top) + "\" data-plot=\"" +
         coord(kLeft) + "," + coord(kTop) + "," + coord(plot_w) + "," + coord(plot_h) +
         "\" data-series=\"" + html_escaped(data) + "\">";

  // Grid and axes.
  svg += "<g class=\"grid\">";
  for (double v = 0; v <= v_top + v_step * 1e-9; v += v_step) {
    const std::string y = coord(y_of(v));
    svg += "<line x1=\"" + coord(kLeft) + "\" x2=\"" + coord(kLeft + plot_w) + "\" y1=\"" + y +
           "\" y2=\"" + y + "\"/>";
    svg += "<text class=\"ylabel\" x=\"" + coord(kLeft - 8) + "\" y=\"" + y + "\">" +
           format_number(v, v_step < 1 ? (v_step < 0.1 ? 2 : 1) : 0) + "</text>";
  }
  const double t_step = time_tick_step(t_end);
  for (double t = 0; t <= t_end + t_step * 1e-9; t += t_step) {
    const std::string x = coord(x_of(t));
    svg += "<line x1=\"" + x + "\" x2=\"" + x + "\" y1=\"" + coord(kTop) + "\" y2=\"" +
           coord(kTop + plot_h) + "\"/>";
    svg += "<text class=\"xlabel\" x=\"" + x + "\" y=\"" + coord(kTop + plot_h + 18) + "\">" +
           time_tick_label(t, t_step) + "</text>";
  }
  svg += "</g>";
  svg += "<text class=\"axis-title\" x=\"" + coord(kLeft) + "\" y=\"" + coord(kTop - 10) + "\">" +
         html_escaped(unit) + "</text>";
  svg += "<text class=\"axis-title end\" x=\"" + coord(kLeft + plot_w) + "\" y=\"" +
         coord(kHeight - 4) + "\">time</text>";

  // Where operations start.
  svg += "<g class=\"markers\">";
  for (const ChartMarker& m : markers) {
    const std::string x = coord(x_of(m.t_s));
    svg += "<line x1=\"" + x + "\" x2=\"" + x + "\" y1=\"" + coord(kTop) + "\" y2=\"" +
           coord(kTop + plot_h) + "\"/><text x=\"" + coord(x_of(m.t_s) + 4) + "\" y=\"" +
           coord(kTop + 12) + "\">" + html_escaped(m.label) + "</text>";
  }
  svg += "</g>";

  // The data: an area under a single line, plain lines when several are overlaid.
  for (const ChartLine& l : lines) {
    if (l.points.t_s.empty()) continue;
    std::string path;
    for (std::size_t k = 0; k < l.points.t_s.size(); ++k)
      path +=
          (k ? " L" : "M") + coord(x_of(l.points.t_s[k])) + " " + coord(y_of(l.points.value[k]));
    if (lines.size() == 1) {
      const std::string area = path + " L" + coord(x_of(l.points.t_s.back())) + " " +
                               coord(y_of(0)) + " L" + coord(x_of(l.points.t_s.front())) + " " +
                               coord(y_of(0)) + " Z";
      svg += "<path class=\"area\" fill=\"" + l.color + "\" d=\"" + area + "\"/>";
    }
    svg += std::string("<path class=\"line") + (l.faint ? " faint" : "") + "\" stroke=\"" +
           l.color + "\" d=\"" + path + "\"><title>" + html_escaped(l.name) + "</title></path>";
  }
  svg += "<rect class=\"frame\" x=\"" + coord(kLeft) + "\" y=\"" + coord(kTop) + "\" width=\"" +
         coord(plot_w) + "\" height=\"" + coord(plot_h) + "\"/>";
  svg += "</svg></figure>";
  return svg;
}

std::string svg_bar_chart(const std::string& id, const std::string& title, const std::string& unit,
                          const std::vector<BarRow>& rows, double scale, bool legend) {
  constexpr double kRowHeight = 30, kBarHeight = 20, kLabelWidth = 260, kValueWidth = 110;
  const double height = kTop + kRowHeight * std::max<std::size_t>(rows.size(), 1) + 8;
  const double plot_w = kWidth - kLabelWidth - kValueWidth;
  double max_total = 0;
  for (const BarRow& r : rows) {
    double total = 0;
    for (const BarSegment& s : r.segments)
      total += std::max(0.0, s.value);
    max_total = std::max(max_total, total);
  }
  if (!(max_total > 0)) max_total = 1;

  std::string svg = "<figure class=\"chart\" id=\"" + id + "\"><figcaption>" + html_escaped(title) +
                    "</figcaption>";
  if (legend) {
    std::vector<const BarSegment*> seen;
    std::set<std::string> names;
    for (const BarRow& r : rows)
      for (const BarSegment& s : r.segments)
        if (s.value > 0 && names.insert(s.name).second) seen.push_back(&s);
    svg += "<div class=\"legend\">";
    for (const BarSegment* s : seen)
      svg +=
          "<span><i style=\"background:" + s->color + "\"></i>" + html_escaped(s->name) + "</span>";
    svg += "</div>";
  }
  svg += "<svg class=\"bar-chart\" viewBox=\"0 0 " + coord(kWidth) + " " + coord(height) +
         "\" role=\"img\" aria-label=\"" + html_escaped(title) + "\">";
  svg += "<text class=\"axis-title\" x=\"" + coord(kLabelWidth) + "\" y=\"" + coord(kTop - 10) +
         "\">" + html_escaped(unit) + "</text>";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const BarRow& r = rows[i];
    const double y = kTop + kRowHeight * static_cast<double>(i);
    const double bar_y = y + (kRowHeight - kBarHeight) / 2;
    svg += "<text class=\"bar-label\" x=\"" + coord(kLabelWidth - 10) + "\" y=\"" +
           coord(y + kRowHeight / 2) + "\">" + html_escaped(r.label) + "</text>";
    svg += "<rect class=\"track\" x=\"" + coord(kLabelWidth) + "\" y=\"" + coord(bar_y) +
           "\" width=\"" + coord(plot_w) + "\" height=\"" + coord(kBarHeight) + "\"/>";
    double x = kLabelWidth, total = 0;
    for (const BarSegment& s : r.segments) {
      if (!(s.value > 0)) continue;
      const double w = plot_w * s.value / max_total;
      svg += "<rect class=\"bar\" x=\"" + coord(x) + "\" y=\"" + coord(bar_y) + "\" width=\"" +
             coord(std::max(w, 0.5)) + "\" height=\"" + coord(kBarHeight) + "\" fill=\"" + s.color +
             "\"><title>" +
             html_escaped(r.label + ": " + s.name + " " + format_number(s.value / scale, 2) + " " +
                          unit) +
             "</title></rect>";
      x += w;
      total += s.value;
    }
    svg += "<text class=\"bar-value\" x=\"" + coord(x + 8) + "\" y=\"" + coord(y + kRowHeight / 2) +
           "\">" + format_number(total / scale, 2) + "</text>";
  }
  svg += "</svg></figure>";
  return svg;
}

} // namespace ncjoule::report_detail
