// The velocity profile alone: durations against closed forms, and time_at as the inverse of
// distance_at.
#include <cmath>
#include <doctest/doctest.h>

#include "test_helpers.hpp"
#include "velocity_profile.hpp"

using namespace ncjoule::kinematics_detail;
using ncjoule::test::trapezoid_time;

TEST_CASE("trapezoid rest to rest: accelerate, cruise, decelerate") {
  const double v = 762.0 / 60, a = 1000, length = 254;
  const VelocityProfile p = VelocityProfile::rest_to_rest(v, length, a, 0);
  CHECK(p.duration() == doctest::Approx(length / v + v / a).epsilon(1e-12));
  CHECK(p.peak_speed() == doctest::Approx(v));
  CHECK(p.distance_at(p.duration()) == doctest::Approx(length));
}

TEST_CASE("trapezoid too short to reach its speed is a triangle") {
  const double a = 1000, length = 0.05;
  const VelocityProfile p = VelocityProfile::rest_to_rest(100, length, a, 0);
  CHECK(p.peak_speed() == doctest::Approx(std::sqrt(a * length)));
  CHECK(p.peak_speed() < 100);
  CHECK(p.duration() == doctest::Approx(2 * std::sqrt(length / a)));
}

TEST_CASE("trapezoid between two cruise speeds") {
  const VelocityProfile p = VelocityProfile::build(20, 5, 50, 30, 500, 0);
  CHECK(p.entry_speed() == 20);
  CHECK(p.exit_speed() == 5);
  CHECK(p.duration() == doctest::Approx(trapezoid_time(20, 5, 50, 30, 500)));
}

TEST_CASE("S-curve with full ramps takes a/j longer than the trapezoid") {
  const double v = 100, a = 1000, j = 20000, length = 100;
  REQUIRE(v * j >= a * a); // the ramps reach full acceleration
  const VelocityProfile p = VelocityProfile::rest_to_rest(v, length, a, j);
  CHECK(p.duration() == doctest::Approx(length / v + v / a + a / j));
  CHECK(p.distance_at(p.duration()) == doctest::Approx(length));
}

TEST_CASE("S-curve too short for its speed: peak found, distance exact") {
  const double a = 1000, j = 20000, length = 0.5;
  const VelocityProfile p = VelocityProfile::rest_to_rest(200, length, a, j);
  CHECK(p.peak_speed() < 200);
  CHECK(speed_change_distance(0, p.peak_speed(), a, j) * 2 == doctest::Approx(length));
  CHECK(p.distance_at(p.duration()) == doctest::Approx(length));
}

TEST_CASE("time_at inverts distance_at on every piece") {
  for (double jerk : {0.0, 5000.0}) {
    const VelocityProfile p = VelocityProfile::build(3, 7, 40, 12, 300, jerk);
    for (int k = 0; k <= 100; ++k) {
      const double t = p.duration() * k / 100.0;
      CHECK(p.time_at(p.distance_at(t)) == doctest::Approx(t).epsilon(1e-9));
    }
  }
}

TEST_CASE("reachable speed is the inverse of the ramp distance") {
  // Short and long distances, from rest and from speed: both regimes of the jerk-limited ramp.
  for (double jerk : {0.0, 20000.0})
    for (double v0 : {0.0, 10.0})
      for (double length : {1e-4, 0.01, 3.0, 500.0}) {
        CAPTURE(jerk);
        CAPTURE(v0);
        CAPTURE(length);
        const double v1 = reachable_speed(v0, length, 1000, jerk);
        CHECK(v1 > v0);
        CHECK(speed_change_distance(v0, v1, 1000, jerk) == doctest::Approx(length).epsilon(1e-9));
      }
}

TEST_CASE("with jerk the reachable speed is not monotone in the start speed: its lowest is found") {
  // 0.5 mm at 10,000 mm/s^3: from rest a ramp gains 13.6 mm/s, from 7.07 mm/s only 6.1.
  CHECK(reachable_speed(0, 0.5, 1000, 10000) > reachable_speed(7.066, 0.5, 1000, 10000) + 0.3);
  for (const double jerk : {0.0, 2000.0, 10000.0, 1e6})
    for (const double length : {0.05, 0.5, 5.0, 50.0}) {
      CAPTURE(jerk);
      CAPTURE(length);
      const double lowest = lowest_reachable_speed(length, 1000, jerk);
      double swept = reachable_speed(0, length, 1000, jerk);
      for (double v0 = 0; v0 <= 400; v0 += 0.01) {
        const double v = reachable_speed(v0, length, 1000, jerk);
        CHECK(lowest <= v * (1 + 1e-12));
        swept = std::min(swept, v);
      }
      CHECK(lowest == doctest::Approx(swept).epsilon(1e-6));
    }
}
