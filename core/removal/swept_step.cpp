// Exact per-column minimum of the tool bottom along a straight step, and the inside test.
#include "swept_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace ncjoule::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Below this XY length a step is treated as a plunge (the tool axis does not move sideways).
constexpr double kMinXyLength = 1e-9;

// sqrt(x^2 + y^2) as IEEE arithmetic gives it, the same on every C library: std::hypot is a
// library function (glibc's and MinGW's differ in the last bit), and a column whose centre lies
// on the tool's edge would be inside on one system and outside on the other. No overflow at the
// lengths of a machine's travel.
double planar_length(double x, double y) {
  return std::sqrt(x * x + y * y);
}

// Minimum of a convex function on [a, b] by golden-section search, end points included.
template <class F> double convex_min(F&& f, double a, double b) {
  double best = std::min(f(a), f(b));
  if (!(b - a > 1e-12)) return best;
  constexpr double inv_phi = 0.6180339887498949;
  double x1 = b - inv_phi * (b - a), x2 = a + inv_phi * (b - a);
  double f1 = f(x1), f2 = f(x2);
  // 1e-10 mm on a step of a few mm: about 50 iterations.
  for (int it = 0; it < 200 && b - a > 1e-10; ++it) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1;
      x1 = b - inv_phi * (b - a), f1 = f(x1);
    } else {
      a = x1, x1 = x2, f1 = f2;
      x2 = a + inv_phi * (b - a), f2 = f(x2);
    }
  }
  return std::min({best, f1, f2});
}

} // namespace

SweptStep::SweptStep(const Tool& tool, const Point3& from, const Point3& to)
    : tool_(tool), ax_(from.x()), ay_(from.y()), az_(from.z()), dz_(to.z() - from.z()),
      radius_(tool.radius()), reach_(tool.reach_radius()), zlow_(std::min(from.z(), to.z())) {
  const double dx = to.x() - from.x(), dy = to.y() - from.y();
  len_ = planar_length(dx, dy);
  if (len_ > kMinXyLength) {
    ux_ = dx / len_, uy_ = dy / len_;
    slope_ = dz_ / len_;
    slope_norm_ = std::sqrt(1 + slope_ * slope_);
  } else {
    len_ = 0;
  }
  if (reach_ > radius_) {
    shank_radius_ = reach_;
    shank_height_ = tool.cutting_length_mm;
  }
  if (tool.shape == ToolShape::Drill || tool.shape == ToolShape::Chamfer)
    tan_half_ = tool.tan_half_tip_angle();
  if (tool.shape == ToolShape::Chamfer) tip_radius_ = tool.tip_diameter_mm / 2;
  xmin_ = std::min(from.x(), to.x()) - reach_, xmax_ = std::max(from.x(), to.x()) + reach_;
  ymin_ = std::min(from.y(), to.y()) - reach_, ymax_ = std::max(from.y(), to.y()) + reach_;
}

double SweptStep::profile_height(double r) const {
  r = std::min(r, radius_);
  switch (tool_.shape) {
  case ToolShape::FlatEndMill:
    return 0;
  case ToolShape::BallEndMill:
    return radius_ - std::sqrt(std::max(0.0, radius_ * radius_ - r * r));
  case ToolShape::BullNose:
    return tool_.envelope_height(r);
  case ToolShape::Chamfer: // Tool::envelope_height's cone, with the tangent worked out once
    return r <= tip_radius_ ? 0 : (r - tip_radius_) / tan_half_;
  case ToolShape::Drill:
    return r / tan_half_;
  }
  return 0;
}

double SweptStep::lowest_bottom(double x, double y, bool shank) const {
  const double R = shank ? shank_radius_ : radius_;
  const double lift = shank ? shank_height_ : 0.0;
  const double qx = x - ax_, qy = y - ay_;
  if (len_ == 0) { // plunge or retract: the lowest tip position is the lowest bottom
    const double r = planar_length(qx, qy);
    if (r > R) return kInf;
    return zlow_ + lift + (shank ? 0.0 : profile_height(r));
  }
  const double along = qx * ux_ + qy * uy_; // foot of the perpendicular, mm from the start
  const double perp = qy * ux_ - qx * uy_;
  const double p2 = perp * perp;
  if (p2 > R * R) return kInf;
  const double c = std::sqrt(R * R - p2);
  // u: position along the step measured from the foot, limited to the step and to the part of
  // the line where the column is under the tool.
  const double ul = std::max(-along, -c), uh = std::min(len_ - along, c);
  if (ul > uh) return kInf;
  const double base = az_ + along * slope_ + lift;
  auto bottom = [&](double u) {
    return base + u * slope_ + (shank ? 0.0 : profile_height(std::sqrt(p2 + u * u)));
  };
  if (slope_ == 0) return bottom(std::clamp(0.0, ul, uh)); // the profile grows with distance
  // Sloped steps (ramps, helices): the bottom is convex in u, so the clamped stationary point
  // is the minimum. Closed forms where they are short; golden section otherwise.
  const ToolShape shape = shank ? ToolShape::FlatEndMill : tool_.shape;
  switch (shape) {
  case ToolShape::FlatEndMill:
    return bottom(slope_ > 0 ? ul : uh);
  case ToolShape::BallEndMill: {
    const double u = -slope_ * c / slope_norm_;
    return bottom(std::clamp(u, ul, uh));
  }
  case ToolShape::Drill: {
    const double m = -slope_ * tan_half_; // u / sqrt(p2 + u^2) at the stationary point
    if (std::abs(m) >= 1) return bottom(slope_ > 0 ? ul : uh);
    const double u = m * std::abs(perp) / std::sqrt(1 - m * m);
    return bottom(std::clamp(u, ul, uh));
  }
  case ToolShape::Chamfer: {
    // Flat over the tip's radius (the bottom is linear in u there), a cone beyond it: the
    // minimum is at an end, at a kink where the cone begins, or at the cone's stationary point
    // (as the drill's). Each is a point of the step, so the least of them is the minimum.
    double lowest = std::min(bottom(ul), bottom(uh));
    if (p2 < tip_radius_ * tip_radius_) {
      const double w = std::sqrt(tip_radius_ * tip_radius_ - p2);
      lowest = std::min({lowest, bottom(std::clamp(-w, ul, uh)), bottom(std::clamp(w, ul, uh))});
    }
    const double m = -slope_ * tan_half_;
    if (std::abs(m) < 1)
      lowest =
          std::min(lowest, bottom(std::clamp(m * std::abs(perp) / std::sqrt(1 - m * m), ul, uh)));
    return lowest;
  }
  case ToolShape::BullNose:
    return convex_min(bottom, ul, uh);
  }
  return kInf;
}

double SweptStep::envelope_at(double x, double y) const {
  double e = lowest_bottom(x, y, false);
  if (shank_radius_ > 0) e = std::min(e, lowest_bottom(x, y, true));
  return e;
}

double SweptStep::plunge_offset(double x, double y) const {
  // lowest_bottom's plunge case less the lowest tip: zlow + min(a, b) rounds as
  // min(zlow + a, zlow + b) does, since rounding a sum is monotonic in each term.
  const double r = planar_length(x - ax_, y - ay_);
  double offset = r > radius_ ? kInf : profile_height(r);
  if (shank_radius_ > 0 && r <= shank_radius_) offset = std::min(offset, shank_height_);
  return offset;
}

bool SweptStep::contains(double x, double y, double z) const {
  const double qx = x - ax_, qy = y - ay_;
  // Horizontal distance from the tool axis to the point when the tip is at parameter t (mm of
  // XY travel along the step).
  auto distance = [&](double t) { return planar_length(qx - t * ux_, qy - t * uy_); };
  auto closest = [&](double t0, double t1) { // min distance for t in [t0, t1]
    return distance(std::clamp(qx * ux_ + qy * uy_, t0, t1));
  };
  // The tip positions from which the point is at or above the tip: t in [t0, t1].
  auto above_tip = [&](double lift, double& t0, double& t1) {
    if (len_ == 0) {
      t0 = t1 = 0;
      return z - zlow_ >= lift;
    }
    t0 = 0, t1 = len_;
    if (slope_ == 0) return z - az_ >= lift;
    const double t_level = (z - lift - az_) / slope_; // where the tip is at z - lift
    if (slope_ > 0)
      t1 = std::min(t1, t_level);
    else
      t0 = std::max(t0, t_level);
    return t0 <= t1;
  };
  double t0, t1;
  if (shank_radius_ > 0 && above_tip(shank_height_, t0, t1) && closest(t0, t1) <= shank_radius_)
    return true;
  if (!above_tip(0, t0, t1)) return false;
  if (len_ == 0) return planar_length(qx, qy) <= tool_.section_radius(z - zlow_);
  if (slope_ == 0) return closest(t0, t1) <= tool_.section_radius(z - az_);
  // distance - section radius is convex in t (distance convex, section radius concave in height).
  auto gap = [&](double t) { return distance(t) - tool_.section_radius(z - (az_ + t * slope_)); };
  return convex_min(gap, t0, t1) <= 0;
}

bool SweptStep::row_span(double y, double& xlo, double& xhi) const {
  // The footprint is a capsule: discs at both ends joined by a band. A horizontal line meets it
  // in one interval, the hull of its meetings with the two discs and the band.
  xlo = kInf, xhi = -kInf;
  const double R = reach_;
  auto disc = [&](double cx, double cy) {
    const double d = y - cy;
    if (std::abs(d) > R) return;
    const double w = std::sqrt(R * R - d * d);
    xlo = std::min(xlo, cx - w), xhi = std::max(xhi, cx + w);
  };
  disc(ax_, ay_);
  const double bx = ax_ + ux_ * len_, by = ay_ + uy_ * len_;
  disc(bx, by);
  if (len_ > 0) {
    const double nx = -uy_ * R, ny = ux_ * R;
    const double px[4] = {ax_ + nx, bx + nx, bx - nx, ax_ - nx};
    const double py[4] = {ay_ + ny, by + ny, by - ny, ay_ - ny};
    for (int e = 0; e < 4; ++e) {
      const int f = (e + 1) % 4;
      const double y0 = py[e], y1 = py[f];
      if ((y0 - y) * (y1 - y) > 0) continue;
      if (y0 == y1) {
        xlo = std::min({xlo, px[e], px[f]}), xhi = std::max({xhi, px[e], px[f]});
        continue;
      }
      const double x = px[e] + (y - y0) * (px[f] - px[e]) / (y1 - y0);
      xlo = std::min(xlo, x), xhi = std::max(xhi, x);
    }
  }
  return xlo <= xhi;
}

} // namespace ncjoule::detail
