// Time taken by the commands that are not moves: dwell, tool change, spindle ramps, stops.
// Keeps the spindle's running speed from command to command, since a ramp's time depends on
// the speed it starts from.
#pragma once

#include <string>

#include "ncjoule/gcode.hpp"
#include "ncjoule/machine.hpp"

namespace ncjoule::kinematics_detail {

struct EventTiming {
  double duration_s = 0;
  bool stops_motion = false; // the path comes to rest before it (no blending across)
  std::string note;
};

class MachineEvents {
public:
  explicit MachineEvents(const Kinematics& machine) : machine_(machine) {}
  EventTiming time(const CanonCommand& command);

private:
  double ramp_to(double signed_rpm); // seconds to go from the current speed to signed_rpm
  double tool_change(int tool);      // seconds of an M6 for `tool`, by the sequence it runs

  const Kinematics& machine_;
  double programmed_rpm_ = 0; // last S word
  double running_rpm_ = 0;    // signed: + clockwise, - counter-clockwise, 0 stopped
  int spindle_tool_ = -1;     // the tool an M6 of this program put in the spindle; -1 none yet
};

} // namespace ncjoule::kinematics_detail
