// Builds canonical commands, their Timeline and RemovalResult by hand, so energy tests do not
// depend on the planner and removal stages.
#pragma once

#include <vector>

#include "ncjoule/gcode.hpp"
#include "ncjoule/kinematics.hpp"
#include "ncjoule/removal.hpp"

namespace ncjoule::test {

class ProgramBuilder {
public:
  std::vector<CanonCommand> commands;
  Timeline timeline;
  RemovalResult removal;
  double sample_dt_s = 0.02; // time between samples of a move

  // Spindle to rpm (0 stops it), taking ramp_s seconds.
  void spindle(double rpm, double ramp_s = 0);
  void coolant(bool on);
  void dwell(double seconds);
  void tool_change(int tool, double seconds);
  // Straight move to `to` at `feed_mm_s`; accel 0 means constant speed from start to end. The
  // removed cross-section `area_mm2` makes every step remove area * step length.
  void move(CanonKind kind, const Pose& to, double feed_mm_s, double area_mm2 = 0,
            double accel_mm_s2 = 0);
  void traverse(const Pose& to, double speed_mm_s, double accel_mm_s2 = 0) {
    move(CanonKind::Traverse, to, speed_mm_s, 0, accel_mm_s2);
  }
  void feed(const Pose& to, double feed_mm_s, double area_mm2 = 0, double accel_mm_s2 = 0) {
    move(CanonKind::Feed, to, feed_mm_s, area_mm2, accel_mm_s2);
  }

  const Pose& position() const { return position_; }
  double now() const { return now_; }

private:
  void append(CanonCommand command, TimedCommand timed, CommandRemoval removed);

  ModalState state_;
  Pose position_;
  double now_ = 0;
};

} // namespace ncjoule::test
