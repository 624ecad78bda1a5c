// LinuxCNC's naive-CAM detector (emccanon.cc, see_segment/linkable/flush_segments): under
// G64 P Q (Q defaults to P), consecutive G1 end points that stay within Q of the straight line
// from the first start to the newest end are sent to the planner as one move; up to 101 points.
// An XY arc whose chord deviates less than Q from it is taken as two such points (its middle and
// its end). Anything else the interpreter sends (a rapid, another arc, a new F, G61/G64, ...)
// closes the group.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::kinematics_detail::linuxcnc {

// One line of the program's share of a merged move.
struct Member {
  std::size_t command = 0;
  double length = 0; // mm of the merged path that belong to it
};

// A straight move as the planner receives it: one G1, or several merged.
struct MergedLine {
  Pose start, end;
  const CanonCommand* last = nullptr; // the last command merged (its state and feed apply)
  std::vector<Member> members;
};

class NaiveCam {
public:
  using Sink = std::function<void(MergedLine&&)>;
  explicit NaiveCam(Sink sink) : sink_(std::move(sink)) {}

  // Offers a feed move (G1, or an arc that qualifies as two points) under the naive-CAM
  // tolerance in force (0: none); false when the detector does not take it (the caller then
  // flushes and sends the move on its own).
  bool offer(std::size_t index, const CanonCommand& move, double tolerance);
  // Sends what is held as one move.
  void flush();

private:
  struct Point {
    Pose at;
    std::size_t command;
  };
  bool linkable(const Pose& p, double tolerance) const;
  // A point the path reaches, coming from `from` (where a new group starts).
  void see(const Pose& from, const Pose& p, std::size_t index, const CanonCommand& move,
           double tolerance);

  Sink sink_;
  Pose start_; // where the held group starts
  std::vector<Point> points_;
  const CanonCommand* last_ = nullptr;
};

} // namespace ncjoule::kinematics_detail::linuxcnc
