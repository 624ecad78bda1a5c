// The speed of one move over time: a trapezoid (acceleration limited) or an S-curve (jerk
// limited), built from up to seven pieces of constant jerk, with the exact distance, speed and
// inverse (time at a distance) of each piece.
#pragma once

#include <array>

namespace ncjoule::kinematics_detail {

// Time to change speed by dv (>= 0) from zero acceleration to zero acceleration.
// jerk <= 0 means no jerk limit (a step in acceleration, as in a trapezoid).
double speed_change_time(double dv, double accel, double jerk);
// Distance covered while changing speed from v0 to v1 (either direction). The ramp is
// symmetric in time, so the mean speed is (v0 + v1) / 2.
double speed_change_distance(double v0, double v1, double accel, double jerk);
// The highest speed reachable from v0 (or the highest from which v0 is reachable when
// slowing down) within `length`.
double reachable_speed(double v0, double length, double accel, double jerk);
// The lowest reachable_speed() over `length` from any v0 >= 0. Without jerk it is the speed
// reached from rest. With jerk it is lower: a ramp that starts and ends at zero acceleration
// covers its distance sooner from a higher speed and so gains less, and reaching from 7 mm/s can
// end below reaching from rest (0.5 mm at 10,000 mm/s^3: 13.2 against 13.6 mm/s).
double lowest_reachable_speed(double length, double accel, double jerk);

class VelocityProfile {
public:
  // A move of `length` entering at v0 and leaving at v1 (both reachable within length, as the
  // look-ahead guarantees), never faster than vmax. jerk <= 0 gives a trapezoid.
  static VelocityProfile build(double v0, double v1, double vmax, double length, double accel,
                               double jerk);
  // Constant acceleration from v0 to v1 over `length`, whatever the acceleration limit: the
  // linear speed ramp LinuxCNC gives segments that take less than a few servo cycles.
  static VelocityProfile ramp(double v0, double v1, double length);
  // Rest-to-rest convenience.
  static VelocityProfile rest_to_rest(double vmax, double length, double accel, double jerk) {
    return build(0, 0, vmax, length, accel, jerk);
  }

  double duration() const { return duration_; }
  double length() const { return length_; }
  double peak_speed() const { return peak_; }
  double entry_speed() const { return entry_; }
  double exit_speed() const { return exit_; }

  double distance_at(double t) const;
  double speed_at(double t) const;
  double time_at(double distance) const;
  // Start times of the pieces (for finding the peaks of combined profiles).
  int piece_count() const { return count_; }
  double piece_start(int i) const { return pieces_[i].t0; }

private:
  // A profile of no length between `v0` and `v1` (negative speeds read as 0), to add phases to.
  static VelocityProfile between(double v0, double v1);
  struct Piece {
    double t0, s0, v0, a0, jerk, duration;
  };
  void add_speed_change(double from, double to, double accel, double jerk);
  void add_cruise(double speed, double distance);
  void add(double a0, double jerk, double duration);
  int piece_at_time(double t) const;

  // Only the first count_ are set, and only they are read: a planner builds and copies millions
  // of profiles (four in each span of a move), and zeroing the rest was a tenth of its work.
  std::array<Piece, 7> pieces_;
  int count_ = 0;
  double duration_ = 0, length_ = 0, peak_ = 0, entry_ = 0, exit_ = 0;
  // Running end state while building.
  double end_s_ = 0, end_v_ = 0;
};

} // namespace ncjoule::kinematics_detail
