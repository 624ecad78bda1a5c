// The path LinuxCNC 2.9 would run for a program, as look-ahead items for plan_speeds(): its
// segments (moves shortened by blend arcs, G1s merged by the naive-CAM detector), the blend
// arcs between them, each with LinuxCNC's speed and acceleration limits and its junction speed.
//
// Commands go in one at a time, in program order; a segment is settled (and its items written)
// once the move after it has arrived or the queue empties, so memory does not grow with the
// program. Each move command is then told which items it is charged with:
//  - its own segment, and the blend arc before it (LinuxCNC charges a blend arc to the line it
//    leads into); when a blend consumed what was left of the move, the part of that blend arc
//    that runs the rest instead of its own segment (LinuxCNC charges all of the arc to the next
//    line, leaving the move with no time);
//  - a share of the merged segment, in proportion to length, when several G1s were merged
//    (LinuxCNC reports all of it on the last one; sharing keeps time and energy on every line
//    that removes material).
// The programmed path (what removal sees) is not changed; only its timing is.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "linuxcnc_blend.hpp"
#include "linuxcnc_naive_cam.hpp"
#include "lookahead.hpp"
#include "warnings.hpp"

namespace ncjoule::kinematics_detail::linuxcnc {

// What one move command is charged with: `count` consecutive items from `first` (0 to 2, up to 4
// for an arc split over two segments), and of their total length the part between the fractions
// `begin` and `end`.
struct Charge {
  std::uint32_t first = 0;
  std::uint16_t count = 0;
  float begin = 0, end = 1;
};

class PathBuilder {
public:
  using ChargeSink = std::function<void(std::size_t command, const Charge&)>;
  PathBuilder(const Kinematics& machine, ItemWindow& items, ChargeSink sink);

  // A move LinuxCNC's planner queues (G0, G1, G2/G3 with a length). `limits`, where given, are
  // move_limits(c): a line sent as it is needs them again, not worked out twice.
  void move(std::size_t index, const CanonCommand& c, const MoveLimits* limits = nullptr);
  // Any other command: a new F, G61/G64 or G93/G94 ends a naive-CAM group; the commands task
  // waits on (spindle, coolant, tool change, dwell, offsets, messages, stops) empty the queue.
  // True for those: task runs them with the machine at rest (kTaskLatency_s each).
  bool event(const CanonCommand& c);
  // The path comes to rest for a reason of ncjoule's own (a probe, a dog-leg rapid).
  void stop();
  // End of the program.
  void finish() { stop(); }
  // The oldest item a move still to be charged may be charged with.
  std::size_t oldest_item_in_use() const {
    std::size_t oldest = pending_arc_in_ ? *pending_arc_in_ : items_.size();
    if (open_charge_) oldest = std::min<std::size_t>(oldest, open_charge_->first);
    return oldest;
  }

private:
  // A straight move as the planner receives it; `limits`: the line's move_limits, where known.
  void send(MergedLine&& line, const MoveLimits* limits = nullptr);
  void queue(Segment&& s, std::vector<Member>&& members);
  // `continues`: the last line charged with the pending segment goes on in the next one.
  void settle(std::optional<Segment> blend, bool consumed, double consumed_length, double exit_cap,
              bool continues);
  std::uint32_t push(const Segment& s, double exit_cap);
  Segment line_segment(const CanonCommand& state_from, const Pose& start, const Pose& end,
                       const MoveLimits* limits) const;
  Segment circle_segment(const CanonCommand& c) const;
  void apply_state(Segment& s, const CanonCommand& c);

  const Kinematics& machine_;
  ItemWindow& items_;
  mutable Warnings scratch_; // plan() has reported the moves' warnings already
  ChargeSink sink_;
  AxisBounds feed_bounds_, rapid_bounds_;
  NaiveCam naive_cam_;
  double naive_tolerance_ = 0;
  bool path_mode_programmed_ = false; // a G61, G61.1 or G64 of the program's own
  bool startup_tolerance_ = false;    // G64 P0.001 inch, from a canned cycle before any of them
  double feed_rate_ = -1;             // last F, to see changes
  bool atspeed_next_feed_ = false;    // a spindle start waits for speed at the next feed move
  int work_index_ = 1;                // G54..G59.3 in force, and its offset
  Pose work_offset_;
  // The segment waiting for its successor, the lines charged with it, its blend arc in.
  std::optional<Segment> pending_;
  std::vector<Member> pending_members_;
  std::optional<std::uint32_t> pending_arc_in_;
  double arc_in_skip_ = 0; // mm at the start of that arc that run the move before
  // An arc the naive-CAM detector split over two segments (its middle point closed one group, its
  // end opened the next, as emccanon's see_segment does): charged once, when the second segment
  // settles, with everything from where it began in the first.
  struct OpenCharge {
    std::size_t command = 0;
    std::uint32_t first = 0; // the first item of the first segment's charge
    double begin_mm = 0;     // where the arc begins, from the start of that item
  };
  std::optional<OpenCharge> open_charge_;
  bool flowing_ = false; // the last item written runs on into the next one
  double exit_cap_ = 0;  // its own limit at that junction
};

} // namespace ncjoule::kinematics_detail::linuxcnc
