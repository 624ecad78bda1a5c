#include "long_arc_check.hpp"

#include <cmath>
#include <numbers>

namespace ncjoule::estimate_detail {

void LongArcCheck::add(const CanonCommand& c) {
  if (c.kind != CanonKind::Arc) return;
  // Whole circles and arcs of extra turns are meant to go round: they are not counted.
  if (c.rotation > 1 || c.rotation < -1) return;
  const double sweep_deg = std::abs(arc_geometry(c).sweep) * 180 / std::numbers::pi;
  if (!(sweep_deg < 360 - 1e-6)) return;
  ++arcs_;
  if (sweep_deg > kLongSweepDeg) {
    if (long_ == 0) first_long_line_ = c.line;
    ++long_;
  }
}

std::optional<Diagnostic> LongArcCheck::verdict(const std::string& file) const {
  if (arcs_ < kMinArcs || 2 * long_ <= arcs_) return std::nullopt;
  return Diagnostic{
      Severity::Warning, file, first_long_line_ + 1, 0,
      std::to_string(long_) + " of the program's " + std::to_string(arcs_) +
          " arcs turn more than " + std::to_string(int(kLongSweepDeg)) +
          " degrees (CAM posts write about a half turn at most, or whole circles): G2 and G3 look "
          "swapped, as a post "
          "writes them when it exchanges or mirrors axes without exchanging the arc directions. "
          "The controller runs each arc as written, the long way round, and it is timed so: "
          "check the post before running the program"};
}

} // namespace ncjoule::estimate_detail
