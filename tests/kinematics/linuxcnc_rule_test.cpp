// The "linuxcnc-2.9" junction rule on cases worked out by hand from LinuxCNC's planner rules
// (docs/machine-profiles.md); the measured comparisons are in linuxcnc_golden_test.cpp.
#include <cmath>
#include <doctest/doctest.h>
#include <numbers>

#include "linuxcnc_blend.hpp"
#include "test_helpers.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

// lcnc-time's machine: 100 mm/s and 1000 mm/s^2 on every axis.
MachineProfile linuxcnc_machine() {
  MachineProfile m = round_machine();
  for (AxisLimits& a : m.kinematics.axes)
    a.rapid_mm_s = a.max_feed_mm_s = 100;
  m.kinematics.junction_rule = JunctionRule::LinuxCnc29;
  m.kinematics.tool_change_s = 0;
  m.kinematics.spindle_s_per_1000rpm = 0;
  return m;
}

std::vector<CanonCommand> square(PathMode mode, double side, double f) {
  return {feed(at(0, 0), at(side, 0), f, mode), feed(at(side, 0), at(side, side), f, mode),
          feed(at(side, side), at(0, side), f, mode), feed(at(0, side), at(0, 0), f, mode)};
}

} // namespace

TEST_CASE("a lone move under G64 keeps its parabolic-blend mark: half the acceleration") {
  // LinuxCNC 2.9, G1 X254 F762 from rest: 20.026 s under G64, 20.013 s under G61.
  const double v = 762.0 / 60;
  const Timeline g64 = plan({feed(at(0, 0), at(254, 0), 762)}, linuxcnc_machine());
  CHECK(g64.total_s == doctest::Approx(trapezoid_time(0, 0, v, 254, 500)));
  CHECK(g64.total_s == doctest::Approx(20.026).epsilon(1e-4));
  const Timeline g61 =
      plan({feed(at(0, 0), at(254, 0), 762, PathMode::ExactPath)}, linuxcnc_machine());
  CHECK(g61.total_s == doctest::Approx(trapezoid_time(0, 0, v, 254, 1000)));
}

TEST_CASE("50 mm square at F3000: G61.1 stops at every corner, G64 blends them with arcs") {
  const double v = 50, a = 1000;
  const Timeline stop = plan(square(PathMode::ExactStop, 50, 3000), linuxcnc_machine());
  CHECK(stop.total_s == doctest::Approx(4 * trapezoid_time(0, 0, v, 50, a))); // LinuxCNC 4.200
  for (int i = 0; i < 3; ++i)
    CHECK(stop.commands[i].exit_speed_mm_s == 0);

  // G64 without P: tolerance a quarter of a side; blend distance at most half a side. The
  // corner speed that radius allows (sqrt(0.866 a 25) = 147 mm/s) is above the feed, so the arc
  // is only as large as a parabolic blend at the feed would need: R = v * (v / (a/2)) / (pi/2).
  const double radius = v * (v / (a / 2)) / (std::numbers::pi / 2); // 3.18 mm
  const double arc = radius * std::numbers::pi / 2;                 // 5 mm at 90 degrees
  const double path = 4 * 50 - 6 * radius + 3 * arc;
  // Cruise at the feed throughout, from rest at a, to rest at a/2 (the last side keeps its mark).
  const double expected = path / v + v / (2 * a) + v / (2 * (a / 2));
  const Timeline blend = plan(square(PathMode::Continuous, 50, 3000), linuxcnc_machine());
  CHECK(blend.total_s == doctest::Approx(expected));
  CHECK(blend.total_s == doctest::Approx(3.994).epsilon(2e-3)); // LinuxCNC 2.9: 3.994 s
  // The blend arc before a side is charged to that side.
  CHECK(blend.commands[0].duration_s == doctest::Approx((50 - radius) / v + v / (2 * a)));
  CHECK(blend.commands[1].duration_s == doctest::Approx((50 - 2 * radius + arc) / v));
  CHECK(blend.commands[1].entry_speed_mm_s == doctest::Approx(v));
}

TEST_CASE("G64 P limits the blend arc to the tolerance") {
  // 90-degree corner, P0.01: the arc's middle within 0.01 mm of the corner.
  const double tol = 0.01, a = 1000, theta = std::numbers::pi / 4;
  const double d = std::cos(theta) * tol / (1 - std::sin(theta));
  const double radius = std::tan(theta) * d;
  const double corner = std::sqrt(0.8660254037844386 * a * radius);
  const Timeline t = plan({feed(at(0, 0), at(50, 0), 3000, PathMode::Continuous, tol),
                           feed(at(50, 0), at(50, 50), 3000, PathMode::Continuous, tol)},
                          linuxcnc_machine());
  CHECK(t.commands[0].exit_speed_mm_s == doctest::Approx(corner));
  CHECK(t.commands[1].entry_speed_mm_s == doctest::Approx(corner));
}

TEST_CASE("under G61 a corner stops and both moves keep 90% of the acceleration") {
  const Timeline t = plan({feed(at(0, 0), at(50, 0), 3000, PathMode::ExactPath),
                           feed(at(50, 0), at(50, 50), 3000, PathMode::ExactPath)},
                          linuxcnc_machine());
  CHECK(t.commands[0].exit_speed_mm_s == 0);
  CHECK(t.total_s == doctest::Approx(2 * trapezoid_time(0, 0, 50, 50, 900)));
}

TEST_CASE("the path stops between G0 and G1, at reversals, and at codes task waits on") {
  const MachineProfile m = linuxcnc_machine();
  // G0 into G1, collinear: a stop.
  const Timeline mode = plan({rapid(at(0, 0), at(10, 0)), feed(at(10, 0), at(20, 0), 600)}, m);
  CHECK(mode.commands[0].exit_speed_mm_s == 0);
  // A reversal within 2 degrees: a stop.
  const Timeline back = plan({feed(at(0, 0), at(10, 0), 600), feed(at(10, 0), at(0, 0.3), 600)}, m);
  CHECK(back.commands[0].exit_speed_mm_s == 0);
  // Coolant, spindle speed, messages and a new tool length offset stop the path...
  for (CanonKind kind : {CanonKind::FloodOn, CanonKind::MistOff, CanonKind::SpindleSpeed,
                         CanonKind::Message, CanonKind::ToolLengthOffset, CanonKind::Dwell}) {
    CAPTURE(static_cast<int>(kind));
    const Timeline t =
        plan({feed(at(0, 0), at(10, 0), 600), event(kind), feed(at(10, 0), at(20, 1), 600)}, m);
    CHECK(t.commands[0].exit_speed_mm_s == 0);
  }
  // ...a T word, a new F, a comment and the same work offset again do not.
  CanonCommand g54 = event(CanonKind::WorkOffset, 1);
  for (const CanonCommand& between :
       {event(CanonKind::SelectTool, 2), event(CanonKind::SetFeedRate, 600),
        event(CanonKind::Comment), g54}) {
    CAPTURE(static_cast<int>(between.kind));
    const Timeline t =
        plan({feed(at(0, 0), at(10, 0), 600), between, feed(at(10, 0), at(20, 1), 600)}, m);
    CHECK(t.commands[0].exit_speed_mm_s > 5);
  }
}

TEST_CASE("a spindle start stops the path: the first feed after it starts from rest") {
  const MachineProfile m = linuxcnc_machine();
  std::vector<CanonCommand> program{
      feed(at(-10, 0), at(0, 0), 600), event(CanonKind::SpindleClockwise),
      feed(at(0, 0), at(10, 0), 600), feed(at(10, 0), at(20, 1), 600)};
  const Timeline t = plan(program, m);
  CHECK(t.commands[0].exit_speed_mm_s == 0);
  CHECK(t.commands[2].entry_speed_mm_s == 0);
  CHECK(t.commands[2].exit_speed_mm_s > 5); // it blends into the next one
}

TEST_CASE("naive CAM (G64 P Q): nearly collinear G1s run as one move, time shared by length") {
  const double q = 0.01;
  std::vector<CanonCommand> program;
  CanonCommand mode = event(CanonKind::PathControl, q);
  mode.state.path_mode = PathMode::Continuous;
  mode.state.path_tolerance = q;
  program.push_back(mode);
  double x = 0, y = 0;
  for (int i = 1; i <= 10; ++i) {
    const double nx = 2.0 * i, ny = (i % 2) * 0.004;
    program.push_back(feed(at(x, y), at(nx, ny), 1200, PathMode::Continuous, q));
    x = nx, y = ny;
  }
  const Timeline t = plan(program, linuxcnc_machine());
  // One move from (0, 0) to (20, 0), at a/2 throughout (the last one queued keeps its mark).
  const double expected = trapezoid_time(0, 0, 20, 20, 500);
  CHECK(t.total_s == doctest::Approx(expected).epsilon(1e-6));
  for (int i = 2; i <= 9; ++i) // the middle lines cruise at the feed
    CHECK(t.commands[i].duration_s == doctest::Approx(move_length(program[i]) / 20).epsilon(1e-4));
}

TEST_CASE("a segment shorter than a servo cycle's travel is held to one length per cycle") {
  // 0.05 mm steps at F6000 (100 mm/s) would need 0.5 ms each: LinuxCNC holds them to 50 mm/s.
  std::vector<CanonCommand> program;
  for (int i = 0; i < 40; ++i)
    program.push_back(feed(at(0.05 * i, 0), at(0.05 * (i + 1), 0), 6000));
  const Timeline t = plan(program, linuxcnc_machine());
  double peak = 0;
  for (const TimedCommand& c : t.commands)
    peak = std::max(peak, c.peak_speed_mm_s);
  CHECK(peak <= 0.05 / 0.001 + 1e-9);
  CHECK(t.total_s > 2.0 / 50);
}

TEST_CASE("blend arcs shorten the timed path, never the programmed one") {
  PlanOptions options;
  options.max_sample_step_mm = 1;
  const Timeline t = plan(square(PathMode::Continuous, 50, 3000), linuxcnc_machine(), options);
  for (const TimedCommand& c : t.commands) {
    REQUIRE(c.samples.size() >= 2);
    CHECK(c.samples.front().u == 0);
    CHECK(c.samples.back().u == 1);
    for (std::size_t k = 1; k < c.samples.size(); ++k)
      CHECK(c.samples[k].t_s >= c.samples[k - 1].t_s);
  }
  // The second side's samples lie on the programmed side, x = 50, corner to corner.
  CHECK(t.commands[1].samples.front().position.y == 0);
  CHECK(t.commands[1].samples.back().position.y == 50);
  for (const MotionSample& s : t.commands[1].samples)
    CHECK(s.position.x == 50);
}

TEST_CASE("LinuxCNC's task runs each code it waits on in a few ms, charged to the move before") {
  const MachineProfile m = linuxcnc_machine();
  const CanonCommand a = feed(at(0, 0), at(10, 0), 600), b = feed(at(10, 0), at(20, 5), 600);
  const Timeline plain = plan({a, b}, m);
  const Timeline coolant = plan({a, event(CanonKind::FloodOn), event(CanonKind::MistOn), b}, m);
  const double latency = ncjoule::kinematics_detail::linuxcnc::kTaskLatency_s;
  // Two codes between the moves: the path stops, and task takes its time for each.
  CHECK(coolant.commands[0].exit_speed_mm_s == 0);
  const double stopped = plan({a, event(CanonKind::Dwell, 0), b}, m).total_s - latency;
  CHECK(coolant.total_s == doctest::Approx(stopped + 2 * latency));
  CHECK(coolant.total_s > plain.total_s);
  CHECK(coolant.commands[0].samples.back().t_s == doctest::Approx(coolant.commands[0].duration_s));
  // After the last move (and before the first) the codes are not timed.
  const Timeline after = plan({a, event(CanonKind::FloodOff)}, m);
  CHECK(after.total_s == doctest::Approx(plan({a}, m).total_s));
}

TEST_CASE("naive CAM takes an XY arc within Q of its chord as two points of a straight move") {
  const double q = 0.1;
  CanonCommand mode = event(CanonKind::PathControl, q);
  mode.state.path_tolerance = q;
  // A 10 mm arc of radius 200 strays 0.0625 mm from its chord: merged with the lines around it.
  CanonCommand flat = arc(at(10, 0), at(20, 0), 15, -199.9375, -1, 1200);
  flat.state.path_tolerance = q;
  const std::vector<CanonCommand> program{
      mode, feed(at(0, 0), at(10, 0), 1200, PathMode::Continuous, q), flat,
      feed(at(20, 0), at(30, 0), 1200, PathMode::Continuous, q)};
  const Timeline t = plan(program, linuxcnc_machine());
  // One 30 mm move at 20 mm/s, at a/2 throughout (the last move queued keeps its mark).
  CHECK(t.total_s == doctest::Approx(trapezoid_time(0, 0, 20, 30, 500)).epsilon(1e-3));
  CHECK(t.commands[2].duration_s == doctest::Approx(10.0 / 20).epsilon(1e-2));
}

TEST_CASE("an arc whose middle ends one naive-CAM move and whose end starts the next") {
  // G64 P0.5, a 90-degree corner arc of radius 1 after a 19 mm line: the arc's middle is within
  // 0.5 of the line (0,0)-middle, its end is not, so the detector sends two straight moves and
  // the arc is in both. It runs as the same path written with two G1s (middle, end), and is
  // charged once, with both halves and the blend between them, though its first half settles
  // long before its second (64 more moves keep the queue busy).
  const double q = 0.5;
  CanonCommand mode = event(CanonKind::PathControl, q);
  mode.state.path_tolerance = q;
  const Pose mid = at(19 + std::sqrt(0.5), 1 - std::sqrt(0.5));
  auto program = [&](bool as_lines) {
    std::vector<CanonCommand> p{mode, feed(at(0, 0), at(19, 0), 1200, PathMode::Continuous, q)};
    if (as_lines) {
      p.push_back(feed(at(19, 0), mid, 1200, PathMode::Continuous, q));
      p.push_back(feed(mid, at(20, 1), 1200, PathMode::Continuous, q));
    } else {
      CanonCommand corner = arc(at(19, 0), at(20, 1), 19, 1, 1, 1200);
      corner.state.path_tolerance = q;
      p.push_back(corner);
    }
    for (int i = 0; i < 64; ++i) // a zigzag up the side: every point a corner
      p.push_back(feed(at(20 + (i % 2), 1 + i), at(20 + ((i + 1) % 2), 2 + i), 1200,
                       PathMode::Continuous, q));
    return p;
  };
  const Timeline arcs = plan(program(false), linuxcnc_machine());
  const Timeline lines = plan(program(true), linuxcnc_machine());
  CHECK(arcs.total_s == doctest::Approx(lines.total_s).epsilon(1e-3));
  // The arc's time is the two lines' (the two halves of the same path).
  CHECK(arcs.commands[2].duration_s ==
        doctest::Approx(lines.commands[2].duration_s + lines.commands[3].duration_s).epsilon(1e-3));
  CHECK(arcs.commands[2].duration_s == doctest::Approx(std::numbers::pi / 2 / 20).epsilon(0.05));
  double sum = 0;
  for (const TimedCommand& c : arcs.commands)
    sum += c.duration_s;
  CHECK(sum == doctest::Approx(arcs.total_s));
}

TEST_CASE("a move whose rest runs in the next blend arc keeps that part of the arc's time") {
  // 0.15 mm moves at F3000 turning by a degree or two: the last few servo cycles of each move
  // run in the blend arc after it. LinuxCNC lists such a move with no time; ncjoule charges it
  // the part of the arc that runs its rest, so that every line that cuts has a time.
  std::vector<CanonCommand> program;
  Pose p = at(0, 0);
  for (int i = 0; i < 200; ++i) {
    const double heading = 0.03 * std::sin((i / 2) * 0.7); // pairs of collinear moves
    const Pose q = at(p.x + 0.15 * std::cos(heading), p.y + 0.15 * std::sin(heading));
    program.push_back(feed(p, q, 3000));
    p = q;
  }
  const Timeline t = plan(program, linuxcnc_machine());
  double sum = 0;
  for (const TimedCommand& c : t.commands) {
    CHECK(c.duration_s > 0);
    sum += c.duration_s;
  }
  CHECK(sum == doctest::Approx(t.total_s));
  // At 50 mm/s the middle moves take about their length over the feed.
  CHECK(t.commands[100].duration_s == doctest::Approx(0.15 / 50).epsilon(0.2));
}
