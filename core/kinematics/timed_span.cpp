#include "timed_span.hpp"

#include <algorithm>

namespace ncjoule::kinematics_detail {

void TimedSpan::add(const VelocityProfile& piece) {
  if (count_ == kMaxPieces) return; // callers never charge more (see linuxcnc_path.hpp)
  pieces_[count_++] = piece;
  total_length_ += piece.length();
  total_duration_ += piece.duration();
  begin_s_ = begin_t_ = 0;
  end_s_ = total_length_;
  end_t_ = total_duration_;
}

void TimedSpan::restrict(double begin_fraction, double end_fraction) {
  begin_fraction = std::clamp(begin_fraction, 0.0, 1.0);
  end_fraction = std::clamp(end_fraction, begin_fraction, 1.0);
  begin_s_ = total_length_ * begin_fraction;
  end_s_ = total_length_ * end_fraction;
  begin_t_ = whole_time_at(begin_s_);
  end_t_ = end_fraction >= 1 ? total_duration_ : whole_time_at(end_s_);
}

double TimedSpan::whole_time_at(double distance) const {
  double t = 0;
  for (int i = 0; i < count_; ++i) {
    const VelocityProfile& p = pieces_[i];
    if (distance <= p.length() || i + 1 == count_) return t + p.time_at(distance);
    distance -= p.length();
    t += p.duration();
  }
  return t;
}

double TimedSpan::whole_distance_at(double t) const {
  double s = 0;
  for (int i = 0; i < count_; ++i) {
    const VelocityProfile& p = pieces_[i];
    if (t <= p.duration() || i + 1 == count_) return s + p.distance_at(t);
    t -= p.duration();
    s += p.length();
  }
  return s;
}

double TimedSpan::whole_speed_at(double t) const {
  for (int i = 0; i < count_; ++i) {
    const VelocityProfile& p = pieces_[i];
    if (t < p.duration() || i + 1 == count_) return p.speed_at(t);
    t -= p.duration();
  }
  return 0;
}

double TimedSpan::time_at(double distance) const {
  return std::clamp(whole_time_at(begin_s_ + distance) - begin_t_, 0.0, duration());
}

double TimedSpan::distance_at(double t) const {
  return std::clamp(whole_distance_at(begin_t_ + t) - begin_s_, 0.0, length());
}

double TimedSpan::speed_at(double t) const {
  return whole_speed_at(std::clamp(begin_t_ + t, begin_t_, end_t_));
}

double TimedSpan::peak_speed() const {
  // A piecewise-linear or S-shaped speed peaks where one of its pieces starts or ends.
  double peak = std::max(entry_speed(), exit_speed());
  double offset = 0;
  for (int i = 0; i < count_; ++i) {
    const VelocityProfile& p = pieces_[i];
    for (int k = 0; k < p.piece_count(); ++k) {
      const double t = offset + p.piece_start(k);
      if (t > begin_t_ && t < end_t_) peak = std::max(peak, whole_speed_at(t));
    }
    offset += p.duration();
  }
  return peak;
}

} // namespace ncjoule::kinematics_detail
