// Blend arcs (LinuxCNC 2.9's blendmath.c): where a corner under G64 is rounded by an arc within
// the blend tolerance, the arc, its speed and the trims of the two segments. join()
// (linuxcnc_blend.hpp) tries one and keeps it when it is faster than the parabolic blend or the
// tangent run.
#pragma once

#include "linuxcnc_blend.hpp"

namespace ncjoule::kinematics_detail::linuxcnc {

// Where the arc meets the two segments, and how much it takes off each.
struct BlendPoints { // BlendPoints3
  Vec3 arc_start = Vec3::Zero(), arc_end = Vec3::Zero(), arc_centre = Vec3::Zero();
  double trim1 = 0, trim2 = 0;
};

// A blend arc that could be made: the arc as a segment of its own, where it meets the segments,
// and what is left of them.
struct ArcAttempt {
  Segment arc;
  BlendPoints points;
  bool consume = false;
  double line_part = 0;    // what is left of the first segment, run in the arc when consumed
  Circle circle1, circle2; // trimmed circles
};

// The blend arc between `prev` and `next` (line-line, line-arc, arc-line, arc-arc) within their
// tolerance and the axis bounds; false when none can be made (out of plane, too small, ...).
bool try_blend_arc(ArcAttempt& at, const Segment& prev, const Segment& next,
                   const AxisBounds& bounds);

// Shortens both segments by the arc (or drops what is left of the first, run in the arc).
void apply_blend_arc(Segment& prev, Segment& next, const ArcAttempt& at);

} // namespace ncjoule::kinematics_detail::linuxcnc
