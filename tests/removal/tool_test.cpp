// Tool profiles: lower envelopes and section radii.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "fixture.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("tool lower envelopes") {
  const Tool flat = flat_end_mill(1, 10);
  CHECK(flat.envelope_height(0) == 0);
  CHECK(flat.envelope_height(5) == 0);
  CHECK(std::isinf(flat.envelope_height(5.01)));

  const Tool ball = ball_end_mill(2, 10);
  CHECK(ball.envelope_height(0) == 0);
  CHECK(ball.envelope_height(3) == doctest::Approx(5 - 4)); // 3-4-5 triangle
  CHECK(ball.envelope_height(5) == doctest::Approx(5));

  Tool bull = flat_end_mill(3, 10);
  bull.shape = ToolShape::BullNose;
  bull.corner_radius_mm = 1;
  CHECK(bull.envelope_height(4) == 0);
  CHECK(bull.envelope_height(5) == doctest::Approx(1));
  CHECK(bull.envelope_height(4.6) == doctest::Approx(1 - 0.8));

  const Tool d = drill(4, 8, 118);
  CHECK(d.envelope_height(4) == doctest::Approx(4 / std::tan(59 * std::numbers::pi / 180)));

  Tool vbit = flat_end_mill(5, 10);
  vbit.shape = ToolShape::Chamfer;
  vbit.tip_angle_deg = 90;
  vbit.tip_diameter_mm = 1;
  CHECK(vbit.envelope_height(0.5) == 0);
  CHECK(vbit.envelope_height(3.5) == doctest::Approx(3));

  // A 3 mm cutter on a 6 mm shank: beyond the flutes the shank reaches down to 8 mm.
  Tool necked = flat_end_mill(6, 3);
  necked.cutting_length_mm = 8;
  necked.shank_diameter_mm = 6;
  CHECK(necked.reach_radius() == 3);
  CHECK(necked.envelope_height(2) == 8);
  CHECK(std::isinf(necked.envelope_height(3.1)));

  // The section radius inverts the envelope where the profile rises (flat parts excepted, where
  // the section is the whole flat).
  for (const Tool& t : {ball, bull, d, vbit})
    for (double r = 0.6; r < t.radius(); r += 0.17) {
      if (t.envelope_height(r) == 0)
        CHECK(t.section_radius(0) >= r);
      else
        CHECK(t.section_radius(t.envelope_height(r)) == doctest::Approx(r));
    }
}
