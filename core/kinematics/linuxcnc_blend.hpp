// How LinuxCNC 2.9's trajectory planner joins one segment to the next (src/emc/tp: tp.c,
// blendmath.c, tc.c), as far as it decides how long the path takes.
//
// LinuxCNC plans segments ("TCs") one at a time as they arrive. When a move arrives, the one
// before it is settled:
//  - a change between G0 and G1 stops the path, and so does a reversal within 2 degrees;
//  - two segments that meet at a very small kink run through it ("tangent"), slowing to the
//    speed at which the kink stays within a tenth of the acceleration limit;
//  - otherwise, under G64, a blend arc joins them: tolerance min(P, L1/4, L2/4) (G64 without P
//    has no P), blend distance at most half of each segment, radius from the tolerance, corner
//    speed sqrt(0.866 a R) at most the higher feed of the two. The segments are shortened by the
//    blend distance; what is left of the first one, if shorter than 4 servo cycles at the corner
//    speed, is run as part of the arc. The arc accelerates at a/2 along the path;
//  - if no arc can be made (rotary axes, a corner out of the arc's plane, an arc too small) the
//    faster of a parabolic blend (both segments at a/2, a corner speed from the segment lengths)
//    and a tangent run through the kink is taken;
//  - under G61 the path stops at every corner that is not nearly tangent, and both segments keep
//    90% of their acceleration (the kink allowance); G61.1 stops everywhere.
// A segment that is still waiting for its successor is marked for a parabolic blend under G64,
// and keeps that mark (and a/2) when the queue empties before another move arrives. A parabolic
// blend is timed as a junction speed and a length the two segments run side by side.
//
// The rules here work on one pair of segments; linuxcnc_path.cpp feeds them the program.
#pragma once

#include <cstdint>
#include <optional>

#include "move_limits.hpp"

namespace ncjoule::kinematics_detail::linuxcnc {

// Planner constants at LinuxCNC's defaults ([TRAJ] and motion module parameters).
inline constexpr double kCycle_s = 0.001;                       // servo and trajectory period
inline constexpr double kTangentialAccelRatio = 0.5;            // BLEND_ACC_RATIO_TANGENTIAL
inline constexpr double kNormalAccelRatio = 0.8660254037844386; // sqrt(1 - 0.5^2)
inline constexpr double kKinkRatio = 0.1;                       // arc_blend_tangent_kink_ratio
inline constexpr int kGapCycles = 4;                            // arc_blend_gap_cycles
inline constexpr double kRampCutoff_s = 0.01;                   // 1 / arc_blend_ramp_freq (100 Hz)
inline constexpr double kMinSegmentCycles = 1.02;               // TP_MIN_SEGMENT_CYCLES
inline constexpr double kBlendDistanceFraction = 0.5;           // BLEND_DIST_FRACTION
inline constexpr double kToleranceFraction = 0.25;              // tcFindBlendTolerance
// The tolerance LinuxCNC's canon layer starts with (INIT_CANON): G64 P0.001 inch. The planner
// starts with none; a canned cycle hands it over when it restores the path mode.
inline constexpr double kStartupTolerance_mm = 0.0254;
// The time LinuxCNC's task takes to run a code it waits on (spindle, coolant, offsets, dwell,
// messages) with the machine at rest, beyond the code's own time: its 1 ms task and I/O cycles
// (measured: 2.6 to 4.6 ms).
inline constexpr double kTaskLatency_s = 0.003;

// The unit vector along a; zero stays zero. Scaled by the reciprocal of the length, as
// posemath's pmCartUnit does (not divided: the last bit differs).
Vec3 unit(const Vec3& a);

// A circle, helix or planar spiral as LinuxCNC describes one (posemath's PmCircle): the point at
// angle phi is centre + (radius + spiral * phi / angle) * (cos phi, sin phi in the plane of
// r_tan and r_perp, normalised) + r_helix * phi / angle.
struct Circle {
  Vec3 centre = Vec3::Zero(), normal = Vec3::Zero(), r_tan = Vec3::Zero(), r_perp = Vec3::Zero(),
       r_helix = Vec3::Zero();
  double radius = 0, spiral = 0, angle = 0;

  Vec3 point(double phi) const;
  Vec3 tangent(double phi) const; // unit
};

enum class Term : std::uint8_t { Stop, Exact, Parabolic, Tangent }; // how a segment ends
enum class Shape : std::uint8_t { Line, Circle, Blend };

// One segment of LinuxCNC's queue, with what its timing depends on.
struct Segment {
  Shape shape = Shape::Line;
  Vec3 start = Vec3::Zero(), end = Vec3::Zero(),
       direction = Vec3::Zero(); // lines: current end points (after trimming), unit direction
  Circle circle;                 // circles
  double length = 0;             // current length (LinuxCNC's target)
  double nominal = 0;            // length as programmed
  double reqvel = 0;             // requested speed: the feed, at most maxvel
  double maxvel = 0;             // highest speed the machine allows along it
  double accel = 0;              // path acceleration limit before the reductions below
  double acc_ratio_tan = kTangentialAccelRatio; // circles and blend arcs
  double tolerance = 0;                         // G64 P; 0 = none given
  double kink_vel = -1;                         // speed cap at a kink into the next; < 0 none
  double kink_reduce = 0, kink_reduce_prev = 0; // acceleration given up to kinks at either end
  double overlap = 0; // mm run in parallel with a neighbour in parabolic blends: not timed
  Term term = Term::Parabolic;
  bool blend_prev = false;    // the segment before blends into this one parabolically
  bool traverse = false;      // G0
  bool rotary = false;        // moves A/B/C: no blend arcs, no tangent runs
  bool atspeed = false;       // first feed after a spindle start: the path stops before it, and
                              // it is never consumed by a blend
  bool after_tangent = false; // entered tangentially: held to a length per 1.02 servo cycles

  Vec3 start_tangent() const;
  Vec3 end_tangent() const;
  // Tangential acceleration limit with the reductions in force (kinks, parabolic blends, the
  // share of a circle's acceleration left after its centripetal part).
  double tangential_accel() const;
  // Highest speed the segment runs at: the feed, the machine, one length per servo cycle.
  double target_vel() const;
};

struct AxisBounds {
  Vec3 accel = Vec3::Zero(); // per-axis acceleration limits (mm/s^2)
  Vec3 vel = Vec3::Zero();   // per-axis speed limits (mm/s)
};

// The outcome of joining `prev` to `next`.
struct Join {
  std::optional<Segment> blend; // a blend arc between them, run as a segment of its own
  bool consumed = false;        // what was left of prev is part of the blend arc
  double consumed_length = 0;   // its length, at the start of the blend arc
  double parabolic_vel = 0;     // prev->term == Parabolic: junction speed that times the blend
};

// Settles the junction between `prev` (waiting in the queue) and `next` (just arrived), as
// tpAddLine/tpAddCircle do: mode changes, kinks, blend arcs, parabolic blends, early stops.
// Changes both segments (lengths, ends, marks); `prev` is final afterwards.
Join join(Segment& prev, Segment& next, const AxisBounds& bounds);

} // namespace ncjoule::kinematics_detail::linuxcnc
