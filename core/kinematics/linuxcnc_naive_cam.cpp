#include "linuxcnc_naive_cam.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ncjoule::kinematics_detail::linuxcnc {
namespace {

constexpr std::size_t kMaxPoints = 101; // linkable() refuses once more than 100 are held

double distance(const Pose& a, const Pose& b) {
  return std::sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y) +
                   (b.z - a.z) * (b.z - a.z));
}

bool same_rotary(const Pose& a, const Pose& b) {
  return a.a == b.a && a.b == b.b && a.c == b.c;
}

// How far an XY arc strays from its chord, and its middle point (chord_deviation).
double chord_deviation(const CanonCommand& arc, double& mid_x, double& mid_y) {
  const double cx = arc.centre_first, cy = arc.centre_second;
  const double th1 = std::atan2(arc.start.y - cy, arc.start.x - cx);
  double th2 = std::atan2(arc.end.y - cy, arc.end.x - cx);
  const double r = std::hypot(arc.start.y - cy, arc.start.x - cx);
  constexpr double two_pi = 2 * std::numbers::pi;
  for (int pass = 0; pass < 2; ++pass) { // atan2's -pi/pi edge may need a second turn
    const double dth = th2 - th1;
    if (arc.rotation < 0 && dth >= -1e-5) th2 -= two_pi;
    if (arc.rotation >= 0 && dth <= 1e-5) th2 += two_pi;
  }
  const double included = std::abs(th2 - th1), mid = (th1 + th2) / 2;
  mid_x = cx + r * std::cos(mid);
  mid_y = cy + r * std::sin(mid);
  return r * (1 - std::cos(included / 2));
}

} // namespace

bool NaiveCam::linkable(const Pose& p, double tolerance) const {
  if (points_.size() >= kMaxPoints || !same_rotary(p, points_.back().at)) return false;
  if (p.x == start_.x && p.y == start_.y && p.z == start_.z) return false;
  const double mx = p.x - start_.x, my = p.y - start_.y, mz = p.z - start_.z;
  const double mm = mx * mx + my * my + mz * mz;
  for (const Point& q : points_) {
    const double t = std::clamp(
        (mx * (q.at.x - start_.x) + my * (q.at.y - start_.y) + mz * (q.at.z - start_.z)) / mm, 0.0,
        1.0);
    const Pose on{start_.x + t * mx, start_.y + t * my, start_.z + t * mz};
    if (distance(q.at, on) > tolerance) return false;
  }
  return true;
}

void NaiveCam::see(const Pose& from, const Pose& p, std::size_t index, const CanonCommand& move,
                   double tolerance) {
  if (!points_.empty() && !linkable(p, tolerance)) flush();
  if (points_.empty()) start_ = from;
  points_.push_back(Point{p, index});
  last_ = &move;
  if (!same_rotary(p, start_)) flush();
}

bool NaiveCam::offer(std::size_t index, const CanonCommand& move, double tolerance) {
  if (!(tolerance > 0) || move.state.path_mode != PathMode::Continuous ||
      move.state.feed_mode != FeedMode::UnitsPerMinute)
    return false;
  if (move.kind == CanonKind::Feed) {
    see(move.start, move.end, index, move, tolerance);
    return true;
  }
  if (move.kind != CanonKind::Arc || move.plane != Plane::XY) return false;
  double mid_x = 0, mid_y = 0;
  if (!(chord_deviation(move, mid_x, mid_y) < tolerance)) return false;
  Pose mid = move.end;
  mid.x = mid_x, mid.y = mid_y;
  mid.z = (move.start.z + move.end.z) / 2;
  mid.a = (move.start.a + move.end.a) / 2;
  mid.b = (move.start.b + move.end.b) / 2;
  mid.c = (move.start.c + move.end.c) / 2;
  see(move.start, mid, index, move, tolerance);
  // When the end does not link, the middle closes a move and the end starts the next from it.
  if (!points_.empty()) see(mid, move.end, index, move, tolerance);
  return true;
}

void NaiveCam::flush() {
  if (points_.empty()) return;
  MergedLine line;
  line.start = start_;
  line.end = points_.back().at;
  line.last = last_;
  Pose from = start_;
  for (const Point& q : points_) {
    const double length = distance(from, q.at);
    if (!line.members.empty() && line.members.back().command == q.command)
      line.members.back().length += length;
    else
      line.members.push_back(Member{q.command, length});
    from = q.at;
  }
  points_.clear();
  start_ = line.end;
  sink_(std::move(line));
}

} // namespace ncjoule::kinematics_detail::linuxcnc
