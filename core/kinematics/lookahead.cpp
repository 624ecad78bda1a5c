#include "lookahead.hpp"

#include <algorithm>

#include "velocity_profile.hpp"

namespace ncjoule::kinematics_detail {

void plan_speeds(std::vector<SpeedPlanItem>& items) {
  const std::size_t n = items.size();
  // Backward: the fastest each move may enter and still reach the speed the moves after it allow.
  double next_entry = 0;
  for (std::size_t i = n; i-- > 0;) {
    SpeedPlanItem& m = items[i];
    m.exit = std::min(m.junction_after, next_entry);
    const double entry_limit = i > 0 ? items[i - 1].junction_after : 0.0;
    m.entry = std::min({entry_limit, m.vmax, reachable_speed(m.exit, m.length, m.accel, m.jerk)});
    next_entry = m.entry;
  }
  // Forward: no faster than each move can reach from its entry speed.
  double previous_exit = 0;
  for (SpeedPlanItem& m : items) {
    m.entry = std::min(m.entry, previous_exit);
    m.exit = std::min({m.exit, m.vmax, reachable_speed(m.entry, m.length, m.accel, m.jerk)});
    previous_exit = m.exit;
  }
}

} // namespace ncjoule::kinematics_detail
