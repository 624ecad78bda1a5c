// Internal: arcs that turn the long way round. CAM posts write arcs of at most a half turn, or
// whole circles; a program whose arcs mostly turn well past a half turn has G2 and G3 swapped,
// as a post writes them when it exchanges or mirrors axes (X for Y, or Y scaled by -1) without
// exchanging the arc directions. The controller runs each arc as written, the long way round,
// and the estimate times it so: the check says why a program takes far longer than its CAM said.
#pragma once

#include <optional>

#include "ncjoule/gcode.hpp"

namespace ncjoule::estimate_detail {

class LongArcCheck {
public:
  void add(const CanonCommand& command);
  // A warning when at least kMinArcs arcs were seen, more than half of them long.
  std::optional<Diagnostic> verdict(const std::string& file) const;

  static constexpr int kMinArcs = 10;
  // Past a half turn by this much: an arc split at its middle by a post stays below it.
  static constexpr double kLongSweepDeg = 200;

private:
  int arcs_ = 0, long_ = 0;
  int first_long_line_ = -1;
};

} // namespace ncjoule::estimate_detail
