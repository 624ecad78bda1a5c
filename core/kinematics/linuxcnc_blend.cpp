// How one segment joins the next in LinuxCNC 2.9's planner (linuxcnc_blend.hpp): a stop, a tangent
// run through a kink, a parabolic blend or a blend arc (made in linuxcnc_blend_arc.cpp).
#include "linuxcnc_blend.hpp"

#include "linuxcnc_blend_arc.hpp"
#include "linuxcnc_blend_common.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ncjoule::kinematics_detail::linuxcnc {

Vec3 unit(const Vec3& a) {
  const double n = a.norm();
  return n > 0 ? Vec3((1 / n) * a) : Vec3::Zero();
}

namespace {

void set_kink(Segment& prev, Segment& next, double kink_vel, double reduction) {
  prev.kink_vel = kink_vel;
  prev.kink_reduce = std::max(reduction, prev.kink_reduce);
  next.kink_reduce_prev = std::max(reduction, next.kink_reduce_prev);
}

void remove_kink(Segment& prev, Segment& next) {
  prev.kink_vel = -1;
  prev.kink_reduce = 0;
  next.kink_reduce_prev = 0;
}

// Speeds at which two segments may overlap in a parabolic blend (tpComputeBlendVelocity);
// `planning` halves the lengths of segments that blend arcs may still shorten.
struct ParabolicSpeeds {
  double this_vel = 0, next_vel = 0, net = 0;
};
ParabolicSpeeds parabolic_speeds(const Segment& a, const Segment& b, bool planning) {
  const double acc_a = a.tangential_accel(), acc_b = b.tangential_accel();
  const double len_a = planning ? a.length / 2 : a.length;
  const double len_b = planning ? b.length / 2 : b.length;
  const double reach_a = std::min(std::sqrt(acc_a * len_a), max_target_vel(a));
  const double reach_b = std::min(std::sqrt(acc_b * len_b), max_target_vel(b));
  ParabolicSpeeds v;
  if (!(reach_a > 0) || !(reach_b > 0)) return v;
  const double t_reach = std::min(a.length / reach_a, b.length / reach_b);
  const double t_blend = std::min(t_reach, std::max(reach_a / acc_a, reach_b / acc_b));
  v.this_vel = std::min(reach_a, t_blend * acc_a);
  v.next_vel = std::min(reach_b, t_blend * acc_b);
  const double theta = intersection_angle(a.end_tangent(), b.start_tangent());
  const double cos_theta = std::cos(theta);
  if (a.tolerance > 0 && cos_theta > std::cos(kPi / 2 - kMinBlendCosAngle)) {
    const double tol_vel = 2 * std::sqrt(acc_a * a.tolerance / cos_theta);
    v.this_vel = std::min(v.this_vel, tol_vel);
    v.next_vel = std::min(v.next_vel, tol_vel);
  }
  v.net = std::sin(theta) * (v.this_vel + v.next_vel) / 2;
  return v;
}

// A parabolic blend as LinuxCNC runs it (tpDoParabolicBlending): from the blend speed V, the
// first segment slows to rest at its acceleration a1 while the second starts from rest at a2,
// both at once. Timed here as a junction at speed v, with `overlap` mm of each segment run in
// parallel with the other:
//  - a2 < a1: the second lags behind; passing at v = V (1 - sqrt((a1/a2 - 1) / (a1/a2 + 1)))
//    takes the same time;
//  - a2 >= a1: their speeds add up to more than V; passing at V over a path shorter by
//    V^2/2 (1/a1 - 1/a2) takes the same time. LinuxCNC charges the overlap to the faster of the
//    two, the first until t = V / (a1 + a2): the shortening is shared the same way.
struct ParabolicJunction {
  double vel = 0, overlap_prev = 0, overlap_next = 0;
};
ParabolicJunction parabolic_junction(const Segment& a, const Segment& b) {
  ParabolicJunction j;
  const double v = j.vel = parabolic_speeds(a, b, false).this_vel;
  const double a1 = a.tangential_accel(), a2 = b.tangential_accel();
  if (!(a1 > 0) || !(a2 > 0)) return j;
  if (a2 < a1) {
    const double ratio = a1 / a2;
    j.vel = v * (1 - std::sqrt((ratio - 1) / (ratio + 1)));
    return j;
  }
  const double gain_s = v / 2 * (1 / a1 - 1 / a2);
  const double gain_prev_s = std::min(gain_s, v / (2 * a1) - v / (a1 + a2));
  // At most a quarter of either segment: the formula holds where both run at V.
  j.overlap_prev = std::min(v * gain_prev_s, a.length / 4);
  j.overlap_next = std::min(v * (gain_s - gain_prev_s), b.length / 4);
  return j;
}

enum class Choice { None, Parabolic, Tangent, Arc };

// The fastest way through the corner (tpChooseBestBlend): a parabolic blend (rated at half its
// speed, since it halves the acceleration of both segments), a run through the kink, or the arc.
Choice choose_blend(Segment& prev, Segment& next, double arc_vel) {
  if (prev.term == Term::Exact || prev.term == Term::Stop) return Choice::None;
  const double parabolic = parabolic_speeds(prev, next, true).net / 2;
  const double tangent = prev.kink_vel;
  Choice best = Choice::Parabolic;
  double best_vel = parabolic;
  if (tangent > best_vel) best = Choice::Tangent, best_vel = tangent;
  if (arc_vel > best_vel) best = Choice::Arc;
  switch (best) {
  case Choice::Parabolic:
    remove_kink(prev, next);
    set_term(prev, next, Term::Parabolic);
    break;
  case Choice::Tangent:
    set_term(prev, next, Term::Tangent);
    break;
  default:
    remove_kink(prev, next);
    break;
  }
  return best;
}

// tpSetupTangent: true when the junction is settled here (a stop, or a run through a kink small
// enough to ignore); otherwise the kink speed is recorded for comparison with a blend.
bool settle_tangent(Segment& prev, Segment& next, const AxisBounds& bounds) {
  if (prev.rotary || next.rotary) return true;
  if (prev.term == Term::Stop) return true;
  const Vec3 u1 = prev.end_tangent(), u2 = next.start_tangent();
  const double sharp = kPi * kSharpCornerDeg / 180;
  const Vec3 sum = u1 + u2;
  if (sum.squaredNorm() < sharp * sharp) {
    set_term(prev, next, Term::Stop);
    return true;
  }
  const double v_max = std::min(max_target_vel(prev), max_target_vel(next));
  // The acceleration of turning within one servo cycle, from a stop and into a full start.
  const double a_inst = v_max / kCycle_s + next.accel;
  const Vec3 diff = a_inst * (u2 - u1);
  double scale = 0;
  for (int i = 0; i < 3; ++i)
    if (bounds.accel[i] != 0) scale = std::max(scale, std::abs(diff[i] / bounds.accel[i]));
  if (prev.shape == Shape::Circle || next.shape == Shape::Circle) scale /= kTangentialAccelRatio;
  if (scale < kKinkRatio) {
    set_term(prev, next, Term::Tangent);
    set_kink(prev, next, v_max, scale);
    return true;
  }
  set_kink(prev, next, v_max * kKinkRatio / scale, kKinkRatio);
  return false;
}

// Clamps a segment's speed to one length per servo cycle and sets a circle's share of
// tangential acceleration (tcFinalizeLength, tcUpdateCircleAccRatio, pmCircleActualMaxVel).
void finalize_segment(Segment& s) {
  s.maxvel = std::min(s.maxvel, s.length / kCycle_s);
  if (s.shape != Shape::Circle) return;
  const Circle& c = s.circle;
  const double a = s.accel * (1 - std::max(s.kink_reduce, s.kink_reduce_prev)) *
                   ((s.blend_prev || s.term == Term::Parabolic) ? 0.5 : 1.0);
  // Curvature radius of the spiral, and of the helix around it (pmCircleEffectiveMinRadius).
  const double dr = c.spiral / c.angle;
  const double inner = dr * dr + c.radius * c.radius;
  const double r_spiral = std::sqrt(inner * inner * inner) / (inner + dr * dr);
  const double radius = c.r_helix.squaredNorm() / r_spiral + r_spiral;
  const double a_normal_max = kNormalAccelRatio * a;
  const double a_normal = s.maxvel * s.maxvel / std::max(radius, 1e-300);
  if (a_normal > a_normal_max) {
    s.maxvel = std::sqrt(a_normal_max * radius);
    s.acc_ratio_tan = kTangentialAccelRatio;
  } else {
    s.acc_ratio_tan = a > 0 ? std::sqrt(std::max(0.0, 1 - (a_normal / a) * (a_normal / a))) : 1;
  }
}

} // namespace

Vec3 Circle::point(double phi) const {
  Vec3 p = std::cos(phi) * r_tan + std::sin(phi) * r_perp;
  const double scale = angle != 0 ? phi / angle : 0;
  p = p + (scale * spiral) * unit(p);
  p = p + scale * r_helix;
  return centre + p;
}

Vec3 Circle::tangent(double phi) const {
  const Vec3 r = point(phi) - centre;
  Vec3 t = normal.cross(r);
  if (angle != 0) t = t + (1 / angle) * r_helix + (spiral / angle) * unit(r);
  return unit(t);
}

Vec3 Segment::start_tangent() const {
  return shape == Shape::Circle ? circle.tangent(0) : direction;
}

Vec3 Segment::end_tangent() const {
  return shape == Shape::Circle ? circle.tangent(circle.angle) : direction;
}

double Segment::tangential_accel() const {
  double a = accel * (1 - std::max(kink_reduce, kink_reduce_prev));
  if (blend_prev || term == Term::Parabolic) a *= 0.5;
  if (shape != Shape::Line) a *= acc_ratio_tan;
  return a;
}

double Segment::target_vel() const {
  double v = std::min(reqvel, maxvel);
  if (after_tangent) v = std::min(v, length / (kCycle_s * kMinSegmentCycles));
  return v;
}

Join join(Segment& prev, Segment& next, const AxisBounds& bounds) {
  Join result;
  if (prev.traverse != next.traverse) set_term(prev, next, Term::Stop); // handleModeChange
  if (!settle_tangent(prev, next, bounds)) {
    ArcAttempt at;
    const bool made = prev.term == Term::Parabolic && !prev.rotary && !next.rotary &&
                      try_blend_arc(at, prev, next, bounds);
    if (choose_blend(prev, next, made ? at.arc.maxvel : 0) == Choice::Arc) {
      apply_blend_arc(prev, next, at);
      result.blend = at.arc;
      result.consumed = at.consume;
      result.consumed_length = at.line_part;
    }
  }
  finalize_segment(prev);
  if (next.atspeed) set_term(prev, next, Term::Stop); // tcFlagEarlyStop
  if (prev.term == Term::Parabolic) {
    const ParabolicJunction p = parabolic_junction(prev, next);
    result.parabolic_vel = p.vel;
    prev.overlap += p.overlap_prev;
    next.overlap += p.overlap_next;
  }
  if (result.blend)
    next.after_tangent = true, result.blend->after_tangent = true;
  else if (prev.term == Term::Tangent)
    next.after_tangent = true;
  return result;
}

} // namespace ncjoule::kinematics_detail::linuxcnc
