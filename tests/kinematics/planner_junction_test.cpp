// Look-ahead and junctions: where the path keeps its speed between blocks and where it must slow.
#include <cmath>
#include <doctest/doctest.h>

#include "test_helpers.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

std::vector<CanonCommand> corner(PathMode mode, double tolerance, double f = 6000) {
  return {feed(at(0, 0), at(100, 0), f, mode, tolerance),
          feed(at(100, 0), at(100, 100), f, mode, tolerance)};
}

// Speed at which a 90-degree corner may be taken with path tolerance `tol`.
double corner_speed(double accel, double tol) {
  const double s = std::sqrt(0.5); // sine of half the interior angle
  return std::sqrt(accel * tol * s / (1 - s));
}

} // namespace

TEST_CASE("collinear blocks run through at full feed") {
  std::vector<CanonCommand> program;
  for (int i = 0; i < 10; ++i)
    program.push_back(feed(at(25.4 * i, 0), at(25.4 * (i + 1), 0), 762));
  const Timeline t = plan(program, round_machine());
  const Timeline single = plan({feed(at(0, 0), at(254, 0), 762)}, round_machine());
  CHECK(t.total_s == doctest::Approx(single.total_s));
  for (int i = 0; i + 1 < 10; ++i) {
    CHECK(t.commands[i].exit_speed_mm_s == doctest::Approx(762.0 / 60));
    CHECK(t.commands[i + 1].entry_speed_mm_s == t.commands[i].exit_speed_mm_s);
  }
}

TEST_CASE("state changes between moves do not stop the path") {
  std::vector<CanonCommand> program{feed(at(0, 0), at(50, 0), 762), event(CanonKind::Comment),
                                    event(CanonKind::PlaneSelect),
                                    feed(at(50, 0), at(100, 0), 762)};
  const Timeline t = plan(program, round_machine());
  CHECK(t.commands[0].exit_speed_mm_s == doctest::Approx(762.0 / 60));
  CHECK(t.commands[3].entry_speed_mm_s == doctest::Approx(762.0 / 60));
}

TEST_CASE("coolant codes stop the path (grbl and LinuxCNC), except in Pavanaskar's analyzer") {
  std::vector<CanonCommand> program{feed(at(0, 0), at(50, 0), 762), event(CanonKind::FloodOn),
                                    feed(at(50, 0), at(100, 0), 762)};
  CHECK(plan(program, round_machine()).commands[0].exit_speed_mm_s == 0);
  MachineProfile analyzer = round_machine();
  analyzer.kinematics.junction_rule = JunctionRule::NextFeed;
  CHECK(plan(program, analyzer).commands[0].exit_speed_mm_s == doctest::Approx(762.0 / 60));
}

TEST_CASE("a dwell between collinear moves stops the path") {
  std::vector<CanonCommand> program{feed(at(0, 0), at(50, 0), 762), event(CanonKind::Dwell, 1),
                                    feed(at(50, 0), at(100, 0), 762)};
  const Timeline t = plan(program, round_machine());
  CHECK(t.commands[0].exit_speed_mm_s == 0);
  CHECK(t.commands[2].entry_speed_mm_s == 0);
  CHECK(t.total_s == doctest::Approx(1 + 2 * trapezoid_time(0, 0, 12.7, 50, 1000)));
}

TEST_CASE("90-degree corner under G61 exact path and G61.1 exact stop: stop at the corner") {
  for (PathMode mode : {PathMode::ExactPath, PathMode::ExactStop}) {
    const Timeline t = plan(corner(mode, 0), round_machine());
    CHECK(t.commands[0].exit_speed_mm_s == 0);
    CHECK(t.total_s == doctest::Approx(2 * trapezoid_time(0, 0, 100, 100, 1000)));
  }
}

TEST_CASE("90-degree corner under G64 P: blend within the tolerance at the acceleration limit") {
  const double tol = 0.02, a = 1000, v = 100;
  const double vj = corner_speed(a, tol);
  const Timeline t = plan(corner(PathMode::Continuous, tol), round_machine());
  CHECK(t.commands[0].exit_speed_mm_s == doctest::Approx(vj));
  CHECK(t.commands[1].entry_speed_mm_s == doctest::Approx(vj));
  CHECK(t.total_s ==
        doctest::Approx(trapezoid_time(0, vj, v, 100, a) + trapezoid_time(vj, 0, v, 100, a)));
  const Timeline stop = plan(corner(PathMode::ExactPath, 0), round_machine());
  CHECK(t.total_s < stop.total_s);
}

TEST_CASE("G64 without P uses the profile's path tolerance") {
  MachineProfile m = round_machine();
  m.kinematics.path_tolerance_mm = 0.1;
  const Timeline t = plan(corner(PathMode::Continuous, 0), m);
  CHECK(t.commands[0].exit_speed_mm_s == doctest::Approx(corner_speed(1000, 0.1)));
}

TEST_CASE("a reversal stops the path") {
  const Timeline t =
      plan({feed(at(0, 0), at(10, 0), 600), feed(at(10, 0), at(0, 0), 600)}, round_machine());
  CHECK(t.commands[0].exit_speed_mm_s == 0);
}

TEST_CASE("next-feed junctions (Pavanaskar) slow only to the next block's feed") {
  MachineProfile m = round_machine();
  m.kinematics.junction_rule = JunctionRule::NextFeed;
  std::vector<CanonCommand> program = corner(PathMode::Continuous, 0);
  program[1].state.feed = 600;
  const Timeline t = plan(program, m);
  CHECK(t.commands[0].exit_speed_mm_s == doctest::Approx(10));
  CHECK(t.total_s ==
        doctest::Approx(trapezoid_time(0, 10, 100, 100, 1000) + 100.0 / 10 + 10.0 / 2000));
}

TEST_CASE("exact stop on every block when the profile says so") {
  MachineProfile m = round_machine();
  m.kinematics.exact_stop_every_block = true;
  const Timeline t = plan({feed(at(0, 0), at(50, 0), 762), feed(at(50, 0), at(100, 0), 762)}, m);
  CHECK(t.commands[0].exit_speed_mm_s == 0);
}

TEST_CASE("settle_s: every move that ends at rest waits for the in-position check") {
  // Two collinear feeds blend (no stop between them), then a rapid: the stops are at the end of
  // the second feed (the rapid turns back) and of the rapid: 2 x 0.1 s more than without.
  const std::vector<CanonCommand> program{feed(at(0, 0), at(50, 0), 762),
                                          feed(at(50, 0), at(100, 0), 762),
                                          rapid(at(100, 0), at(0, 0))};
  MachineProfile m = round_machine();
  const Timeline without = plan(program, m);
  m.kinematics.settle_s = 0.1;
  const Timeline with = plan(program, m);
  REQUIRE(without.commands[0].exit_speed_mm_s > 0);
  CHECK(with.commands[0].duration_s == doctest::Approx(without.commands[0].duration_s));
  CHECK(with.commands[1].duration_s == doctest::Approx(without.commands[1].duration_s + 0.1));
  CHECK(with.commands[2].duration_s == doctest::Approx(without.commands[2].duration_s + 0.1));
  CHECK(with.total_s == doctest::Approx(without.total_s + 0.2));
  // The next command starts after the wait; the move's last sample is at its end, at rest.
  CHECK(with.commands[2].start_s ==
        doctest::Approx(with.commands[1].start_s + with.commands[1].duration_s));
  CHECK(with.commands[1].samples.back().t_s ==
        doctest::Approx(with.commands[1].start_s + with.commands[1].duration_s));
}

TEST_CASE("backward pass: never faster than the machine can stop within the blocks ahead") {
  // A long fast block, then short collinear blocks, then the end of the path.
  std::vector<CanonCommand> program{feed(at(0, 0), at(200, 0), 6000)};
  for (int i = 0; i < 4; ++i)
    program.push_back(feed(at(200 + 0.1 * i, 0), at(200 + 0.1 * (i + 1), 0), 6000));
  const Timeline t = plan(program, round_machine());
  const double a = 1000;
  // The speed at each junction is what stopping in the distance left allows.
  for (int i = 0; i < 5; ++i) {
    const double left = 0.1 * (4 - i);
    CHECK(t.commands[i].exit_speed_mm_s == doctest::Approx(std::sqrt(2 * a * left)));
  }
  // ...and the short blocks together take the time of one deceleration from there.
  double tail = 0;
  for (int i = 1; i < 5; ++i)
    tail += t.commands[i].duration_s;
  CHECK(tail == doctest::Approx(std::sqrt(2 * a * 0.4) / a));
}

TEST_CASE("forward pass: a chain of short blocks accelerates as one") {
  std::vector<CanonCommand> program;
  for (int i = 0; i < 20; ++i)
    program.push_back(feed(at(0.5 * i, 0), at(0.5 * (i + 1), 0), 6000));
  const Timeline t = plan(program, round_machine());
  // 10 mm in total, rest to rest, peak sqrt(a * L) = 100 mm/s exactly at the middle.
  CHECK(t.total_s == doctest::Approx(2 * std::sqrt(10.0 / 1000)));
  CHECK(t.commands[0].exit_speed_mm_s == doctest::Approx(std::sqrt(2 * 1000 * 0.5)));
}

TEST_CASE("a line running tangentially into an arc keeps its speed, in XY and in XZ") {
  const double f = 1200, v = f / 60;
  // G17: +X into a counter-clockwise quarter circle around (10, 5).
  const Timeline xy =
      plan({feed(at(0, 0), at(10, 0), f), arc(at(10, 0), at(15, 5), 10, 5, 1, f)}, round_machine());
  CHECK(xy.commands[0].exit_speed_mm_s == doctest::Approx(v));

  // G18 (first axis Z, second X): +X into a clockwise quarter circle around z=5, x=10.
  CanonCommand xz = arc(at(10, 0, 0), at(15, 0, 5), 5, 10, -1, f);
  xz.plane = Plane::XZ;
  const Timeline t = plan({feed(at(0, 0), at(10, 0), f), xz}, round_machine());
  CHECK(t.commands[0].exit_speed_mm_s == doctest::Approx(v));

  // The same arc the other way round starts against the line: a reversal.
  xz.rotation = 1;
  xz.end = at(5, 0, 5);
  const Timeline reversed = plan({feed(at(0, 0), at(10, 0), f), xz}, round_machine());
  CHECK(reversed.commands[0].exit_speed_mm_s == 0);
}

TEST_CASE("transition_speed_ratio: every transition between feed blocks slows to a share of F") {
  // Two collinear feeds at 12.7 mm/s run through at full speed by the corner rule; a control that
  // slows at every block end takes the transition at a quarter of the feed. At the 90-degree
  // corner the corner rule's lower speed stays; into a rapid the ratio does not apply.
  MachineProfile m = round_machine();
  const std::vector<CanonCommand> straight{feed(at(0, 0), at(50, 0), 762),
                                           feed(at(50, 0), at(100, 0), 762)};
  REQUIRE(plan(straight, m).commands[0].exit_speed_mm_s == doctest::Approx(12.7));
  m.kinematics.transition_speed_ratio = 0.25;
  const Timeline t = plan(straight, m);
  CHECK(t.commands[0].exit_speed_mm_s == doctest::Approx(0.25 * 12.7));
  const double a = 1000;
  CHECK(t.total_s == doctest::Approx(trapezoid_time(0, 3.175, 12.7, 50, a) +
                                     trapezoid_time(3.175, 0, 12.7, 50, a)));

  const Timeline sharp = plan(corner(PathMode::Continuous, 0.001, 6000), m);
  CHECK(sharp.commands[0].exit_speed_mm_s == doctest::Approx(corner_speed(a, 0.001)));
  const Timeline to_rapid = plan({feed(at(0, 0), at(50, 0), 762), rapid(at(50, 0), at(100, 0))}, m);
  CHECK(to_rapid.commands[0].exit_speed_mm_s == doctest::Approx(12.7));
}

TEST_CASE("lookahead_blocks: at each block's end the control can stop within the blocks it read") {
  // 100 collinear blocks of 0.1 mm at F6000 (100 mm/s), 1 m/s^2: seen whole, the chain
  // accelerates as one move (a peak of 70.7 mm/s at 5 mm). Reading 5 blocks beyond the one it
  // runs, the control ends each block at the speed that stops in those 0.5 mm, 31.6 mm/s; within
  // a block it may go faster (it has 0.6 mm ahead at the block's start) and be back at 31.6 by
  // its end: each middle block is a small trapezoid from 31.6 to 31.6 mm/s.
  std::vector<CanonCommand> program;
  for (int i = 0; i < 100; ++i)
    program.push_back(feed(at(0.1 * i, 0), at(0.1 * (i + 1), 0), 6000));
  MachineProfile m = round_machine();
  const Timeline whole = plan(program, m);
  CHECK(whole.commands[49].exit_speed_mm_s == doctest::Approx(std::sqrt(2 * 1000 * 5.0)));
  m.kinematics.lookahead_blocks = 5;
  const Timeline five = plan(program, m);
  const double v = std::sqrt(2 * 1000 * 0.5);
  double middle = 0;
  for (int i = 10; i < 90; ++i) {
    CHECK(five.commands[i].exit_speed_mm_s == doctest::Approx(v));
    middle += five.commands[i].duration_s;
  }
  const double peak = std::sqrt(v * v + 1000 * 0.1); // up over 0.05 mm and down over 0.05 mm
  CHECK(middle == doctest::Approx(80 * trapezoid_time(v, v, peak, 0.1, 1000)));
  CHECK(middle > 80 * 0.1 / 70.7); // slower than the whole path's peak allows
  CHECK(five.total_s > 1.2 * whole.total_s);
  // More blocks than the program has: the path is seen to its end, as without a limit.
  m.kinematics.lookahead_blocks = 200;
  CHECK(plan(program, m).total_s == doctest::Approx(whole.total_s));
}
