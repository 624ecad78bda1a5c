#include "velocity_profile.hpp"

#include <algorithm>
#include <cmath>

namespace ncjoule::kinematics_detail {
namespace {

// Bisection steps for the S-curve's peak and reachable speeds: 2^-50 of the bracket is far
// below anything a machine can resolve.
constexpr int kBisectionSteps = 50;

double piece_distance(double v0, double a0, double jerk, double tau) {
  return tau * (v0 + tau * (a0 / 2 + tau * jerk / 6));
}
double piece_speed(double v0, double a0, double jerk, double tau) {
  return v0 + tau * (a0 + tau * jerk / 2);
}

} // namespace

double speed_change_time(double dv, double accel, double jerk) {
  dv = std::abs(dv);
  if (jerk <= 0) return dv / accel;
  // Full ramps reach `accel` only when dv >= accel^2 / jerk; below that the ramp is two jerk
  // pieces peaking at sqrt(dv * jerk).
  if (dv * jerk >= accel * accel) return dv / accel + accel / jerk;
  return 2 * std::sqrt(dv / jerk);
}

double speed_change_distance(double v0, double v1, double accel, double jerk) {
  return 0.5 * (v0 + v1) * speed_change_time(v1 - v0, accel, jerk);
}

double reachable_speed(double v0, double length, double accel, double jerk) {
  if (jerk <= 0) return std::sqrt(v0 * v0 + 2 * accel * length);
  if (!(length > 0)) return v0;
  // Solve speed_change_distance(v0, v0 + dv) = length for dv, in the ramp's two regimes.
  const double dv_full = accel * accel / jerk; // smallest change that reaches full acceleration
  if (length <= speed_change_distance(v0, v0 + dv_full, accel, jerk)) {
    // (2 v0 + dv) sqrt(dv / j) = length: with x = sqrt(dv), x^3 + 2 v0 x - length sqrt(j) = 0,
    // which has one real root (Cardano), polished by Newton.
    const double p = 2 * v0, q = -length * std::sqrt(jerk);
    const double root = std::sqrt(q * q / 4 + p * p * p / 27);
    double x = std::cbrt(-q / 2 + root) + std::cbrt(-q / 2 - root);
    for (int i = 0; i < 2; ++i)
      x -= (x * x * x + p * x + q) / (3 * x * x + p);
    return v0 + std::max(0.0, x * x);
  }
  // (2 v0 + dv) / 2 * (dv / a + a / j) = length: a quadratic in dv.
  const double b = dv_full + 2 * v0, c = 2 * v0 * dv_full - 2 * length * accel;
  return v0 + 0.5 * (-b + std::sqrt(b * b - 4 * c));
}

double lowest_reachable_speed(double length, double accel, double jerk) {
  double lowest = reachable_speed(0, length, accel, jerk);
  if (jerk <= 0 || !(length > 0)) return lowest;
  // reachable_speed falls, then rises, with v0 in each regime; the lowest is at a turning point
  // or where the regimes meet. Turning points: without full acceleration where dv = 2 v0, i.e.
  // 32 v0^3 = length^2 jerk; with it at v0 = accel^2 / (2 jerk). The regimes meet where
  // (2 v0 + accel^2 / jerk) accel / jerk = length.
  const double dv_full = accel * accel / jerk;
  const double turn_partial = std::cbrt(length * length * jerk / 32);
  const double turn_full = dv_full / 2;
  const double regimes_meet = std::max(0.0, (length * jerk / accel - dv_full) / 2);
  for (double v0 : {turn_partial, turn_full, regimes_meet})
    lowest = std::min(lowest, reachable_speed(v0, length, accel, jerk));
  return lowest;
}

VelocityProfile VelocityProfile::between(double v0, double v1) {
  VelocityProfile p;
  p.entry_ = std::max(0.0, v0);
  p.exit_ = std::max(0.0, v1);
  p.peak_ = std::max(p.entry_, p.exit_);
  p.end_v_ = p.entry_;
  return p;
}

VelocityProfile VelocityProfile::build(double v0, double v1, double vmax, double length,
                                       double accel, double jerk) {
  VelocityProfile p = between(v0, v1);
  v0 = p.entry_;
  v1 = p.exit_;
  if (!(length > 0) || !(vmax > 0) || !(accel > 0)) return p; // takes no time
  p.length_ = length;
  const double floor_speed = std::max(v0, v1);
  vmax = std::max(vmax, floor_speed);
  auto needed = [&](double peak) {
    return speed_change_distance(v0, peak, accel, jerk) +
           speed_change_distance(peak, v1, accel, jerk);
  };
  if (needed(floor_speed) > length * (1 + 1e-9)) {
    // Entry and exit speeds not reachable within the length (only rounding in the look-ahead
    // gets here): change speed at the constant acceleration that fits exactly.
    p.add((v1 * v1 - v0 * v0) / (2 * length), 0, 2 * length / (v0 + v1));
    p.end_s_ = length;
    p.end_v_ = v1;
    return p;
  }
  double peak = vmax;
  if (needed(vmax) > length) {
    if (jerk <= 0) {
      peak = std::clamp(std::sqrt(accel * length + 0.5 * (v0 * v0 + v1 * v1)), floor_speed, vmax);
    } else {
      double lo = floor_speed, hi = vmax;
      for (int i = 0; i < kBisectionSteps; ++i) {
        const double mid = 0.5 * (lo + hi);
        (needed(mid) <= length ? lo : hi) = mid;
      }
      peak = lo;
    }
  }
  p.peak_ = peak;
  p.add_speed_change(v0, peak, accel, jerk);
  p.add_cruise(peak, length - needed(peak));
  p.add_speed_change(peak, v1, accel, jerk);
  return p;
}

VelocityProfile VelocityProfile::ramp(double v0, double v1, double length) {
  VelocityProfile p = between(v0, v1);
  v0 = p.entry_;
  v1 = p.exit_;
  if (!(length > 0) || !(v0 + v1 > 0)) return p;
  p.length_ = length;
  p.add((v1 * v1 - v0 * v0) / (2 * length), 0, 2 * length / (v0 + v1));
  p.end_s_ = length;
  p.end_v_ = v1;
  return p;
}

void VelocityProfile::add(double a0, double jerk, double duration) {
  if (!(duration > 0)) return;
  pieces_[count_++] = Piece{duration_, end_s_, end_v_, a0, jerk, duration};
  end_s_ += piece_distance(end_v_, a0, jerk, duration);
  end_v_ = piece_speed(end_v_, a0, jerk, duration);
  duration_ += duration;
}

void VelocityProfile::add_speed_change(double from, double to, double accel, double jerk) {
  const double dv = std::abs(to - from);
  if (dv <= 0) return;
  const double sign = to > from ? 1.0 : -1.0;
  if (jerk <= 0) {
    add(sign * accel, 0, dv / accel);
  } else if (dv * jerk >= accel * accel) {
    add(0, sign * jerk, accel / jerk);
    add(sign * accel, 0, dv / accel - accel / jerk);
    add(sign * accel, -sign * jerk, accel / jerk);
  } else {
    const double peak_accel = std::sqrt(dv * jerk);
    add(0, sign * jerk, peak_accel / jerk);
    add(sign * peak_accel, -sign * jerk, peak_accel / jerk);
  }
  end_v_ = to; // no drift from rounding into the next piece
}

void VelocityProfile::add_cruise(double speed, double distance) {
  if (distance > 0 && speed > 0) add(0, 0, distance / speed);
}

int VelocityProfile::piece_at_time(double t) const {
  int i = 0;
  while (i + 1 < count_ && pieces_[i + 1].t0 <= t)
    ++i;
  return i;
}

double VelocityProfile::distance_at(double t) const {
  if (count_ == 0 || t <= 0) return 0;
  if (t >= duration_) return length_;
  const Piece& p = pieces_[piece_at_time(t)];
  const double s = p.s0 + piece_distance(p.v0, p.a0, p.jerk, t - p.t0);
  return std::clamp(s, 0.0, length_);
}

double VelocityProfile::speed_at(double t) const {
  if (count_ == 0) return entry_;
  if (t <= 0) return entry_;
  if (t >= duration_) return exit_;
  const Piece& p = pieces_[piece_at_time(t)];
  return std::max(0.0, piece_speed(p.v0, p.a0, p.jerk, t - p.t0));
}

double VelocityProfile::time_at(double distance) const {
  if (count_ == 0 || distance <= 0) return 0;
  if (distance >= length_) return duration_;
  int i = 0;
  while (i + 1 < count_ && pieces_[i + 1].s0 <= distance)
    ++i;
  const Piece& p = pieces_[i];
  const double ds = distance - p.s0;
  double tau;
  if (p.jerk == 0) {
    // v0*tau + a0/2*tau^2 = ds, in the form that stays accurate when a0 is small or negative.
    const double root = std::sqrt(std::max(0.0, p.v0 * p.v0 + 2 * p.a0 * ds));
    tau = (p.v0 + root) > 0 ? 2 * ds / (p.v0 + root) : 0;
  } else {
    // A cubic, monotonic because the speed is never negative: Newton kept inside a bracket.
    double lo = 0, hi = p.duration;
    tau = 0.5 * (lo + hi);
    for (int k = 0; k < 60; ++k) {
      const double f = piece_distance(p.v0, p.a0, p.jerk, tau) - ds;
      if (std::abs(f) <= 1e-13 * std::max(1.0, length_)) break;
      (f > 0 ? hi : lo) = tau;
      const double v = piece_speed(p.v0, p.a0, p.jerk, tau);
      double next = v > 0 ? tau - f / v : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      tau = next;
    }
  }
  return std::clamp(p.t0 + std::min(tau, p.duration), 0.0, duration_);
}

} // namespace ncjoule::kinematics_detail
