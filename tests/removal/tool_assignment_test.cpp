// Which tool each move cuts with when the program and the user describe some tools and not
// others: a missing description is never fatal.
#include <doctest/doctest.h>

#include "fixture.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

bool mentions(const std::vector<Diagnostic>& diagnostics, Severity severity,
              const std::string& text) {
  for (const Diagnostic& d : diagnostics)
    if (d.severity == severity && d.message.find(text) != std::string::npos) return true;
  return false;
}

} // namespace

TEST_CASE("a tool used but described nowhere: its moves remove nothing, a warning names it") {
  ProgramBuilder p;
  p.tool(1).feed_rate(300).rapid(0, 0, 5).feed(0, 0, -1);
  p.tool(7).rapid(10, 0, 5).feed(10, 0, -1).feed(20, 0, -1);
  const std::map<int, Tool> described{{1, flat_end_mill(1, 6)}};
  const ToolAssignment a = assign_tools(p.commands(), described, std::nullopt, "part.nc");
  REQUIRE(a.unsimulated == std::vector<int>{7});
  CHECK(!a.tools.count(7));
  REQUIRE(a.diagnostics.size() == 1);
  CHECK(a.diagnostics[0].severity == Severity::Warning);
  CHECK(a.diagnostics[0].line == 4); // first feed with T7, 1-based
  CHECK(a.diagnostics[0].file == "part.nc");
  // The message names every way to describe the tool.
  for (const char* way : {"T7", "--tool", "--job", "--tool-table", "[default_tool]"})
    CHECK(a.diagnostics[0].message.find(way) != std::string::npos);

  // Removal runs without it: T1's plunge counts, T7's moves remove nothing.
  StockSpec stock;
  stock.kind = StockSpec::Kind::Box;
  stock.box = {-5, -5, -5, 30, 5, 0};
  const RemovalResult r =
      simulate_removal(p.commands(), constant_speed_timeline(p.commands(), 0.5), a.tools, stock);
  CHECK(r.commands[1].removed_mm3 > 0);
  CHECK(r.commands[4].removed_mm3 == 0);
  for (const Diagnostic& d : r.diagnostics)
    CHECK(d.severity != Severity::Error);
}

TEST_CASE("rapids before the first tool change need no tool") {
  ProgramBuilder p;
  p.rapid(0, 0, 50).rapid(0, 0, 20); // G28 G91 Z0., G53 G0 Z0. ...
  p.tool(3).feed_rate(300).rapid(0, 0, 5).feed(0, 0, -1);
  const ToolAssignment a =
      assign_tools(p.commands(), {{3, flat_end_mill(3, 6)}}, std::nullopt, "part.nc");
  CHECK(a.unsimulated.empty());
  CHECK(a.diagnostics.empty());
}

TEST_CASE("feed moves before the first tool change cut with the program's only tool") {
  ProgramBuilder p;
  p.feed_rate(300).rapid(0, 0, 5).feed(0, 0, -1); // T0
  p.tool(3).rapid(5, 0, 5).feed(5, 0, -1);
  const ToolAssignment a =
      assign_tools(p.commands(), {{3, flat_end_mill(3, 6)}}, std::nullopt, "part.nc");
  REQUIRE(a.tools.count(0));
  CHECK(a.tools.at(0).diameter_mm == 6);
  CHECK(a.unsimulated.empty());
  CHECK(mentions(a.diagnostics, Severity::Warning, "before the first tool change"));
}

TEST_CASE("a program that selects no tool cuts with the one tool described, with a note") {
  ProgramBuilder p; // Estlcam, grbl-style posts, pcb2gcode: no T word anywhere
  p.feed_rate(300).rapid(0, 0, 5).feed(0, 0, -1).feed(10, 0, -1);
  const ToolAssignment a =
      assign_tools(p.commands(), {{1, ball_end_mill(1, 3.175)}}, std::nullopt, "part.nc");
  REQUIRE(a.tools.count(0));
  CHECK(a.tools.at(0).shape == ToolShape::BallEndMill);
  CHECK(a.unsimulated.empty());
  CHECK(mentions(a.diagnostics, Severity::Note, "selects no tool"));
}

TEST_CASE("nothing described: the profile's default tool, with a warning: else no removal") {
  ProgramBuilder p;
  p.feed_rate(300).rapid(0, 0, 5).feed(0, 0, -1);
  const Tool fallback = flat_end_mill(0, 6);
  const ToolAssignment with = assign_tools(p.commands(), {}, fallback, "part.nc");
  REQUIRE(with.tools.count(0));
  CHECK(with.unsimulated.empty());
  CHECK(mentions(with.diagnostics, Severity::Warning, "default tool"));

  const ToolAssignment without = assign_tools(p.commands(), {}, std::nullopt, "part.nc");
  CHECK(without.tools.empty());
  CHECK(without.unsimulated == std::vector<int>{0});
  CHECK(mentions(without.diagnostics, Severity::Warning, "--tool"));
}

TEST_CASE("several tools described and several used: tool 0 is not guessed among them") {
  ProgramBuilder p;
  p.feed_rate(300).rapid(0, 0, 5).feed(0, 0, -1); // T0
  p.tool(1).feed(1, 0, -1);
  p.tool(2).feed(2, 0, -1);
  const ToolAssignment a =
      assign_tools(p.commands(), {{1, flat_end_mill(1, 6)}, {2, flat_end_mill(2, 3)}},
                   flat_end_mill(0, 10), "part.nc");
  REQUIRE(a.tools.count(0));
  CHECK(a.tools.at(0).diameter_mm == 10); // the default, not T1 or T2
}

TEST_CASE("a LinuxCNC tool table's diameters become tools, shapes read from the comments") {
  std::vector<Diagnostic> d;
  const SourceFile tbl = make_source(
      "tool.tbl", "T1 P1 Z10 D6 ;6mm ball end mill\nT2 P2 D3.175\nT3 P3 D8 ;8mm drill\nT4 P4 Z1\n");
  const std::map<int, Tool> tools =
      tools_from_table(parse_tool_table(tbl, false, d), d, "tool.tbl");
  REQUIRE(tools.size() == 3); // T4 has no diameter
  CHECK(tools.at(1).shape == ToolShape::BallEndMill);
  CHECK(tools.at(1).corner_radius_mm == doctest::Approx(3));
  CHECK(tools.at(2).shape == ToolShape::FlatEndMill);
  CHECK(tools.at(2).diameter_mm == doctest::Approx(3.175));
  CHECK(tools.at(3).shape == ToolShape::Drill);
  CHECK(mentions(d, Severity::Note, "T2"));
}

TEST_CASE("a tool table's numbers are checked as a control takes them: a line out of range is "
          "skipped, with its line and column") {
  std::vector<Diagnostic> d;
  const SourceFile tbl =
      make_source("tool.tbl", "T1 P1 D6\nT4294967297 P2 D50\nT3 P3 D-4\n"
                              "T4 P4 D9000000\nT5 P5 Z100000000 D6\nT2.5 P6 D6\nT6 P7 Dx\n");
  const ToolTable table = parse_tool_table(tbl, false, d);
  CHECK(table.size() == 1); // T1 alone: T4294967297 would have wrapped into T1
  CHECK(table.at(1).diameter == doctest::Approx(6));
  REQUIRE(d.size() == 6); // the last: D's value no number
  for (int k = 0; k < 6; ++k) {
    CHECK(d[k].severity == Severity::Error);
    CHECK(d[k].line == k + 2);
    CHECK(d[k].column > 0);
  }
}
