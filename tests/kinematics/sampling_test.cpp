// The sampled path: bounded steps in space and time, on the arc, at the profile's times.
#include <cmath>
#include <doctest/doctest.h>

#include "test_helpers.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

double distance(const Pose& a, const Pose& b) {
  return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) +
                   (a.z - b.z) * (a.z - b.z));
}

void check_ordered(const TimedCommand& c) {
  REQUIRE(c.samples.size() >= 2);
  CHECK(c.samples.front().u == 0);
  CHECK(c.samples.back().u == 1);
  CHECK(c.samples.front().t_s == doctest::Approx(c.start_s));
  CHECK(c.samples.back().t_s == doctest::Approx(c.start_s + c.duration_s));
  for (std::size_t i = 1; i < c.samples.size(); ++i) {
    CHECK(c.samples[i].t_s >= c.samples[i - 1].t_s);
    CHECK(c.samples[i].u > c.samples[i - 1].u);
  }
}

} // namespace

TEST_CASE("without a step only the end points are sampled") {
  const Timeline t = plan({feed(at(0, 0), at(10, 0), 600)}, round_machine());
  CHECK(t.commands[0].samples.size() == 2);
}

TEST_CASE("line samples: step bounded in space and time, times from the trapezoid") {
  PlanOptions o;
  o.max_sample_step_mm = 0.7;
  o.max_sample_dt_s = 0.05;
  const double v = 20, a = 1000, length = 30;
  const Timeline t = plan({feed(at(1, 2), at(1 + length, 2), v * 60)}, round_machine(), o);
  const TimedCommand& c = t.commands[0];
  check_ordered(c);
  for (std::size_t i = 1; i < c.samples.size(); ++i) {
    CHECK(distance(c.samples[i].position, c.samples[i - 1].position) <= 0.7 + 1e-9);
    CHECK(c.samples[i].t_s - c.samples[i - 1].t_s <= 0.05 + 1e-9);
  }
  // Time at distance s of a rest-to-rest trapezoid, worked out piece by piece.
  const double ramp = v * v / (2 * a);
  for (const MotionSample& s : c.samples) {
    const double d = s.u * length;
    double expected;
    if (d <= ramp)
      expected = std::sqrt(2 * d / a);
    else if (d <= length - ramp)
      expected = v / a + (d - ramp) / v;
    else
      expected = c.duration_s - std::sqrt(2 * (length - d) / a);
    CHECK(s.t_s == doctest::Approx(expected).epsilon(1e-9));
    CHECK(s.position.x == doctest::Approx(1 + d));
    CHECK(s.speed_mm_s <= v + 1e-9);
  }
}

TEST_CASE("arc samples follow the arc, not its chord") {
  PlanOptions o;
  o.max_sample_step_mm = 0.5;
  const double r = 10;
  const Timeline t = plan({arc(at(r, 0), at(-r, 0), 0, 0, 1, 1200)}, round_machine(), o);
  const TimedCommand& c = t.commands[0];
  check_ordered(c);
  CHECK(c.samples.size() >= 3.14159 * r / 0.5);
  for (std::size_t i = 0; i < c.samples.size(); ++i) {
    const Pose& p = c.samples[i].position;
    CHECK(std::hypot(p.x, p.y) == doctest::Approx(r));
    CHECK(p.y >= -1e-9); // counter-clockwise from +X to -X passes through +Y
    if (i > 0) CHECK(distance(p, c.samples[i - 1].position) <= 0.5 + 1e-9);
  }
}

TEST_CASE("S-curve samples are consistent with their speeds") {
  MachineProfile m = round_machine();
  m.kinematics.feed_profile = FeedProfile::SCurve;
  for (AxisLimits& a : m.kinematics.axes)
    a.jerk_mm_s3 = 5000;
  PlanOptions o;
  o.max_sample_step_mm = 0.05;
  const Timeline t = plan({feed(at(0, 0), at(20, 0), 3000)}, m, o);
  const TimedCommand& c = t.commands[0];
  check_ordered(c);
  // Distance between samples against the trapezoidal rule on the sampled speeds: with jerk j
  // the rule's error is at most j * dt^3 / 12.
  const double jerk = 5000;
  for (std::size_t i = 1; i < c.samples.size(); ++i) {
    const MotionSample &p = c.samples[i - 1], &q = c.samples[i];
    const double dt = q.t_s - p.t_s;
    const double ds = distance(p.position, q.position);
    CHECK(std::abs(ds - 0.5 * (p.speed_mm_s + q.speed_mm_s) * dt) <=
          jerk * dt * dt * dt / 12 + 1e-9);
  }
}

TEST_CASE("a move asks for more samples than allowed: they thin out, ends and order kept") {
  PlanOptions o;
  o.max_sample_step_mm = 0.01; // 100 m / 0.01 mm would be ten million samples
  o.max_sample_dt_s = 0.001;
  o.max_samples_per_move = 50;
  const Timeline t = plan({feed(at(0, 0), at(100000, 0), 600)}, round_machine(), o);
  const TimedCommand& c = t.commands[0];
  check_ordered(c);
  // 50 intervals in space, each with at most 50 / 50 = 1 in time: 51 samples.
  CHECK(c.samples.size() <= 51);
  CHECK(c.samples.back().position.x == doctest::Approx(100000));
}
