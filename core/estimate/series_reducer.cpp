#include "series_reducer.hpp"

#include <algorithm>
#include <cmath>

namespace ncjoule::estimate_detail {

SeriesReducer::SeriesReducer(std::size_t buckets) : capacity_(std::max<std::size_t>(buckets, 2)) {}

void SeriesReducer::add(double t_s, double value) {
  if (!std::isfinite(t_s) || !std::isfinite(value)) return;
  const Point p{t_s, value};
  if (!bucketed_) {
    raw_.push_back(p);
    if (raw_.size() > 2 * capacity_) start_buckets();
    return;
  }
  // The point put last again (a segment's end is the next one's start): its bucket already
  // holds it between its lowest and highest, so putting it again changes nothing.
  if (p.t == last_.t && p.v == last_.v) return;
  put(p);
  last_ = p;
}

void SeriesReducer::start_buckets() {
  t0_ = raw_.front().t;
  const double span = raw_.back().t - t0_;
  width_ = span > 0 ? span / double(capacity_) * 2 : 1e-9;
  buckets_.assign(capacity_, Bucket{});
  bucketed_ = true;
  for (const Point& p : raw_)
    put(p);
  raw_.clear();
  raw_.shrink_to_fit();
}

void SeriesReducer::put(const Point& p) {
  double index = std::floor((p.t - t0_) / width_);
  while (index >= double(capacity_)) {
    widen();
    index = std::floor((p.t - t0_) / width_);
  }
  Bucket& b = buckets_[std::size_t(std::max(0.0, index))];
  if (!b.used) {
    b.low = b.high = p;
    b.used = true;
    return;
  }
  if (p.v < b.low.v) b.low = p;
  if (p.v > b.high.v) b.high = p;
}

void SeriesReducer::widen() {
  for (std::size_t i = 0; i < capacity_; ++i) {
    Bucket merged;
    for (std::size_t k = 2 * i; k < 2 * i + 2 && k < capacity_; ++k) {
      const Bucket& b = buckets_[k];
      if (!b.used) continue;
      if (!merged.used) {
        merged = b;
        continue;
      }
      if (b.low.v < merged.low.v) merged.low = b.low;
      if (b.high.v > merged.high.v) merged.high = b.high;
    }
    buckets_[i] = merged;
  }
  width_ *= 2;
}

Series SeriesReducer::result() const {
  Series s;
  const std::size_t most = bucketed_ ? 2 * buckets_.size() : raw_.size();
  s.t_s.reserve(most);
  s.value.reserve(most);
  auto put = [&s](const Point& p) {
    s.t_s.push_back(p.t);
    s.value.push_back(p.v);
  };
  if (!bucketed_) {
    for (const Point& p : raw_)
      put(p);
    return s;
  }
  for (const Bucket& b : buckets_) {
    if (!b.used) continue;
    const Point& first = b.low.t <= b.high.t ? b.low : b.high;
    const Point& second = b.low.t <= b.high.t ? b.high : b.low;
    put(first);
    if (second.t != first.t || second.v != first.v) put(second);
  }
  return s;
}

PathReducer::PathReducer(std::size_t max_points)
    : max_points_(std::max<std::size_t>(max_points, 16)) {}

bool PathReducer::keeps(const PathPoint& last, const PathPoint& p) const {
  if (p.rapid != last.rapid) return true;
  const double dx = double(p.x - last.x), dy = double(p.y - last.y), dz = double(p.z - last.z);
  if (dx * dx + dy * dy + dz * dz >= tolerance_mm_ * tolerance_mm_) return true;
  const double scale = std::max(1.0f, std::max(std::abs(last.power_w), std::abs(p.power_w)));
  return std::abs(p.power_w - last.power_w) > power_tolerance_ * scale;
}

void PathReducer::add(const PathPoint& point) {
  if (points_.empty() || keeps(points_.back(), point)) {
    points_.push_back(point);
    has_pending_ = false;
    if (points_.size() > max_points_) thin();
    return;
  }
  pending_ = point;
  has_pending_ = true;
}

void PathReducer::thin() {
  for (int pass = 0; pass < 8 && points_.size() > max_points_ / 2; ++pass) {
    tolerance_mm_ *= 2;
    power_tolerance_ *= 2;
    std::vector<PathPoint> kept;
    kept.reserve(points_.size());
    for (const PathPoint& p : points_)
      if (kept.empty() || keeps(kept.back(), p)) kept.push_back(p);
    points_.swap(kept);
  }
  if (points_.size() <= max_points_ / 2) return;
  // The tolerances alone do not thin this path: keep every other point (the last included).
  std::size_t kept = 0;
  for (std::size_t i = points_.size() % 2 == 0 ? 1 : 0; i < points_.size(); i += 2)
    points_[kept++] = points_[i];
  points_.resize(kept);
}

std::vector<PathPoint> PathReducer::result() const {
  std::vector<PathPoint> out = points_;
  if (has_pending_) out.push_back(pending_);
  return out;
}

} // namespace ncjoule::estimate_detail
