#include "junction.hpp"

#include <algorithm>
#include <cmath>

namespace ncjoule::kinematics_detail {

double junction_speed(const MoveLimits& before, const MoveLimits& after, PathMode mode,
                      double tolerance, const Kinematics& machine) {
  if (machine.exact_stop_every_block || mode != PathMode::Continuous) return 0;
  double cap = std::min(before.vmax, after.vmax);
  if (!before.traverse && !after.traverse) cap *= machine.transition_speed_ratio;
  if (machine.junction_rule == JunctionRule::NextFeed) return cap;
  // Moves of rotary axes only have no direction in space: stop, as their tangents are unknown.
  if (before.rotary_only || after.rotary_only) return 0;

  const double cos_turn = std::clamp(before.dir_out.dot(after.dir_in), -1.0, 1.0);
  if (cos_turn >= 1 - 1e-12) return cap; // straight on
  if (cos_turn <= -1 + 1e-12) return 0;  // reversal
  // Blend arc tangent to both moves whose middle stays within `tolerance` of the corner: with
  // half the corner's interior angle alpha, its radius is R = tol * sin(alpha) / (1 - sin(alpha)),
  // and the centripetal limit v^2 / R <= a gives the speed.
  if (tolerance <= 0) tolerance = machine.path_tolerance_mm;
  if (tolerance <= 0) return 0;
  const double sin_half_interior = std::sqrt(0.5 * (1 + cos_turn));
  const double radius = tolerance * sin_half_interior / (1 - sin_half_interior);
  const double accel = std::min(before.accel, after.accel);
  return std::min(cap, std::sqrt(accel * radius));
}

} // namespace ncjoule::kinematics_detail
