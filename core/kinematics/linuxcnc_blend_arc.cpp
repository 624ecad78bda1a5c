// Blend arcs as LinuxCNC 2.9 makes them (blendmath.c: blendInit3FromLineLine and its siblings,
// blendComputeParameters, blendFindPoints3, the arc fits): the arc between two segments, its
// speed, and how much of each segment it takes (linuxcnc_blend_arc.hpp).
#include "linuxcnc_blend_arc.hpp"

#include "linuxcnc_blend_common.hpp"

namespace ncjoule::kinematics_detail::linuxcnc {
namespace {

struct Geometry { // BlendGeom3
  Vec3 u1 = Vec3::Zero(), u2 = Vec3::Zero(), u_tan1 = Vec3::Zero(), u_tan2 = Vec3::Zero(),
       p = Vec3::Zero(), normal = Vec3::Zero(), binormal = Vec3::Zero(), centre1 = Vec3::Zero(),
       centre2 = Vec3::Zero();
  double radius1 = 0, radius2 = 0, theta_tan = 0;
};

struct Parameters { // BlendParameters
  double tolerance = 0, l1 = 0, l2 = 0, v_req = 0, v_goal = 0, a_max = 0, a_n_max = 0;
  double theta = 0, phi = 0, phi1_max = 0, phi2_max = 0;
  bool convex1 = false, convex2 = false;
  double v_plan = 0, r_plan = 0, d_plan = 0, s_arc = 0;
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
  g.binormal = unit(g.u_tan1.cross(g.u_tan2));
  g.normal = unit(g.u_tan2 - g.u_tan1);
  return true;
}

// Local circle through P fitted to a spiral (findSpiralApproximation).
void spiral_fit(const Circle& c, const Vec3& p, const Vec3& u_tan, Vec3& centre, double& radius) {
  centre = c.centre + (c.spiral / c.angle) * u_tan;
  radius = (p - centre).norm();
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
    const double base = (v_max2 * g.u2 - v_max1 * g.u1).norm();
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
  return std::acos(std::clamp(unit(p - centre).dot(unit(arc_centre - centre)), -1.0, 1.0));
}

// Where a blend arc of radius R touching a line meets a circle (blendLineArcPostProcess and
// blendArcLinePostProcess): distance along the line from P (signed by `along`) and the centre.
bool line_circle_fit(const Geometry& g, const Parameters& q, const Vec3& u_line, double along,
                     const Vec3& circle_centre, double circle_radius, bool convex, double& d_line,
                     Vec3& arc_centre) {
  const double d = (convex ? -q.r_plan : q.r_plan) + circle_radius;
  const Vec3 n = unit(g.binormal.cross(u_line));
  const Vec3 r_pc = circle_centre - g.p;
  const double c_u = r_pc.dot(u_line) * along, c_n = r_pc.dot(n);
  const double b = 2 * c_u, c = c_u * c_u - d * d + (q.r_plan - c_n) * (q.r_plan - c_n);
  const double disc = b * b - 4 * c;
  if (disc < 0) return false;
  const double root = std::sqrt(disc);
  d_line = std::min(std::abs((-b + root) / 2), std::abs((-b - root) / 2));
  const Vec3 r = (along * -d_line) * u_line + q.r_plan * n;
  arc_centre = g.p + r;
  return r.norm() - q.r_plan <= q.tolerance;
}

// Trims a circle to `new_angle`, from its start or its end (pmCircleStretch); helices refuse.
bool stretch(Circle& c, double new_angle, bool from_start) {
  if (new_angle <= 1e-10 || c.r_helix.squaredNorm() > 1e-6) return false;
  if (from_start) {
    const Vec3 new_start = c.point(c.angle - new_angle);
    c.r_tan = new_start - c.centre;
    c.r_perp = c.normal.cross(c.r_tan);
    c.radius = c.r_tan.norm();
  }
  c.spiral *= new_angle / c.angle;
  c.angle = new_angle;
  return true;
}

double circle_length(const Circle& c) {
  const double planar = (c.radius + c.spiral / 2) * c.angle;
  return std::sqrt(planar * planar + c.r_helix.squaredNorm());
}

// The spherical arc through two points around a centre: its angle, radius and the unit tangent
// at either end (arcInitFromPoints, arcTangent), for the tangency check against a circle.
struct BlendArc {
  double radius = 0, angle = 0;
  Vec3 r_start = Vec3::Zero(), r_end = Vec3::Zero();
};
bool arc_from_points(BlendArc& a, const Vec3& start, const Vec3& end, const Vec3& centre) {
  a.r_start = start - centre;
  a.r_end = end - centre;
  const double r0 = a.r_start.norm(), r1 = a.r_end.norm();
  if (r0 < 1e-12 || r1 < 1e-12) return false;
  a.radius = r0;
  a.angle = std::acos(std::clamp(((1 / r0) * a.r_start).dot((1 / r1) * a.r_end), -1.0, 1.0));
  return a.angle >= kMinArcAngle;
}
Vec3 arc_tangent(const BlendArc& a, const Vec3& binormal, bool at_end) {
  const Vec3 r = at_end ? a.r_end : a.r_start;
  const double dr = (a.r_end.norm() - a.r_start.norm()) / a.angle;
  return unit(binormal.cross(r) + dr * unit(r));
}

// checkTangentAngle: the blend arc must meet the circle within the kink one servo cycle allows.
bool tangent_ok(const Circle& c, const BlendArc& a, const Vec3& binormal, const Parameters& q,
                bool at_end) {
  const Vec3 u_arc = arc_tangent(a, binormal, at_end);
  const Vec3 u_circ = at_end ? c.tangent(0) : c.tangent(c.angle);
  const double angle = std::acos(std::clamp(u_circ.dot(u_arc), -1.0, 1.0));
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

bool line_line(ArcAttempt& at, const Segment& prev, const Segment& next, const AxisBounds& bounds) {
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

bool line_arc(ArcAttempt& at, const Segment& prev, const Segment& next, const AxisBounds& bounds) {
  Geometry g;
  Parameters q;
  if (!init_geometry(g, prev, next)) return false;
  const Circle& c2 = next.circle;
  spiral_fit(c2, g.p, g.u_tan2, g.centre2, g.radius2);
  q.convex2 = (g.p - g.centre2).dot(g.u_tan1) >= 0;
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
  Vec3 centre = Vec3::Zero();
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

bool arc_line(ArcAttempt& at, const Segment& prev, const Segment& next, const AxisBounds& bounds) {
  Geometry g;
  Parameters q;
  if (!init_geometry(g, prev, next)) return false;
  const Circle& c1 = prev.circle;
  spiral_fit(c1, g.p, g.u_tan1, g.centre1, g.radius1);
  q.convex1 = (g.p - g.centre1).dot(g.u_tan2) < 0;
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
  Vec3 centre = Vec3::Zero();
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

bool arc_arc(ArcAttempt& at, const Segment& prev, const Segment& next, const AxisBounds& bounds) {
  if (!parallel_units(prev.circle.normal, next.circle.normal)) return false;
  Geometry g;
  Parameters q;
  if (!init_geometry(g, prev, next)) return false;
  const Circle &c1 = prev.circle, &c2 = next.circle;
  spiral_fit(c1, g.p, g.u_tan1, g.centre1, g.radius1);
  spiral_fit(c2, g.p, g.u_tan2, g.centre2, g.radius2);
  g.p = c2.point(0);
  q.convex1 = (g.p - g.centre1).dot(g.u_tan2) < 0;
  q.convex2 = (g.p - g.centre2).dot(g.u_tan1) >= 0;
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
  const double span = c1c2.norm();
  if (!(span > 0)) return false;
  const double cx = (-d1 * d1 + d2 * d2 - span * span) / (-2 * span);
  const double cy2 = d1 * d1 - cx * cx;
  if (!(cy2 >= 0)) return false;
  double cy = std::sqrt(cy2);
  const Vec3 uc = (1 / span) * c1c2;
  Vec3 nc = g.binormal.cross(uc);
  if (g.normal.dot(nc) < 0) nc = -1.0 * nc;
  nc = unit(nc);
  const Vec3 r_pc1 = g.centre1 - g.p;
  if ((r_pc1 + cx * uc - cy * nc).norm() < (r_pc1 + cx * uc + cy * nc).norm()) cy = -cy;
  const Vec3 centre = g.centre1 + cx * uc + cy * nc;
  if ((centre - g.p).norm() - q.r_plan > q.tolerance) return false;
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

} // namespace

bool try_blend_arc(ArcAttempt& at, const Segment& prev, const Segment& next,
                   const AxisBounds& bounds) {
  if (prev.shape == Shape::Line && next.shape == Shape::Line)
    return line_line(at, prev, next, bounds);
  if (prev.shape == Shape::Line && next.shape == Shape::Circle)
    return line_arc(at, prev, next, bounds);
  if (prev.shape == Shape::Circle && next.shape == Shape::Line)
    return arc_line(at, prev, next, bounds);
  if (prev.shape == Shape::Circle && next.shape == Shape::Circle)
    return arc_arc(at, prev, next, bounds);
  return false;
}

// Applies a blend arc that won: shortens both segments (or drops what is left of the first).
void apply_blend_arc(Segment& prev, Segment& next, const ArcAttempt& at) {
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
    next.length = (next.end - next.start).norm();
  } else {
    next.circle = at.circle2;
    next.length = circle_length(next.circle);
  }
  set_term(prev, next, Term::Tangent);
}

} // namespace ncjoule::kinematics_detail::linuxcnc
