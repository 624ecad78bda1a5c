#include "linuxcnc_blend.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ncjoule::kinematics_detail::linuxcnc {

Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec3 operator*(double k, const Vec3& a) {
  return {k * a.x, k * a.y, k * a.z};
}
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double norm(const Vec3& a) {
  return std::sqrt(dot(a, a));
}
Vec3 unit(const Vec3& a) {
  const double n = norm(a);
  return n > 0 ? (1 / n) * a : Vec3{};
}

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kAngleEpsilon = 1e-6;     // TP_ANGLE_EPSILON
constexpr double kPosEpsilon = 1e-12;      // TP_POS_EPSILON
constexpr double kMinArcLength = 1e-6;     // TP_MIN_ARC_LENGTH
constexpr double kMinArcAngle = 1e-6;      // ARC_MIN_ANGLE (spherical blend arcs)
constexpr double kSharpCornerDeg = 2.0;    // tpSetupTangent: reversals stop
constexpr double kMinBlendCosAngle = 1e-3; // TP_MIN_ARC_ANGLE in tpComputeBlendVelocity
constexpr double kMaxFeedScale = 1.0;      // [DISPLAY] MAX_FEED_OVERRIDE
constexpr double kKinkFactor = 0.25;       // BLEND_KINK_FACTOR

double component(const Vec3& v, int i) {
  return i == 0 ? v.x : i == 1 ? v.y : v.z;
}

// Speed the segment may reach at full feed override (tcGetMaxTargetVel).
double max_target_vel(const Segment& s) {
  return std::min(s.reqvel * kMaxFeedScale, s.maxvel);
}

// Half the angle between the directions (findIntersectionAngle): pi/2 straight on, 0 reversal.
double intersection_angle(const Vec3& u1, const Vec3& u2) {
  return std::acos(std::clamp(-dot(u1, u2), -1.0, 1.0)) / 2;
}

// The largest circle centred on the origin inside the box of per-axis bounds, cut by the plane
// with this unit normal: the limit of a vector of any direction in that plane
// (calculateInscribedDiameter).
double inscribed_bound(const Vec3& normal, const Vec3& bounds) {
  double result = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const double b = component(bounds, i);
    if (b == 0) continue;
    const double n = component(normal, i);
    const double scale = std::max(std::sqrt(std::max(0.0, 1 - n * n)), kPosEpsilon);
    result = std::min(result, b / scale);
  }
  return std::isfinite(result) ? result : 0.0;
}

bool parallel_units(const Vec3& a, const Vec3& b) {
  const Vec3 d = a - b, s = a + b;
  const double tol = kAngleEpsilon * kAngleEpsilon;
  return dot(d, d) < tol || dot(s, s) < tol;
}

void set_term(Segment& prev, Segment& next, Term term) {
  prev.term = term;
  next.blend_prev = term == Term::Parabolic;
}

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
  if (dot(sum, sum) < sharp * sharp) {
    set_term(prev, next, Term::Stop);
    return true;
  }
  const double v_max = std::min(max_target_vel(prev), max_target_vel(next));
  // The acceleration of turning within one servo cycle, from a stop and into a full start.
  const double a_inst = v_max / kCycle_s + next.accel;
  const Vec3 diff = a_inst * (u2 - u1);
  double scale = 0;
  for (int i = 0; i < 3; ++i)
    if (component(bounds.accel, i) != 0)
      scale = std::max(scale, std::abs(component(diff, i) / component(bounds.accel, i)));
  if (prev.shape == Shape::Circle || next.shape == Shape::Circle) scale /= kTangentialAccelRatio;
  if (scale < kKinkRatio) {
    set_term(prev, next, Term::Tangent);
    set_kink(prev, next, v_max, scale);
    return true;
  }
  set_kink(prev, next, v_max * kKinkRatio / scale, kKinkRatio);
  return false;
}

// ---- blend arcs ----------------------------------------------------------------------------

struct Geometry { // BlendGeom3
  Vec3 u1, u2, u_tan1, u_tan2, p, normal, binormal, centre1, centre2;
  double radius1 = 0, radius2 = 0, theta_tan = 0;
};

struct Parameters { // BlendParameters
  double tolerance = 0, l1 = 0, l2 = 0, v_req = 0, v_goal = 0, a_max = 0, a_n_max = 0;
  double theta = 0, phi = 0, phi1_max = 0, phi2_max = 0;
  bool convex1 = false, convex2 = false;
  double v_plan = 0, r_plan = 0, d_plan = 0, s_arc = 0;
};

struct Points { // BlendPoints3
  Vec3 arc_start, arc_end, arc_centre;
  double trim1 = 0, trim2 = 0;
};

// The blend tolerance: G64 P of either segment, a quarter of either's programmed length
// (tcFindBlendTolerance); G64 without P has only the latter.
double blend_tolerance(const Segment& prev, const Segment& next) {
  const double t1 = prev.tolerance > 0 ? prev.tolerance : prev.nominal * kToleranceFraction;
  const double t2 = next.tolerance > 0 ? next.tolerance : next.nominal * kToleranceFraction;
  return std::min({t1, t2, prev.nominal * kToleranceFraction, next.nominal * kToleranceFraction});
}

bool init_geometry(Geometry& g, const Segment& prev, const Segment& next) {
  g.u_tan1 = prev.end_tangent();
  g.u_tan2 = next.start_tangent();
  g.u1 = g.u_tan1;
  g.u2 = g.u_tan2;
  g.p = next.shape == Shape::Line   ? next.start
        : prev.shape == Shape::Line ? prev.end
                                    : next.circle.point(0);
  g.theta_tan = intersection_angle(g.u_tan1, g.u_tan2);
  if (kPi / 2 - g.theta_tan < kAngleEpsilon || g.theta_tan < kAngleEpsilon) return false;
  g.binormal = unit(cross(g.u_tan1, g.u_tan2));
  g.normal = unit(g.u_tan2 - g.u_tan1);
  return true;
}

// Local circle through P fitted to a spiral (findSpiralApproximation).
void spiral_fit(const Circle& c, const Vec3& p, const Vec3& u_tan, Vec3& centre, double& radius) {
  centre = c.centre + (c.spiral / c.angle) * u_tan;
  radius = norm(p - centre);
}

// blendParamKinematics: the tolerance, the acceleration and speed limits in the blend's plane.
bool kinematics(Geometry& g, Parameters& q, const Segment& prev, const Segment& next,
                const AxisBounds& bounds) {
  q.phi = kPi - 2 * q.theta;
  q.tolerance = blend_tolerance(prev, next);
  q.a_max = inscribed_bound(g.binormal, bounds.accel);
  q.a_n_max = q.a_max * kNormalAccelRatio;
  q.v_req = std::max(std::min(prev.reqvel, prev.maxvel), std::min(next.reqvel, next.maxvel));
  q.v_goal = std::max(max_target_vel(prev), max_target_vel(next));
  const double v_planar_max = inscribed_bound(g.binormal, bounds.vel);
  const double phi_effective = std::min(q.phi, kPi * 0.49);
  const double v_max1 = std::min(prev.maxvel, next.maxvel / std::cos(phi_effective));
  const double v_max2 = std::min(next.maxvel, prev.maxvel / std::cos(phi_effective));
  double v_max_alt = 0;
  if (prev.shape == Shape::Line && next.shape == Shape::Line) {
    // The altitude of the triangle of the two speed vectors: the fastest a vector turning from
    // one to the other may be without leaving either segment's limit.
    const double area = v_max1 * v_max2 / 2 * std::sin(q.phi);
    const double base = norm(v_max2 * g.u2 - v_max1 * g.u1);
    if (base > 0) v_max_alt = 2 * area / base;
  }
  q.v_goal = std::min(q.v_goal, std::max(v_max_alt, v_planar_max));
  return q.a_max > 0;
}

// blendComputeParameters: the radius the tolerance and the lengths allow, the speed that radius
// allows, and the radius actually used (no larger than needed to keep that speed).
bool compute_parameters(Parameters& q) {
  const double h_tol = q.tolerance / (1 - std::sin(q.theta));
  const double d_tol = std::cos(q.theta) * h_tol;
  const double d_geom = std::min({q.l1, q.l2, d_tol});
  const double r_geom = std::tan(q.theta) * d_geom;
  const double v_normal = std::sqrt(q.a_n_max * r_geom);
  q.v_plan = std::min(v_normal, q.v_goal);
  const double a_parabolic = q.a_max * 0.5;
  const double v_triangle = std::sqrt(2 * a_parabolic * d_geom);
  const double t_blend = std::min(v_triangle, q.v_plan) / a_parabolic;
  const double s_blend = t_blend * q.v_plan;
  const double r_blend = std::min(s_blend / q.phi, r_geom);
  q.r_plan = std::max(q.v_plan * q.v_plan / q.a_n_max, r_blend);
  q.d_plan = q.r_plan / std::tan(q.theta);
  q.s_arc = q.r_plan * q.phi;
  return std::isfinite(q.r_plan) && q.r_plan >= kPosEpsilon && q.s_arc >= kMinArcLength;
}

// Angle between the directions from a circle's centre to P and to the blend arc's centre.
double trim_angle(const Vec3& p, const Vec3& arc_centre, const Vec3& centre) {
  return std::acos(std::clamp(dot(unit(p - centre), unit(arc_centre - centre)), -1.0, 1.0));
}

// Where a blend arc of radius R touching a line meets a circle (blendLineArcPostProcess and
// blendArcLinePostProcess): distance along the line from P (signed by `along`) and the centre.
bool line_circle_fit(const Geometry& g, const Parameters& q, const Vec3& u_line, double along,
                     const Vec3& circle_centre, double circle_radius, bool convex, double& d_line,
                     Vec3& arc_centre) {
  const double d = (convex ? -q.r_plan : q.r_plan) + circle_radius;
  const Vec3 n = unit(cross(g.binormal, u_line));
  const Vec3 r_pc = circle_centre - g.p;
  const double c_u = dot(r_pc, u_line) * along, c_n = dot(r_pc, n);
  const double b = 2 * c_u, c = c_u * c_u - d * d + (q.r_plan - c_n) * (q.r_plan - c_n);
  const double disc = b * b - 4 * c;
  if (disc < 0) return false;
  const double root = std::sqrt(disc);
  d_line = std::min(std::abs((-b + root) / 2), std::abs((-b - root) / 2));
  const Vec3 r = (along * -d_line) * u_line + q.r_plan * n;
  arc_centre = g.p + r;
  return norm(r) - q.r_plan <= q.tolerance;
}

// Trims a circle to `new_angle`, from its start or its end (pmCircleStretch); helices refuse.
bool stretch(Circle& c, double new_angle, bool from_start) {
  if (new_angle <= 1e-10 || dot(c.r_helix, c.r_helix) > 1e-6) return false;
  if (from_start) {
    const Vec3 new_start = c.point(c.angle - new_angle);
    c.r_tan = new_start - c.centre;
    c.r_perp = cross(c.normal, c.r_tan);
    c.radius = norm(c.r_tan);
  }
  c.spiral *= new_angle / c.angle;
  c.angle = new_angle;
  return true;
}

double circle_length(const Circle& c) {
  const double planar = (c.radius + c.spiral / 2) * c.angle;
  return std::sqrt(planar * planar + dot(c.r_helix, c.r_helix));
}

// The spherical arc through two points around a centre: its angle, radius and the unit tangent
// at either end (arcInitFromPoints, arcTangent), for the tangency check against a circle.
struct BlendArc {
  double radius = 0, angle = 0;
  Vec3 r_start, r_end;
};
bool arc_from_points(BlendArc& a, const Vec3& start, const Vec3& end, const Vec3& centre) {
  a.r_start = start - centre;
  a.r_end = end - centre;
  const double r0 = norm(a.r_start), r1 = norm(a.r_end);
  if (r0 < 1e-12 || r1 < 1e-12) return false;
  a.radius = r0;
  a.angle = std::acos(std::clamp(dot((1 / r0) * a.r_start, (1 / r1) * a.r_end), -1.0, 1.0));
  return a.angle >= kMinArcAngle;
}
Vec3 arc_tangent(const BlendArc& a, const Vec3& binormal, bool at_end) {
  const Vec3 r = at_end ? a.r_end : a.r_start;
  const double dr = (norm(a.r_end) - norm(a.r_start)) / a.angle;
  return unit(cross(binormal, r) + dr * unit(r));
}

// checkTangentAngle: the blend arc must meet the circle within the kink one servo cycle allows.
bool tangent_ok(const Circle& c, const BlendArc& a, const Vec3& binormal, const Parameters& q,
                bool at_end) {
  const Vec3 u_arc = arc_tangent(a, binormal, at_end);
  const Vec3 u_circ = at_end ? c.tangent(0) : c.tangent(c.angle);
  const double angle = std::acos(std::clamp(dot(u_circ, u_arc), -1.0, 1.0));
  const double max_angle =
      kNormalAccelRatio * kKinkFactor * q.a_max / (q.v_plan / kCycle_s); // findMaxTangentAngle
  return angle <= max_angle;
}

// The blend arc as a segment (tpInitBlendArcFromPrev, tcFinalizeLength).
Segment make_arc(const Segment& prev, const Segment& next, const Parameters& q, double length) {
  Segment s;
  s.shape = Shape::Blend;
  s.length = s.nominal = length;
  s.reqvel = q.v_req;
  s.maxvel = std::min(q.v_plan, length / kCycle_s);
  s.accel = q.a_max;
  s.acc_ratio_tan = kTangentialAccelRatio;
  s.tolerance = next.tolerance;
  s.term = Term::Tangent;
  s.traverse = prev.traverse;
  return s;
}

// A consumed remainder of the first line: left shorter than kGapCycles at the corner speed.
bool consumes(const Segment& prev, double trim, double v_plan) {
  if (prev.shape != Shape::Line || prev.atspeed || prev.blend_prev) return false;
  return (prev.length - trim) / v_plan < kGapCycles * kCycle_s;
}

struct Attempt {
  Segment arc;
  Points points;
  bool consume = false;
  double line_part = 0;    // what is left of the first segment, run in the arc when consumed
  Circle circle1, circle2; // trimmed circles
};

bool line_line(Attempt& at, const Segment& prev, const Segment& next, const AxisBounds& bounds) {
  Geometry g;
  Parameters q;
  if (!init_geometry(g, prev, next)) return false;
  q.theta = g.theta_tan;
  q.l1 = std::min(prev.length, prev.nominal * kBlendDistanceFraction);
  q.l2 = next.length * kBlendDistanceFraction;
  if (!kinematics(g, q, prev, next, bounds) || !compute_parameters(q)) return false;
  at.points.trim1 = at.points.trim2 = q.d_plan;
  at.consume = consumes(prev, q.d_plan, q.v_plan);
  at.line_part = at.consume ? prev.length - q.d_plan : 0;
  at.arc = make_arc(prev, next, q, q.s_arc + at.line_part);
  return true;
}

bool line_arc(Attempt& at, const Segment& prev, const Segment& next, const AxisBounds& bounds) {
  Geometry g;
  Parameters q;
  if (!init_geometry(g, prev, next)) return false;
  const Circle& c2 = next.circle;
  spiral_fit(c2, g.p, g.u_tan2, g.centre2, g.radius2);
  q.convex2 = dot(g.p - g.centre2, g.u_tan1) >= 0;
  q.phi2_max = std::min(c2.angle / 3, q.convex2 ? g.theta_tan : kPi / 2);
  q.theta = g.theta_tan;
  if (q.convex2) {
    g.u2 = unit(c2.point(q.phi2_max / 2) - g.p);
    q.theta = std::min(q.theta, g.theta_tan - q.phi2_max / 4);
  }
  q.l1 = std::min(prev.length, prev.nominal / 2);
  q.l2 = q.convex2 ? std::sin(q.phi2_max / 4) * g.radius2 : q.phi2_max * g.radius2;
  if (!kinematics(g, q, prev, next, bounds)) return false;
  if (!parallel_units(g.binormal, c2.normal)) return false;
  if (!compute_parameters(q)) return false;
  double d_line = 0;
  Vec3 centre;
  if (!line_circle_fit(g, q, g.u1, 1, g.centre2, g.radius2, q.convex2, d_line, centre))
    return false;
  at.points.trim1 = d_line;
  at.points.trim2 = trim_angle(g.p, centre, g.centre2);
  if (at.points.trim2 > q.phi2_max) return false;
  at.consume = consumes(prev, at.points.trim1, q.v_plan);
  at.circle2 = c2;
  if (prev.length - at.points.trim1 <= 0 && !at.consume) return false;
  if (!stretch(at.circle2, c2.angle - at.points.trim2, true)) return false;
  BlendArc arc;
  const Vec3 arc_start = prev.start + (prev.length - at.points.trim1) * prev.direction;
  if (!arc_from_points(arc, arc_start, at.circle2.point(0), centre)) return false;
  at.line_part = at.consume ? prev.length - at.points.trim1 : 0;
  at.arc = make_arc(prev, next, q, arc.radius * arc.angle + at.line_part);
  return tangent_ok(at.circle2, arc, g.binormal, q, true);
}

bool arc_line(Attempt& at, const Segment& prev, const Segment& next, const AxisBounds& bounds) {
  Geometry g;
  Parameters q;
  if (!init_geometry(g, prev, next)) return false;
  const Circle& c1 = prev.circle;
  spiral_fit(c1, g.p, g.u_tan1, g.centre1, g.radius1);
  q.convex1 = dot(g.p - g.centre1, g.u_tan2) < 0;
  q.phi1_max = std::min(c1.angle * 2 / 3, q.convex1 ? g.theta_tan : kPi / 2);
  q.theta = g.theta_tan;
  if (q.convex1) {
    g.u1 = unit(g.p - c1.point(c1.angle - q.phi1_max / 2));
    q.theta = std::min(q.theta, g.theta_tan - q.phi1_max / 4);
  }
  q.l1 = q.convex1 ? std::sin(q.phi1_max / 4) * g.radius1 : q.phi1_max * g.radius1;
  q.l2 = next.nominal / 2;
  if (!kinematics(g, q, prev, next, bounds)) return false;
  if (!parallel_units(g.binormal, c1.normal)) return false;
  if (!compute_parameters(q)) return false;
  double d_line = 0;
  Vec3 centre;
  if (!line_circle_fit(g, q, g.u2, -1, g.centre1, g.radius1, q.convex1, d_line, centre))
    return false;
  at.points.trim1 = trim_angle(g.p, centre, g.centre1);
  at.points.trim2 = d_line;
  if (at.points.trim1 > q.phi1_max) return false;
  at.circle1 = c1;
  if (!stretch(at.circle1, c1.angle - at.points.trim1, false)) return false;
  if (next.length - at.points.trim2 <= 0) return false;
  BlendArc arc;
  const Vec3 arc_end = next.start + at.points.trim2 * next.direction;
  if (!arc_from_points(arc, at.circle1.point(at.circle1.angle), arc_end, centre)) return false;
  at.arc = make_arc(prev, next, q, arc.radius * arc.angle);
  return tangent_ok(at.circle1, arc, g.binormal, q, false);
}

bool arc_arc(Attempt& at, const Segment& prev, const Segment& next, const AxisBounds& bounds) {
  if (!parallel_units(prev.circle.normal, next.circle.normal)) return false;
  Geometry g;
  Parameters q;
  if (!init_geometry(g, prev, next)) return false;
  const Circle &c1 = prev.circle, &c2 = next.circle;
  spiral_fit(c1, g.p, g.u_tan1, g.centre1, g.radius1);
  spiral_fit(c2, g.p, g.u_tan2, g.centre2, g.radius2);
  g.p = c2.point(0);
  q.convex1 = dot(g.p - g.centre1, g.u_tan2) < 0;
  q.convex2 = dot(g.p - g.centre2, g.u_tan1) >= 0;
  q.phi1_max = std::min(c1.angle * 2 / 3, q.convex1 ? g.theta_tan : kPi / 2);
  q.phi2_max = std::min(c2.angle / 3, q.convex2 ? g.theta_tan : kPi / 2);
  q.theta = g.theta_tan;
  if (q.convex1) {
    g.u1 = unit(g.p - c1.point(c1.angle - q.phi1_max / 2));
    q.theta = std::min(q.theta, g.theta_tan - q.phi1_max / 4);
  }
  if (q.convex2) {
    g.u2 = unit(c2.point(q.phi2_max / 2) - g.p);
    q.theta = std::min(q.theta, g.theta_tan - q.phi2_max / 4);
  }
  if (q.theta < kPi / 12) return false;
  q.l1 = q.convex1 ? std::sin(q.phi1_max / 4) * g.radius1 : q.phi1_max * g.radius1;
  q.l2 = q.convex2 ? std::sin(q.phi2_max / 4) * g.radius2 : q.phi2_max * g.radius2;
  if (!kinematics(g, q, prev, next, bounds)) return false;
  if (!parallel_units(g.binormal, c1.normal) || !parallel_units(g.binormal, c2.normal))
    return false;
  if (!compute_parameters(q)) return false;
  // The blend arc's centre: at d1 from one circle's centre and d2 from the other's.
  const double d1 = (q.convex1 ? -q.r_plan : q.r_plan) + g.radius1;
  const double d2 = (q.convex2 ? -q.r_plan : q.r_plan) + g.radius2;
  const Vec3 c1c2 = g.centre2 - g.centre1;
  const double span = norm(c1c2);
  if (!(span > 0)) return false;
  const double cx = (-d1 * d1 + d2 * d2 - span * span) / (-2 * span);
  const double cy2 = d1 * d1 - cx * cx;
  if (!(cy2 >= 0)) return false;
  double cy = std::sqrt(cy2);
  const Vec3 uc = (1 / span) * c1c2;
  Vec3 nc = cross(g.binormal, uc);
  if (dot(g.normal, nc) < 0) nc = -1.0 * nc;
  nc = unit(nc);
  const Vec3 r_pc1 = g.centre1 - g.p;
  if (norm(r_pc1 + cx * uc - cy * nc) < norm(r_pc1 + cx * uc + cy * nc)) cy = -cy;
  const Vec3 centre = g.centre1 + cx * uc + cy * nc;
  if (norm(centre - g.p) - q.r_plan > q.tolerance) return false;
  at.points.trim1 = trim_angle(g.p, centre, g.centre1);
  at.points.trim2 = trim_angle(g.p, centre, g.centre2);
  if (at.points.trim1 > q.phi1_max || at.points.trim2 > q.phi2_max) return false;
  at.circle1 = c1;
  at.circle2 = c2;
  if (!stretch(at.circle1, c1.angle - at.points.trim1, false) ||
      !stretch(at.circle2, c2.angle - at.points.trim2, true))
    return false;
  BlendArc arc;
  if (!arc_from_points(arc, at.circle1.point(at.circle1.angle), at.circle2.point(0), centre))
    return false;
  at.arc = make_arc(prev, next, q, arc.radius * arc.angle);
  return tangent_ok(at.circle1, arc, g.binormal, q, false) &&
         tangent_ok(at.circle2, arc, g.binormal, q, true);
}

// Applies a blend arc that won: shortens both segments (or drops what is left of the first).
void apply_arc(Segment& prev, Segment& next, const Attempt& at) {
  if (prev.shape == Shape::Line) {
    if (!at.consume) {
      prev.length -= at.points.trim1;
      prev.end = prev.start + prev.length * prev.direction;
    }
  } else {
    prev.circle = at.circle1;
    prev.length = circle_length(prev.circle);
  }
  if (next.shape == Shape::Line) {
    next.start = next.start + at.points.trim2 * next.direction;
    next.length = norm(next.end - next.start);
  } else {
    next.circle = at.circle2;
    next.length = circle_length(next.circle);
  }
  set_term(prev, next, Term::Tangent);
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
  const double radius = dot(c.r_helix, c.r_helix) / r_spiral + r_spiral;
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
  Vec3 t = cross(normal, r);
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
    Attempt at;
    bool made = false;
    if (prev.term == Term::Parabolic && !prev.rotary && !next.rotary) {
      if (prev.shape == Shape::Line && next.shape == Shape::Line)
        made = line_line(at, prev, next, bounds);
      else if (prev.shape == Shape::Line && next.shape == Shape::Circle)
        made = line_arc(at, prev, next, bounds);
      else if (prev.shape == Shape::Circle && next.shape == Shape::Line)
        made = arc_line(at, prev, next, bounds);
      else if (prev.shape == Shape::Circle && next.shape == Shape::Circle)
        made = arc_arc(at, prev, next, bounds);
    }
    if (choose_blend(prev, next, made ? at.arc.maxvel : 0) == Choice::Arc) {
      apply_arc(prev, next, at);
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
