// Whole-planner results on moves whose time can be worked out by hand.
#include <cmath>
#include <doctest/doctest.h>
#include <numbers>

#include "test_helpers.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("254 mm at 762 mm/min from rest to rest with 1 m/s^2 takes 20.0127 s") {
  const Timeline t = plan({feed(at(0, 0), at(254, 0), 762)}, round_machine());
  REQUIRE(t.commands.size() == 1);
  CHECK(t.total_s == doctest::Approx(20.0127).epsilon(1e-6));
  CHECK(t.commands[0].entry_speed_mm_s == 0);
  CHECK(t.commands[0].exit_speed_mm_s == 0);
  CHECK(t.commands[0].peak_speed_mm_s == doctest::Approx(762.0 / 60));
}

TEST_CASE("a short move never reaches its feed") {
  const double length = 0.5, a = 1000, v = 6000.0 / 60;
  const Timeline t = plan({feed(at(0, 0), at(0, length), 6000)}, round_machine());
  CHECK(t.commands[0].peak_speed_mm_s == doctest::Approx(std::sqrt(a * length)));
  CHECK(t.commands[0].peak_speed_mm_s < v);
  CHECK(t.total_s == doctest::Approx(2 * std::sqrt(length / a)));
}

TEST_CASE("a diagonal move is held to the slowest axis along its direction") {
  MachineProfile m = round_machine();
  m.kinematics.axes[0].max_feed_mm_s = 10; // X slow
  m.kinematics.axes[0].accel_mm_s2 = 200;
  const double dx = 30, dy = 40, length = 50; // direction (0.6, 0.8)
  const Timeline t = plan({feed(at(0, 0), at(dx, dy), 6000)}, m);
  const double v = 10 / (dx / length), a = std::min(200 / 0.6, 1000 / 0.8);
  CHECK(t.commands[0].peak_speed_mm_s == doctest::Approx(v));
  CHECK(t.total_s == doctest::Approx(trapezoid_time(0, 0, v, length, a)));
}

TEST_CASE("arc speed is capped by the centripetal acceleration v^2/r <= a") {
  const double r = 2.5, a = 1000;
  // Half circle, counter-clockwise, at a feed far above the centripetal limit.
  const Timeline t = plan({arc(at(r, 0), at(-r, 0), 0, 0, 1, 6000)}, round_machine());
  const double v = std::sqrt(a * r), length = std::numbers::pi * r;
  REQUIRE(v < 100);
  CHECK(t.commands[0].length_mm == doctest::Approx(length));
  CHECK(t.commands[0].peak_speed_mm_s == doctest::Approx(v));
  CHECK(t.total_s == doctest::Approx(trapezoid_time(0, 0, v, length, a)));
}

TEST_CASE("arc below the centripetal limit runs at its feed") {
  const double r = 50;
  const Timeline t = plan({arc(at(r, 0), at(0, r), 0, 0, 1, 600)}, round_machine());
  CHECK(t.commands[0].peak_speed_mm_s == doctest::Approx(10));
  CHECK(t.total_s == doctest::Approx(trapezoid_time(0, 0, 10, std::numbers::pi * r / 2, 1000)));
}

TEST_CASE("linear rapids move all axes on one line, dog-leg rapids each at its own rate") {
  MachineProfile m = round_machine();
  auto& x = m.kinematics.axes[0];
  auto& y = m.kinematics.axes[1];
  x.rapid_mm_s = 10000.0 / 60;
  y.rapid_mm_s = 5000.0 / 60;
  y.accel_mm_s2 = 100; // Y limits the line by its acceleration, X by its speed
  const double dx = 100, dy = 20, length = std::hypot(dx, dy);
  const std::vector<CanonCommand> program{rapid(at(0, 0), at(dx, dy))};

  m.kinematics.rapid_mode = RapidMode::Linear;
  const Timeline linear = plan(program, m);
  const double v = x.rapid_mm_s * length / dx;
  const double a = std::min(x.accel_mm_s2 * length / dx, y.accel_mm_s2 * length / dy);
  CHECK(linear.total_s == doctest::Approx(trapezoid_time(0, 0, v, length, a)));

  m.kinematics.rapid_mode = RapidMode::DogLeg;
  const Timeline dog_leg = plan(program, m);
  const double t_x = trapezoid_time(0, 0, x.rapid_mm_s, dx, x.accel_mm_s2);
  REQUIRE(y.rapid_mm_s * y.rapid_mm_s / y.accel_mm_s2 > dy); // Y never reaches its rapid rate
  const double t_y = 2 * std::sqrt(dy / y.accel_mm_s2);
  CHECK(dog_leg.total_s == doctest::Approx(std::max(t_x, t_y)));
  CHECK(dog_leg.total_s < linear.total_s);
}

TEST_CASE("dog-leg samples leave the straight line") {
  MachineProfile m = round_machine();
  m.kinematics.rapid_mode = RapidMode::DogLeg;
  PlanOptions o;
  o.max_sample_step_mm = 1;
  const Timeline t = plan({rapid(at(0, 0), at(100, 10))}, m);
  const Timeline sampled = plan({rapid(at(0, 0), at(100, 10))}, m, o);
  REQUIRE(sampled.commands[0].samples.size() > 10);
  bool off_chord = false;
  for (const MotionSample& s : sampled.commands[0].samples)
    off_chord |= std::abs(s.position.y - s.position.x / 10) > 1;
  CHECK(off_chord); // Y arrives long before X
  CHECK(sampled.total_s == doctest::Approx(t.total_s));
}

TEST_CASE("G93 inverse time: the move is planned to take 60/F seconds at speed") {
  CanonCommand c = feed(at(0, 0), at(50, 0), 2); // F2: 30 s
  c.state.feed_mode = FeedMode::InverseTime;
  const Timeline t = plan({c}, round_machine());
  const double v = 50.0 / 30;
  CHECK(t.commands[0].peak_speed_mm_s == doctest::Approx(v));
  CHECK(t.total_s == doctest::Approx(30 + v / 1000));
}

TEST_CASE("G95 feed per revolution: F mm/rev times the spindle speed") {
  CanonCommand c = feed(at(0, 0), at(10, 0), 0.1);
  c.state.feed_mode = FeedMode::UnitsPerRevolution;
  c.state.spindle = SpindleDir::Clockwise;
  c.state.spindle_rpm = 1000;
  const Timeline t = plan({c}, round_machine());
  const double v = 0.1 * 1000 / 60;
  CHECK(t.commands[0].peak_speed_mm_s == doctest::Approx(v));
  CHECK(t.total_s == doctest::Approx(10 / v + v / 1000));

  c.state.spindle = SpindleDir::Off; // no spindle: warned, timed at the maximum feed
  const Timeline stopped = plan({c}, round_machine());
  CHECK(std::isfinite(stopped.total_s));
  CHECK_FALSE(stopped.diagnostics.empty());
}

TEST_CASE("S-curve option: a long move takes a/j longer than the trapezoid") {
  MachineProfile m = round_machine();
  m.kinematics.feed_profile = FeedProfile::SCurve;
  for (AxisLimits& a : m.kinematics.axes)
    a.jerk_mm_s3 = 50000;
  const Timeline t = plan({feed(at(0, 0), at(100, 0), 3000)}, m);
  const double v = 50, a = 1000, j = 50000;
  REQUIRE(v * j >= a * a); // both ramps reach the full acceleration
  CHECK(t.total_s == doctest::Approx(100 / v + v / a + a / j));
}

TEST_CASE("a feed too slow for a double's range is timed at the slowest speed, finitely") {
  // G95 with a spindle speed of 1e-300 rpm: 1e-306 mm/s, a move of 1e300 s and more, and sums
  // of such that overflow. Held to 1e-9 mm/s with a warning.
  CanonCommand slow = feed(at(0, 0), at(100, 0), 0.0001);
  slow.state.feed_mode = FeedMode::UnitsPerRevolution;
  slow.state.spindle = SpindleDir::Clockwise;
  slow.state.spindle_rpm = 1e-300;
  for (const JunctionRule rule : {JunctionRule::Tolerance, JunctionRule::LinuxCnc29}) {
    MachineProfile m = round_machine();
    m.kinematics.junction_rule = rule;
    const Timeline t = plan({slow, slow, slow}, m);
    CHECK(std::isfinite(t.total_s));
    CHECK(t.total_s > 1e11);
    CHECK(t.total_s < 1e12);
    bool warned = false;
    for (const Diagnostic& d : t.diagnostics)
      warned = warned || d.message.find("feed slower than") != std::string::npos;
    CHECK(warned);
  }
}

TEST_CASE("a control's arc acceleration holds small arcs below the axes' centripetal limit") {
  const double r = 1.712, feed = 110 * 25.4; // NIST's plate bores: 0.0674 in at F110 in/min
  MachineProfile m = round_machine();
  for (AxisLimits& a : m.kinematics.axes)
    a.accel_mm_s2 = 2500; // the arc's own limit, sqrt(2500 r) = 65.4 mm/s, is above its F
  const Timeline free_arc = plan({arc(at(r, 0), at(-r, 0), 0, 0, 1, feed)}, m);
  CHECK(free_arc.commands[0].peak_speed_mm_s == doctest::Approx(feed / 60));
  m.kinematics.arc_accel_mm_s2 = 700;
  const Timeline held = plan({arc(at(r, 0), at(-r, 0), 0, 0, 1, feed)}, m);
  CHECK(held.commands[0].peak_speed_mm_s == doctest::Approx(std::sqrt(700 * r)));
  // Above the axes' acceleration the key changes nothing.
  m.kinematics.arc_accel_mm_s2 = 1e5;
  const Timeline above = plan({arc(at(r, 0), at(-r, 0), 0, 0, 1, 6000)}, m);
  CHECK(above.commands[0].peak_speed_mm_s == doctest::Approx(std::sqrt(2500 * r)));
}
