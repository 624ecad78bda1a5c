#include "lookahead.hpp"

#include <algorithm>

#include "velocity_profile.hpp"

namespace ncjoule::kinematics_detail {

std::size_t plan_speeds(ItemWindow& items, SpeedPlanFront& front, bool at_end, std::size_t hold) {
  const std::size_t from = front.final_items;
  const std::size_t end = items.size();
  if (from >= end) return 0;
  // Backward, as if the path stopped after the last item: the fastest each item may enter and
  // still reach the speed the items after it allow. An item whose entry is held by its own cap,
  // whatever speed it may yet have to leave at, keeps it whatever follows, and so does
  // everything before it. Without jerk a later item can only raise the exit speeds, so the cap
  // need only be within reach of the present exit; with jerk the reach is not monotone in the
  // exit speed (velocity_profile.hpp), so the cap must be within reach of any.
  std::size_t fixed = from; // the highest such item found, if above `from`
  double next_entry = 0;
  for (std::size_t i = end; i-- > from;) {
    SpeedPlanItem& m = items[i];
    m.exit = std::min(m.junction_after, next_entry);
    const double cap =
        std::min(i > from ? items[i - 1].junction_after : front.junction_before, m.vmax);
    const double reach = reachable_speed(m.exit, m.length, m.accel, m.jerk);
    m.entry = std::min(cap, reach);
    if (fixed == from && i > from && cap <= reach &&
        (m.jerk <= 0 || cap <= lowest_reachable_speed(m.length, m.accel, m.jerk)))
      fixed = i;
    next_entry = m.entry;
  }
  const std::size_t final_end =
      at_end ? end : std::max(from, std::min(fixed, end - std::min(end, hold)));
  // Forward, over what is final: no faster than each item can reach from its entry speed.
  double previous_exit = front.exit_before;
  for (std::size_t i = from; i < final_end; ++i) {
    SpeedPlanItem& m = items[i];
    m.entry = std::min(m.entry, previous_exit);
    m.exit = std::min({m.exit, m.vmax, reachable_speed(m.entry, m.length, m.accel, m.jerk)});
    previous_exit = m.exit;
  }
  const std::size_t visited = (end - from) + (final_end - from);
  if (final_end == from) return visited;
  front.final_items = final_end;
  front.junction_before = items[final_end - 1].junction_after;
  front.exit_before = previous_exit;
  return visited;
}

} // namespace ncjoule::kinematics_detail
