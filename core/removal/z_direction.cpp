// Which way a program's Z runs (ZDirectionScan), and its moves as removal sees them on a machine
// whose +Z points into the work (mirrored_z).
#include <algorithm>

#include "ncjoule/removal.hpp"

namespace ncjoule {

void ZDirectionScan::add(const CanonCommand& c) {
  // Moves across XY only: a plunge or a retract in Z alone starts or ends at the clearance, and
  // says nothing of which side of the cuts it is on.
  if (!travels_in_xy(c)) return;
  if (c.kind == CanonKind::Feed || c.kind == CanonKind::Arc) {
    // A helix's or a ramp's Z runs from its start to its end: its ends bound it.
    cut_ = true;
    lowest_cut_ = std::min({lowest_cut_, c.start.z, c.end.z});
  } else if (c.kind == CanonKind::Traverse && c.start_known) {
    rapid_ = true;
    highest_rapid_ = std::max({highest_rapid_, c.start.z, c.end.z});
  }
}

bool ZDirectionScan::points_down() const {
  constexpr double kMarginMm = 1e-6;
  return rapid_ && cut_ && highest_rapid_ < lowest_cut_ - kMarginMm;
}

CanonCommand mirrored_z(const CanonCommand& c) {
  CanonCommand m = c;
  m.start.z = -c.start.z;
  m.end.z = -c.end.z;
  if (c.kind == CanonKind::Arc) {
    // The centre's Z, and the turn of an arc in a plane that holds Z: a mirror reverses it.
    if (c.plane == Plane::XZ) {
      m.centre_first = -c.centre_first; // Z, X
      m.rotation = -c.rotation;
    } else if (c.plane == Plane::YZ) {
      m.centre_second = -c.centre_second; // Y, Z
      m.rotation = -c.rotation;
    }
  }
  return m;
}

} // namespace ncjoule
