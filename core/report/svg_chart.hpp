// Internal: charts as inline SVG for the HTML report. Every chart is a <figure> holding its title
// and an <svg> with a fixed viewBox that scales to the page's width.
#pragma once

#include <string>
#include <vector>

#include "ncjoule/report.hpp"

namespace ncjoule::report_detail {

std::string html_escaped(const std::string& text);
// A number with `decimals` decimals and thin-space thousands separators, for tables and labels.
std::string format_number(double value, int decimals);
// 75 -> "1:15", 3725 -> "1:02:05" (minutes:seconds, hours when needed).
std::string clock_label(double seconds);

struct ChartLine {
  std::string name;
  std::string color;
  Series points;      // already downsampled
  bool faint = false; // drawn light, under the others, and left out of the tooltip
};

struct ChartMarker { // a vertical line at a time, e.g. where an operation starts
  double t_s = 0;
  std::string label;
};

// A value-over-time chart; `unit` labels the y axis. The points go into the SVG's path and, for
// the tooltip script, into a data-series attribute as JSON. Lines of the same name share one
// entry in the legend.
std::string svg_time_chart(const std::string& id, const std::string& title, const std::string& unit,
                           const std::vector<ChartLine>& lines,
                           const std::vector<ChartMarker>& markers, double t_end_s);

struct BarSegment {
  std::string name;
  std::string color;
  double value = 0;
};
struct BarRow {
  std::string label;
  std::vector<BarSegment> segments; // stacked left to right
};

// Horizontal stacked bars, one row per entry, with the row's total at the end of its bar and a
// legend of the segment names that occur. Values are divided by `scale` for the labels
// (1000: J shown as kJ).
std::string svg_bar_chart(const std::string& id, const std::string& title, const std::string& unit,
                          const std::vector<BarRow>& rows, double scale, bool legend);

// A coordinate for an SVG attribute, with one decimal (finer than a pixel at any likely width).
std::string svg_coord(double v);

// The toolpath seen from above (XY) or from the front (XZ): feed moves coloured by their power,
// rapids as thin dashed lines, a colour scale under it. Every segment carries a tooltip with its
// source line, power and removal rate (hover, or tap on a touch screen), the rate in the
// program's units (in^3/min for an inch program).
enum class PathView { XY, XZ };
std::string svg_toolpath(const std::string& id, const std::string& title,
                         const std::vector<PathPoint>& path, PathView view, bool inch = false);

// The operations as a timeline: one bar per operation from its start, as long as its time, with
// a tooltip of its name, tool, time and energy.
std::string svg_operation_timeline(const std::string& id,
                                   const std::vector<OperationSummary>& operations, double total_s);

// Colour of an energy component, fixed so that every chart and table agrees.
std::string component_color(PowerComponent component);
// Colour of the i-th program in a comparison.
std::string program_color(std::size_t index);

} // namespace ncjoule::report_detail
