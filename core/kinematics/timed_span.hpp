// The stretch of timed path one command is charged with. Usually the whole speed profile of its
// move; under the LinuxCNC rule a blend arc and the rest of the move (two profiles back to
// back), or a share of a move merged from several lines. Distances and times are counted from
// the start of the stretch.
#pragma once

#include <array>

#include "velocity_profile.hpp"

namespace ncjoule::kinematics_detail {

class TimedSpan {
public:
  // An arc the naive-CAM detector split runs over four: the blend arc into the first segment,
  // that segment, the blend arc between, and the second (linuxcnc_path.hpp).
  static constexpr int kMaxPieces = 4;

  TimedSpan() = default;
  explicit TimedSpan(const VelocityProfile& whole) { add(whole); }

  // Appends a profile that starts where the previous one ends (at its exit speed).
  void add(const VelocityProfile& piece);
  // Keeps only the part between two fractions of the total length (0 <= begin <= end <= 1).
  void restrict(double begin_fraction, double end_fraction);

  double length() const { return end_s_ - begin_s_; }
  double duration() const { return end_t_ - begin_t_; }
  double entry_speed() const { return speed_at(0); }
  double exit_speed() const { return speed_at(duration()); }
  double peak_speed() const;

  double time_at(double distance) const;
  double distance_at(double t) const;
  double speed_at(double t) const;

private:
  // On the concatenation of all pieces.
  double whole_time_at(double distance) const;
  double whole_distance_at(double t) const;
  double whole_speed_at(double t) const;

  std::array<VelocityProfile, kMaxPieces> pieces_; // the first count_ are set
  int count_ = 0;
  double total_length_ = 0, total_duration_ = 0;
  double begin_s_ = 0, end_s_ = 0, begin_t_ = 0, end_t_ = 0;
};

} // namespace ncjoule::kinematics_detail
