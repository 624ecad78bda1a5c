// Internal: cutter radius compensation (G41/G42) as LinuxCNC's interpreter makes it: the
// geometry of entry moves, corners (straight and arc, convex and concave) and the queue that
// holds the last compensated move until the next one says where its corner is.
//
// Everything here works in the plane of compensation: (first, second) = (X, Y) under G17 and
// (Z, X) under G18, as the centres of arcs are given in CanonCommand.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::detail {

// The side of the programmed path the tool keeps to, looking along the motion.
enum class CompSide : std::int8_t { Off = 0, Left = 1, Right = -1 };

struct PlanePoint {
  double a = 0, b = 0; // first and second axis of the plane
};
PlanePoint plane_point(const Pose& p, Plane plane);
void set_plane_point(Pose& p, Plane plane, PlanePoint q);

// Signed sweep (radians, + counter-clockwise) of an arc about `centre` from `start` to `end`
// turning `turn` times (+ counter-clockwise, - clockwise; 1 = less than one turn); 0 for turn 0.
double arc_sweep(PlanePoint start, PlanePoint centre, int turn, PlanePoint end);

// Angles below this (radians) make no corner; a turn past half a circle by more is concave
// (LinuxCNC's TOLERANCE_CONCAVE_CORNER).
constexpr double kCornerTolerance = 0.05;

// Whether the tool runs inside an arc turning `turn` (+ counter-clockwise) with comp on `side`.
inline bool tool_inside_arc(CompSide side, int turn) {
  return (side == CompSide::Left && turn > 0) || (side == CompSide::Right && turn < 0);
}

// The outcome of one piece of geometry: its point, or why the tool cannot get there.
struct CompPoint {
  PlanePoint point;
  std::string error; // empty when the point is good
};

// Entry move to `end` from `start` (the tool's centre, not yet offset): where the tool ends, a
// radius off the end across the move's direction. The error when the move is no longer than the
// radius.
CompPoint straight_entry_end(PlanePoint start, PlanePoint end, double radius, CompSide side);

// Entry arc from `start` to the programmed `end` about `centre`: the arc the tool takes, through
// `start` and a radius off `end` (its end and new centre), or why it has none.
struct EntryArc {
  PlanePoint end, centre;
  std::string error;
};
EntryArc arc_entry(PlanePoint start, PlanePoint end, PlanePoint centre, int turn, double radius,
                   CompSide side, double spiral_tolerance);

// A compensated arc as the queue holds it (for the corners that follow one).
struct HeldArc {
  PlanePoint end, centre;
  int turn = 0;
};

// Where the tool stops at a concave corner between two straights: back along the tool's path
// from `tool` (a radius off `from`, the programmed corner, across the last move) by the retreat
// the corner's angle makes. `beta` and the directions are those of the straight's corner test.
CompPoint concave_line_line(PlanePoint tool, double theta_gamma, double beta, double radius);
// Where an arc's compensated path meets the next straight (programmed from `from` in direction
// `direction`) at a concave corner.
CompPoint concave_arc_line(const HeldArc& arc, PlanePoint from, double direction, double radius,
                           CompSide side);
// Where a straight's compensated path meets the next arc (programmed centre `centre`, radius
// `arc_radius`, turning `turn`) at a concave corner. `theta` is the direction of the last move
// at its end, `beta` the corner's angle.
CompPoint concave_line_arc(PlanePoint centre, double arc_radius, int turn, double theta,
                           double beta, double radius, CompSide side);
// Where two compensated arcs meet at a concave corner.
CompPoint concave_arc_arc(const HeldArc& previous, PlanePoint centre, double arc_radius, int turn,
                          double radius, CompSide side);

// The moves compensation holds back, and what the control issued after them, in order: the last
// move's end is only known once the next move shows its corner (LinuxCNC's interp_queue).
class CompQueue {
public:
  using Release = std::function<void(CanonCommand&&)>;
  struct Held {
    CanonCommand command;
    PlanePoint direction; // straights: the direction the end may move along without turning back
    double sweep = 0;     // arcs: the programmed sweep a moved end may not exceed (0: unchecked)
  };

  bool empty() const { return items_.empty(); }
  // The first held move (LinuxCNC looks at the front of its queue for the previous move).
  const Held* front() const { return items_.empty() ? nullptr : &items_.front(); }
  void hold(Held item) { items_.push_back(std::move(item)); }
  // The point the held moves start from, for the checks of a moved end.
  void set_start(PlanePoint p) { start_ = p, start_known_ = true; }
  // Issues everything held, as it is.
  void release(const Release& out);
  // Moves the end of every held move in the plane to `p` (a concave corner: the move stops
  // short) and issues them. The error when a move would turn back or an arc sweep further than
  // programmed: the tool cannot reach the corner without gouging. `unit` is mm per program unit.
  std::string move_end_and_release(PlanePoint p, Plane plane, double unit, const Release& out);

private:
  std::vector<Held> items_;
  PlanePoint start_;
  bool start_known_ = false;
};

// The interpreter's state of compensation. The interpreter's own position stays the programmed
// one; `tool` is where the compensated tool is.
struct CutterCompState {
  CompSide side = CompSide::Off;
  double radius = 0; // mm; 0 with side set: on, but moves are taken as programmed
  Plane plane = Plane::XY;
  bool first = true; // the next move is the entry move
  Pose tool;         // where the compensated tool is: the end of the last compensated move
  // After G40 or a move compensation could not make, the tool is not where the program is: the
  // next move starts here.
  std::optional<Pose> exit_from;
  bool arc_not_allowed = false; // just after G40 the move must be straight (LinuxCNC)
  bool suspended = false;       // a problem: moves as programmed until G40
  CompQueue queue;
  bool on() const { return side != CompSide::Off; }
  bool offsetting() const { return on() && radius > 0 && !suspended; }
};

} // namespace ncjoule::detail
