// Test programs built by hand as canonical commands, and a timeline for them that moves at
// constant speed (feed or a fixed rapid rate) and samples every move evenly with
// point_on_move(): removal's tests do not depend on the interpreter or the planner.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "ncjoule/removal.hpp"

namespace ncjoule::test {

class ProgramBuilder {
public:
  ProgramBuilder& tool(int number);
  ProgramBuilder& feed_rate(double mm_per_min);
  ProgramBuilder& rapid(double x, double y, double z);
  ProgramBuilder& feed(double x, double y, double z);
  // XY-plane arc or helix to (x, y, z) around (cx, cy); rotation as in CanonCommand
  // (+1 counter-clockwise, -1 clockwise).
  ProgramBuilder& arc(double x, double y, double z, double cx, double cy, int rotation);
  // An arc in another plane: centre (c1, c2) in the plane's axes (Z/X for G18, Y/Z for G19).
  ProgramBuilder& arc_in(Plane plane, double x, double y, double z, double c1, double c2,
                         int rotation);
  const std::vector<CanonCommand>& commands() const { return commands_; }

private:
  CanonCommand& add(CanonKind kind, double x, double y, double z);
  std::vector<CanonCommand> commands_;
  Pose at_;
  ModalState state_;
};

// Every move at constant speed: feeds at state.feed (mm/min), rapids at rapid_mm_s. Moves are
// cut into equal steps no longer than max_step_mm (end points only when it is 0).
Timeline constant_speed_timeline(const std::vector<CanonCommand>& commands, double max_step_mm,
                                 double rapid_mm_s = 200);

Tool flat_end_mill(int number, double diameter);
Tool ball_end_mill(int number, double diameter);
Tool drill(int number, double diameter, double point_angle_deg);

// The 12 triangles of an axis-aligned box.
TriangleMesh box_mesh(const Box3& box);
std::string ascii_stl(const TriangleMesh& mesh);
std::string binary_stl(const TriangleMesh& mesh);

// A fresh directory for this test run's files.
std::string temp_dir();

} // namespace ncjoule::test

namespace ncjoule::test {
// Prints a measured number to stderr when NCJOULE_TEST_VERBOSE is set (tests stay quiet
// otherwise).
void report(const std::string& what, double value);
} // namespace ncjoule::test
