#include "sampling.hpp"

#include <algorithm>
#include <cmath>

namespace ncjoule::kinematics_detail {
namespace {

// At most `cap` intervals (PlanOptions::max_samples_per_move): beyond it the samples thin out,
// which removal's swept steps between samples tolerate on the long straight moves it happens on.
std::size_t intervals(double extent, double step, std::size_t cap) {
  if (!(step > 0) || !(extent > 0)) return 1;
  return static_cast<std::size_t>(
      std::clamp(std::ceil(extent / step), 1.0, double(std::max<std::size_t>(cap, 1))));
}

} // namespace

void sample_move(const CanonCommand& move, const TimedSpan& profile, double spatial_length,
                 double start_s, const PlanOptions& options, std::vector<MotionSample>& out) {
  const double length = profile.length();
  const double duration = profile.duration();
  const std::size_t cap = options.max_samples_per_move;
  const std::size_t n = intervals(spatial_length, options.max_sample_step_mm, cap);
  out.reserve(out.size() + n + 1);
  out.push_back(MotionSample{start_s, 0.0, move.start, profile.entry_speed()});
  if (!(length > 0)) { // a point: both samples at the same instant
    out.push_back(MotionSample{start_s, 1.0, move.end, profile.exit_speed()});
    return;
  }
  auto push = [&](double s, double t) {
    const double u = s / length;
    out.push_back(MotionSample{start_s + t, u, point_on_move(move, u), profile.speed_at(t)});
  };
  double previous_t = 0;
  // The extra samples in time share the same budget as those in space.
  const std::size_t extra_cap = std::max<std::size_t>(1, cap / n);
  for (std::size_t k = 1; k <= n; ++k) {
    const bool last = k == n;
    const double s = last ? length : length * static_cast<double>(k) / static_cast<double>(n);
    const double t = last ? duration : profile.time_at(s);
    // Slow stretches (ramps from rest) get extra samples so no gap exceeds max_sample_dt_s.
    const std::size_t m =
        std::min(intervals(t - previous_t, options.max_sample_dt_s, cap), extra_cap);
    for (std::size_t j = 1; j < m; ++j) {
      const double tj = previous_t + (t - previous_t) * static_cast<double>(j) / m;
      push(profile.distance_at(tj), tj);
    }
    if (last)
      out.push_back(MotionSample{start_s + duration, 1.0, move.end, profile.exit_speed()});
    else
      push(s, t);
    previous_t = t;
  }
}

void sample_dog_leg(const CanonCommand& move, const DogLegMove& dog_leg, double start_s,
                    const PlanOptions& options, std::vector<MotionSample>& out) {
  const double duration = dog_leg.duration();
  // Uniform in time: at most peak * dt apart in space.
  const std::size_t cap = options.max_samples_per_move;
  std::size_t n = intervals(dog_leg.peak_speed() * duration, options.max_sample_step_mm, cap);
  n = std::max(n, intervals(duration, options.max_sample_dt_s, cap)); // each capped already
  out.reserve(out.size() + n + 1);
  out.push_back(MotionSample{start_s, 0.0, move.start, 0.0});
  for (std::size_t k = 1; k < n; ++k) {
    const double u = static_cast<double>(k) / static_cast<double>(n);
    const double t = duration * u;
    // The path is not the chord, so u is the fraction of the move's time.
    out.push_back(MotionSample{start_s + t, u, dog_leg.position_at(t), dog_leg.speed_at(t)});
  }
  out.push_back(MotionSample{start_s + duration, 1.0, move.end, 0.0});
}

} // namespace ncjoule::kinematics_detail
