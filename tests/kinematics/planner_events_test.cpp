// Commands that are not moves, and properties every timeline must have.
#include <cmath>
#include <doctest/doctest.h>

#include "test_helpers.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("dwell, tool change, spindle ramps and stops take their time") {
  const MachineProfile m = round_machine(); // 5 s tool change, 0.5 s per 1000 rpm
  std::vector<CanonCommand> program{
      event(CanonKind::Dwell, 2.5),         event(CanonKind::ChangeTool, 3),
      event(CanonKind::SpindleSpeed, 1000), event(CanonKind::SpindleClockwise),
      event(CanonKind::SpindleSpeed, 3000), event(CanonKind::SpindleCounterClockwise),
      event(CanonKind::SpindleStop),        event(CanonKind::ProgramStop),
      event(CanonKind::OptionalStop),       event(CanonKind::SelectTool, 4)};
  const Timeline t = plan(program, m);
  CHECK(t.commands[0].duration_s == doctest::Approx(2.5));
  CHECK(t.commands[1].duration_s == doctest::Approx(m.kinematics.tool_change_s));
  CHECK(t.commands[2].duration_s == 0);                    // S before M3: nothing turns yet
  CHECK(t.commands[3].duration_s == doctest::Approx(0.5)); // 0 -> 1000
  CHECK(t.commands[4].duration_s == doctest::Approx(1.0)); // 1000 -> 3000
  CHECK(t.commands[5].duration_s == doctest::Approx(3.0)); // 3000 cw -> 3000 ccw
  CHECK(t.commands[6].duration_s == doctest::Approx(1.5)); // 3000 -> 0
  CHECK(t.commands[7].duration_s == 0);
  CHECK_FALSE(t.commands[7].note.empty());
  CHECK_FALSE(t.commands[8].note.empty());
  CHECK(t.commands[9].duration_s == 0);
}

TEST_CASE("a measured spindle run-up: times from rest, differences between speeds") {
  // As a VMC's logs show it: nothing below 3000 rpm (the at-speed window), 3 s to 7500,
  // 7 s to 12000 (the constant-power range, where each rpm takes longer).
  MachineProfile m = round_machine();
  m.kinematics.spindle_run_up = {{3000, 0.0}, {7500, 3.0}, {12000, 7.0}};
  std::vector<CanonCommand> program{
      event(CanonKind::SpindleSpeed, 12000),
      event(CanonKind::SpindleClockwise),        // 0 -> 12000
      event(CanonKind::SpindleSpeed, 7500),      // down
      event(CanonKind::SpindleSpeed, 9750),      // halfway up
      event(CanonKind::SpindleCounterClockwise), // reversal
      event(CanonKind::SpindleStop),
      event(CanonKind::SpindleSpeed, 2000),
      event(CanonKind::SpindleClockwise),
      event(CanonKind::SpindleSpeed, 15000)}; // past the table: at the last segment's rate
  const Timeline t = plan(program, m);
  CHECK(t.commands[1].duration_s == doctest::Approx(7.0));
  CHECK(t.commands[2].duration_s == doctest::Approx(4.0)); // runs down on the same curve
  CHECK(t.commands[3].duration_s == doctest::Approx(2.0));
  CHECK(t.commands[4].duration_s == doctest::Approx(2 * 5.0)); // 9750 -> 0 -> 9750 ccw
  CHECK(t.commands[5].duration_s == doctest::Approx(5.0));
  CHECK(t.commands[7].duration_s == 0); // inside the at-speed window
  CHECK(t.commands[8].duration_s == doctest::Approx(7.0 + 3 * 4.0 / 4.5));
}

TEST_CASE("the tool-change sequence: the first change, a change to the tool in the spindle") {
  MachineProfile m = round_machine(); // 5 s tool change
  std::vector<CanonCommand> program{
      event(CanonKind::ChangeTool, 3), event(CanonKind::ChangeTool, 3),
      event(CanonKind::ChangeTool, 4), event(CanonKind::ChangeTool, 4)};
  Timeline t = plan(program, m);
  for (const TimedCommand& c : t.commands) // nothing said: every M6 the same
    CHECK(c.duration_s == doctest::Approx(5.0));
  m.kinematics.tool_change_first_extra_s = 2.0;
  m.kinematics.tool_change_same_tool_s = 2.4;
  t = plan(program, m);
  CHECK(t.commands[0].duration_s == doctest::Approx(7.0));
  CHECK(t.commands[1].duration_s == doctest::Approx(2.4));
  CHECK(t.commands[2].duration_s == doctest::Approx(5.0));
  CHECK(t.commands[3].duration_s == doctest::Approx(2.4));
}

TEST_CASE("a tool change that finds the spindle turning stops and orients it first") {
  MachineProfile m = round_machine(); // 5 s tool change
  m.kinematics.tool_change_spindle_stop_s = 1.5;
  m.kinematics.tool_change_same_tool_s = 2.4;
  const std::vector<CanonCommand> program{
      event(CanonKind::ChangeTool, 3),    event(CanonKind::SpindleSpeed, 2000),
      event(CanonKind::SpindleClockwise), event(CanonKind::ChangeTool, 4),
      event(CanonKind::ChangeTool, 4),    event(CanonKind::SpindleStop),
      event(CanonKind::ChangeTool, 5)};
  const Timeline t = plan(program, m);
  CHECK(t.commands[0].duration_s == doctest::Approx(5.0)); // the spindle at rest
  CHECK(t.commands[3].duration_s == doctest::Approx(5.0 + 1.5));
  CHECK(t.commands[4].duration_s == doctest::Approx(2.4)); // the change stopped the spindle
  CHECK(t.commands[6].duration_s == doctest::Approx(5.0)); // after M5
}

TEST_CASE(
    "a control's waits at M1, M0, M30 and coolant on, and a spindle the path does not wait for") {
  MachineProfile m = round_machine(); // 0.5 s per 1000 rpm
  std::vector<CanonCommand> program{event(CanonKind::SpindleSpeed, 2000),
                                    event(CanonKind::SpindleClockwise),
                                    event(CanonKind::FloodOn),
                                    event(CanonKind::OptionalStop),
                                    event(CanonKind::ProgramStop),
                                    event(CanonKind::ProgramEnd)};
  Timeline t = plan(program, m);
  CHECK(t.commands[1].duration_s == doctest::Approx(1.0));
  for (std::size_t i = 2; i < t.commands.size(); ++i)
    CHECK(t.commands[i].duration_s == 0);
  m.kinematics.waits = {6.9, 0.5, 6.4, 6.2}; // optional stop, program stop, end, coolant on
  m.kinematics.spindle_waits = false;
  t = plan(program, m);
  CHECK(t.commands[1].duration_s == 0); // the spindle runs up while the path moves on
  CHECK(t.commands[2].duration_s == doctest::Approx(6.2));
  CHECK(t.commands[3].duration_s == doctest::Approx(6.9));
  CHECK(t.commands[4].duration_s == doctest::Approx(0.5));
  CHECK(t.commands[5].duration_s == doctest::Approx(6.4));
}

TEST_CASE("settling: rapids and feeds that end at rest, each with its own time") {
  MachineProfile m = round_machine();
  const std::vector<CanonCommand> program{
      rapid(at(0, 0, 10), at(50, 0, 10)), event(CanonKind::Dwell, 1),
      feed(at(50, 0, 10), at(50, 0, 0), 600), event(CanonKind::Dwell, 1)};
  const Timeline plain = plan(program, m);
  m.kinematics.settle_s = 0.16;
  m.kinematics.settle_rapid_s = 0.075;
  const Timeline settled = plan(program, m);
  CHECK(settled.commands[0].duration_s - plain.commands[0].duration_s == doctest::Approx(0.075));
  CHECK(settled.commands[2].duration_s - plain.commands[2].duration_s == doctest::Approx(0.16));
}

TEST_CASE("zero-length moves take zero time and keep their two samples") {
  const Timeline t =
      plan({feed(at(5, 5), at(5, 5), 600), rapid(at(5, 5), at(5, 5))}, round_machine());
  for (const TimedCommand& c : t.commands) {
    CHECK(c.duration_s == 0);
    REQUIRE(c.samples.size() == 2);
    CHECK(c.samples.front().u == 0);
    CHECK(c.samples.back().u == 1);
  }
}

TEST_CASE("block times add up to the program time, with no negative or NaN time") {
  CanonCommand bad_dwell = event(CanonKind::Dwell, std::nan(""));
  std::vector<CanonCommand> program{rapid(at(0, 0, 10), at(10, 10, 10)),
                                    event(CanonKind::ChangeTool, 1),
                                    feed(at(10, 10, 10), at(10, 10, 0), 300),
                                    feed(at(10, 10, 0), at(40, 10, 0), 0), // F0
                                    arc(at(40, 10, 0), at(40, 30, 0), 40, 20, -1, 900),
                                    feed(at(40, 30, 0), at(40, 30, 0), 900),
                                    bad_dwell,
                                    event(CanonKind::Dwell, -3),
                                    feed(at(40, 30, 0), at(0, 0, 0), 1200),
                                    rapid(at(0, 0, 0), at(0, 0, 50))};
  const Timeline t = plan(program, round_machine());
  double sum = 0;
  for (std::size_t i = 0; i < t.commands.size(); ++i) {
    const TimedCommand& c = t.commands[i];
    CHECK(std::isfinite(c.duration_s));
    CHECK(c.duration_s >= 0);
    CHECK(c.start_s == doctest::Approx(sum));
    sum += c.duration_s;
  }
  CHECK(t.total_s == doctest::Approx(sum));
  CHECK_FALSE(t.diagnostics.empty()); // the F0 move is reported
}

TEST_CASE("rotary-only moves are timed in degrees") {
  MachineProfile m = round_machine();
  m.kinematics.rotary_rapid_deg_s = 90;
  m.kinematics.rotary_accel_deg_s2 = 360;
  CanonCommand c = feed(at(0, 0), at(0, 0), 1800); // 30 deg/s
  c.end.a = 90;
  const Timeline t = plan({c}, m);
  CHECK(t.commands[0].length_mm == 0);
  CHECK(t.total_s == doctest::Approx(trapezoid_time(0, 0, 30, 90, 360)));
}

TEST_CASE("a feed above the machine's maximum is clamped with one note: the block, the limit, "
          "the count") {
  const MachineProfile m = round_machine(); // max feed 10000 mm/min on every axis
  std::vector<CanonCommand> program{
      feed(at(0, 0), at(100, 0), 50000), feed(at(100, 0), at(100, 100), 8000),
      feed(at(100, 100), at(0, 100), 60000), feed(at(0, 100), at(0, 0), 12000)};
  for (std::size_t i = 0; i < program.size(); ++i)
    program[i].line = int(i) + 4;
  const Timeline t = plan(program, m);
  int notes = 0;
  for (const Diagnostic& d : t.diagnostics) {
    if (d.message.find("clamps it") == std::string::npos) continue;
    ++notes;
    CHECK(d.severity == Severity::Note);
    CHECK(d.line == 5); // the first such block (0-based line 4)
    CHECK(d.message.find("50000 mm/min") != std::string::npos);
    CHECK(d.message.find("(10000 mm/min") != std::string::npos);
    CHECK(d.message.find("3 blocks in all") != std::string::npos);
  }
  CHECK(notes == 1);
  // Timed at the limit: 100 mm at 10000 mm/min is at least 0.6 s.
  CHECK(t.commands[0].duration_s >= 0.6);
  // A feed within the limit, on the diagonal too (each axis at 7071 mm/min), says nothing.
  const Timeline within = plan({feed(at(0, 0), at(100, 100), 14000)}, m);
  for (const Diagnostic& d : within.diagnostics)
    CHECK(d.message.find("clamps it") == std::string::npos);
}
