// Look-ahead over the motion stream: entry and exit speeds such that every move can slow down in
// time for everything after it (backward pass) and speed up only as fast as it can (forward
// pass). The stream is planned in windows: a stretch is final once the look-ahead reaches an item
// whose entry speed its own limits fix, whatever comes after it.
#pragma once

#include <cstddef>
#include <deque>

namespace ncjoule::kinematics_detail {

struct SpeedPlanItem {
  // Inputs.
  double length = 0;
  double vmax = 0;
  double accel = 0;
  double jerk = 0;
  double junction_after = 0; // highest speed at the junction with the next item; 0 = stop there
  bool linear_ramp = false;  // LinuxCNC rule: a ramp from entry to exit speed if it is short
  // Results.
  double entry = 0;
  double exit = 0;
};

// The items still in play, numbered from the start of the program. Items leave from the front
// once their speeds are final and every command charged with them has been timed; the last item
// always stays (the next move may still change its junction speed).
class ItemWindow {
public:
  std::size_t size() const { return first_ + items_.size(); } // one past the last item's number
  bool empty() const { return items_.empty(); }
  std::size_t first() const { return first_; } // number of the oldest item kept
  SpeedPlanItem& operator[](std::size_t number) { return items_[number - first_]; }
  const SpeedPlanItem& operator[](std::size_t number) const { return items_[number - first_]; }
  SpeedPlanItem& back() { return items_.back(); }
  void push_back(const SpeedPlanItem& item) { items_.push_back(item); }
  // Drops the items numbered below `number`, keeping at least the last one.
  void drop_before(std::size_t number) {
    while (first_ < number && items_.size() > 1) {
      items_.pop_front();
      ++first_;
    }
  }

private:
  std::deque<SpeedPlanItem> items_;
  std::size_t first_ = 0;
};

// The planned part of a window and what the rest starts from.
struct SpeedPlanFront {
  std::size_t final_items = 0; // items numbered below this have their final speeds
  double junction_before = 0;  // junction speed into the first item not final yet
  double exit_before = 0;      // exit speed of the item before it
};

// Plans the items from front.final_items on, with the path ending at rest after the last item,
// and moves the front on: to the end when `at_end`, else up to the last item whose entry speed
// its own limits (junction into it, its speed limit) fix, whatever the items after it do, and
// never into the last `hold` items (a control's look-ahead depth: their exits still wait for the
// items after them). Returns the number of items its passes visited (the caller keeps the
// total linear).
std::size_t plan_speeds(ItemWindow& items, SpeedPlanFront& front, bool at_end,
                        std::size_t hold = 0);

} // namespace ncjoule::kinematics_detail
