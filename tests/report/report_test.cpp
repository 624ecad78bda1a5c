// Reports without the pipeline: downsampling keeps extremes, ranking and its differences, the
// reasons a program costs more, operations named after the CAM post's comments, CSV quoting.
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

namespace {

// An estimate by hand: two tool changes and a move each, with energies and volumes.
Estimate two_operations(const SourceFile& source) {
  Estimate e;
  e.dialect = *find_dialect("linuxcnc");
  auto add = [&](CanonKind kind, int line, double value, double start, double duration,
                 double energy, double removed) {
    CanonCommand c;
    c.kind = kind;
    c.line = line;
    c.value = value;
    e.toolpath.commands.push_back(c);
    TimedCommand t;
    t.command = e.toolpath.commands.size() - 1;
    t.line = line;
    t.kind = kind;
    t.start_s = start;
    t.duration_s = duration;
    e.timeline.commands.push_back(t);
    CommandEnergy ce;
    ce.energy_j = energy;
    ce.components_j[static_cast<std::size_t>(PowerComponent::Tare)] = energy;
    e.energy.commands.push_back(ce);
    if (!e.removal) e.removal.emplace();
    CommandRemoval r;
    r.removed_mm3 = removed;
    e.removal->commands.push_back(r);
    e.energy.energy_j += energy;
    e.timeline.total_s = start + duration;
  };
  add(CanonKind::Feed, 0, 0, 0, 1, 10, 0); // before the first tool change
  add(CanonKind::ChangeTool, 3, 1, 1, 5, 50, 0);
  add(CanonKind::Feed, 4, 0, 6, 10, 100, 600);
  add(CanonKind::ChangeTool, 7, 2, 16, 5, 50, 0);
  add(CanonKind::Feed, 8, 0, 21, 4, 40, 80);
  e.energy.co2_kg = 0.025;
  LineSummary moving;
  moving.has_move = true;
  moving.line = 4;
  e.lines.push_back(moving);
  (void)source;
  return e;
}

} // namespace

TEST_CASE("operations start at tool changes and take the CAM post's comment as their name") {
  const SourceFile source = make_source("ops.ngc", "G1 X1 F100\n"
                                                   "(Face1)\n"
                                                   "M5 (spindle off)\n"
                                                   "T1 M6\n"
                                                   "G1 X2\n"
                                                   "(not a name: a move lies between)\n"
                                                   "M9\n"
                                                   "T2 M6 (Drill 4 holes)\n"
                                                   "G1 X3\n");
  const Estimate e = two_operations(source);
  const auto ops = operations(source, e);
  REQUIRE(ops.size() == 3);
  CHECK(ops[0].name == "before first tool change");
  CHECK(ops[0].energy_j == 10);
  CHECK(ops[1].name == "Face1");
  CHECK(ops[1].tool == 1);
  CHECK(ops[1].line == 3);
  CHECK(ops[1].time_s == 15);
  CHECK(ops[1].energy_j == 150);
  CHECK(ops[1].removed_mm3 == 600);
  // The nearest comment-only line above T2 is "(not a name ...)"; it names it since M9 does not
  // move the machine. The comment on the tool-change line is used only when none is above.
  CHECK(ops[2].name == "not a name: a move lies between");
  CHECK(ops[2].tool == 2);
  CHECK(ops[2].energy_j == 90);
  double total = 0, co2 = 0;
  for (const auto& op : ops)
    total += op.energy_j, co2 += op.co2_kg;
  CHECK(total == doctest::Approx(e.energy.energy_j));
  CHECK(co2 == doctest::Approx(0.025));
}

TEST_CASE("the tool-change line's own comment names the operation when none is above") {
  const SourceFile source = make_source("ops.ngc", "G1 X1 F100\nM5\nT1 M6\nG1 X2\n"
                                                   "G1 X2.5\nM9\nT2 M6 (Drill, 4 holes)\nG1 X3\n");
  Estimate e = two_operations(source);
  e.timeline.commands[1].line = e.toolpath.commands[1].line = 2;
  e.timeline.commands[3].line = e.toolpath.commands[3].line = 6;
  LineSummary moving;
  moving.has_move = true;
  moving.line = 0;
  e.lines = {moving};
  const auto ops = operations(source, e);
  REQUIRE(ops.size() == 3);
  CHECK(ops[1].name == "T1");
  CHECK(ops[2].name == "Drill, 4 holes");
  const std::string csv = estimate_csv(e, source);
  CHECK(csv.find("\"Drill, 4 holes\"") == std::string::npos); // no LineSummary for line 8 here
}

TEST_CASE("a name below the tool change is found, and the header's tool list is not a name") {
  // As the Haas samples are posted: tool list, setup codes, T1 M6, spindle, then the name.
  const SourceFile source = make_source("ops.ngc", "G1 X1 F100\n"
                                                   "(T1 D=20. CR=0. - ZMIN=-1. - FLAT END MILL)\n"
                                                   "G90 G94 G17 G21\n"
                                                   "T1 M6\n"
                                                   "G1 X2\n"
                                                   "S5500 M3\n"
                                                   "(FACE1)\n"
                                                   "T2 M6\n"
                                                   "G1 X3\n");
  Estimate e = two_operations(source);
  LineSummary moving;
  moving.has_move = true;
  moving.line = 0;
  e.lines = {moving}; // line 4 does not move here, so the look below T1 reaches (FACE1)
  const auto ops = operations(source, e);
  REQUIRE(ops.size() == 3);
  CHECK(ops[1].name == "FACE1");
  CHECK(ops[2].name == "FACE1"); // the comment-only line just above T2
}
