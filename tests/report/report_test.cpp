// Reports without the pipeline: downsampling keeps extremes, ranking and its differences, the
// reasons a program costs more.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "ncjoule/report.hpp"

using namespace ncjoule;

TEST_CASE("downsampling keeps every bucket's lowest and highest point and the point budget") {
  Series s;
  for (int i = 0; i < 100000; ++i) {
    s.t_s.push_back(i * 0.01);
    s.value.push_back(std::sin(i * 0.001) * 100);
  }
  s.value[54321] = 5000;  // a spike one sample wide
  s.value[77777] = -5000; // and a dip
  const Series d = downsample_min_max(s, 2000);
  CHECK(d.t_s.size() <= 2000);
  CHECK(d.t_s.size() >= 1000);
  CHECK(*std::max_element(d.value.begin(), d.value.end()) == 5000);
  CHECK(*std::min_element(d.value.begin(), d.value.end()) == -5000);
  CHECK(std::is_sorted(d.t_s.begin(), d.t_s.end()));
  // Every kept point is a point of the input.
  for (std::size_t i = 0; i < d.t_s.size(); i += 97) {
    const auto k = static_cast<std::size_t>(std::lround(d.t_s[i] / 0.01));
    CHECK(s.value[k] == d.value[i]);
  }
  const Series short_series{{0, 1, 2}, {5, 6, 7}};
  CHECK(downsample_min_max(short_series, 2000).value == short_series.value);
}

TEST_CASE("programs rank by energy and carry their differences to the best") {
  ProgramTotals a, b, c;
  a.file = "a.ngc";
  a.energy_j = 2000;
  a.time_s = 100;
  a.components_j[static_cast<std::size_t>(PowerComponent::AxisY)] = 1500;
  a.components_j[static_cast<std::size_t>(PowerComponent::Tare)] = 500;
  b.file = "b.ngc";
  b.energy_j = 1600;
  b.time_s = 110;
  b.components_j[static_cast<std::size_t>(PowerComponent::AxisX)] = 1100;
  b.components_j[static_cast<std::size_t>(PowerComponent::Tare)] = 500;
  c = b;
  c.file = "c.ngc";
  c.time_s = 90; // same energy as b, quicker: ranks before it
  const auto ranked = rank_programs({a, b, c});
  REQUIRE(ranked.size() == 3);
  CHECK(ranked[0].totals.file == "c.ngc");
  CHECK(ranked[1].totals.file == "b.ngc");
  CHECK(ranked[2].totals.file == "a.ngc");
  CHECK(ranked[2].rank == 3);
  CHECK(ranked[2].energy_diff_j == doctest::Approx(400));
  CHECK(ranked[2].energy_diff_pct == doctest::Approx(25));
  CHECK(ranked[2].time_diff_s == doctest::Approx(10));
  CHECK(ranked[1].energy_diff_j == 0);
  CHECK(explain_difference(ranked[0]).empty());
  // a - c: axis_y +1500 J, axis_x -1100 J; tare equal so not named.
  CHECK(explain_difference(ranked[2]) == "axis_y +1.5 kJ, axis_x -1.1 kJ");
}

TEST_CASE("a difference is told in time: what the time is spent on, program and operation") {
  ProgramTotals fast, slow;
  fast.file = "fast.ngc";
  fast.removal = slow.removal = true;
  fast.time.feed_s = 100;
  fast.time.air_cut_s = 20;
  fast.time.rapid_s = 10;
  fast.energy_j = 50e3;
  slow = fast;
  slow.file = "slow.ngc";
  slow.time.feed_s = 130; // 25 s more cutting, 5 s more air
  slow.time.air_cut_s = 25;
  slow.time.tool_change_s = 0.02; // under 0.05 s: not named
  slow.energy_j = 104.8e3;
  fast.time_s = fast.time.total_s();
  slow.time_s = slow.time.total_s();
  OperationTotals pocket{"Pocket", 0, 0, 0, {}};
  pocket.time = fast.time;
  pocket.energy_j = fast.energy_j;
  fast.operations = {pocket};
  pocket.time = slow.time;
  pocket.energy_j = slow.energy_j;
  slow.operations = {pocket};
  const auto ranked = rank_programs({slow, fast});
  REQUIRE(ranked[1].totals.file == "slow.ngc");
  CHECK(explain_time_difference(ranked[1].totals.time, ranked[0].totals.time, true) ==
        "cutting +25.0 s, air cutting +5.0 s");
  CHECK(explain_time_difference(ranked[0].totals.time, ranked[0].totals.time, true).empty());
  // Without removal, cutting and air cutting are one part.
  CHECK(explain_time_difference(ranked[1].totals.time, ranked[0].totals.time, false) ==
        "feed moves +30.0 s");
  CHECK(explain_by_operation(ranked[1], ranked[0], RankBy::Energy) ==
        "Pocket +54.8 kJ (cutting +25.0 s, air cutting +5.0 s)");
}

TEST_CASE("the measured runs are drawn over the predicted line, the median run on top") {
  Estimate e;
  e.file = "part.nc";
  e.time_s = 100;
  MeasuredOverlay m;
  m.logs = "mill.shdr";
  m.usable_runs = 3;
  m.total = {"part.nc", 0, 0, 104, 101, 110, 3, 100};
  m.operations = {{"Face <1>", 1, 3, 104, 101, 110, 3, 100}};
  m.runs = {{"2024-05-02 08:00:00 UTC", 101, "PROGRAM_COMPLETED", true, ""},
            {"2024-05-02 09:00:00 UTC", 104, "PROGRAM_COMPLETED", true, ""},
            {"2024-05-02 10:00:00 UTC", 110, "PROGRAM_COMPLETED", true, ""},
            {"2024-05-02 11:00:00 UTC", 30, "STOPPED", false, "held <FEED_HOLD>"}};
  m.predicted = Series{{0, 50, 100}, {1, 10, 20}};
  m.measured = {{"measured, run 2 (median)", Series{{0, 60, 104}, {1, 10, 20}}, true},
                {"run 1", Series{{0, 55, 101}, {1, 10, 20}}, false},
                {"run 3", Series{{0, 70, 110}, {1, 10, 20}}, false}};
  MachineProfile machine;
  const std::string html = html_report({{nullptr, &e, &m}}, machine);
  const std::size_t chart = html.find("id=\"p1-progress\"");
  REQUIRE(chart != std::string::npos);
  const std::string figure = html.substr(chart, html.find("</figure>", chart) - chart);
  // The two other runs faint and under the median one, which is drawn last.
  std::size_t faint = 0;
  for (std::size_t at = figure.find("class=\"line faint\""); at != std::string::npos;
       at = figure.find("class=\"line faint\"", at + 1))
    ++faint;
  CHECK(faint == 2);
  CHECK(figure.rfind("class=\"line faint\"") < figure.rfind("class=\"line\""));
  // One legend entry for the faint runs; the axis runs to the longest run.
  const std::string legend = figure.substr(0, figure.find("<svg"));
  CHECK(legend.find("other usable runs") == legend.rfind("other usable runs"));
  CHECK(figure.find("data-t-end=\"110\"") != std::string::npos);
  // The tables: names and reasons escaped, the error of the program marked (+-5% or more).
  CHECK(html.find("Face &lt;1&gt;") != std::string::npos);
  CHECK(html.find("not usable: held &lt;FEED_HOLD&gt;") != std::string::npos);
  CHECK(html.find("data-measured-s=\"104\"") != std::string::npos);
  CHECK(html.find("<td class=\"off\">\u22123.8%</td>") == std::string::npos);
  CHECK(html.find("<td>\u22123.8%</td>") != std::string::npos);
}
