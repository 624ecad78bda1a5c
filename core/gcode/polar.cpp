// G16/G15 polar coordinates, as the Fanuc family and Mach3 read them: under G16 the selected
// plane's first axis word is a radius and its second an angle in degrees, counterclockwise from
// the first axis (G17: X radius, Y angle; G18: Z radius, X angle; G19: Y radius, Z angle).
//
// Fanuc (Series 16/18 Operator's Manual, 9.2 "Polar coordinate command (G15, G16)"): a radius
// given under G90 is measured from the work coordinate system's zero, one given under G91 from
// the current position; the angle is absolute under G90, an increment of the current one under
// G91. A word left out keeps the current point's radius or angle about the work zero (Mitsubishi
// M700 manual, 6.12, says the same). G10, G52, G92, G53 and G28/G30's points are not polar, nor
// are I, J, K. Mach3: the pole is where the tool was when G16 was read.
//
// The words become Cartesian words before any move reads them, so that lines, arcs given by R
// and canned cycles' holes (a bolt circle: "G16", "G81 X50 Y0", "Y60", "Y120", ...) all see the
// point the control goes to.
#include <cmath>
#include <numbers>

#include "interpreter_impl.hpp"

namespace ncjoule::detail {
namespace {

struct PlaneWords {
  char radius, angle; // word letters
  double Pose::*a;    // the radius's axis
  double Pose::*b;    // the angle's 90-degree axis
};

PlaneWords plane_words(Plane plane) {
  switch (plane) {
  case Plane::XZ:
    return {'z', 'x', &Pose::z, &Pose::x};
  case Plane::YZ:
    return {'y', 'z', &Pose::y, &Pose::z};
  case Plane::XY:
    break;
  }
  return {'x', 'y', &Pose::x, &Pose::y};
}

constexpr double kDegree = std::numbers::pi / 180.0;

} // namespace

void Interpreter::polar_mode(bool on, int column) {
  if (!dialect_.polar_g16) {
    if (on)
      warning(column, "G16 (polar coordinates) is no code of the " + dialect_.name +
                          " dialect: the axis words that follow are read as Cartesian (give "
                          "--dialect fanuc or mach3 if the program was written for one)");
    return;
  }
  polar_ = on;
  if (!on) return;
  polar_pole_ = dialect_.polar_pole_at_g16 ? pos_ : Pose{};
  const PlaneWords w = plane_words(state_.plane);
  const double da = pos_.*w.a - polar_pole_.*w.a, db = pos_.*w.b - polar_pole_.*w.b;
  polar_angle_deg_ = da == 0 && db == 0 ? 0.0 : std::atan2(db, da) / kDegree;
}

void Interpreter::polar_words(BlockValues& v) {
  if (!polar_) return;
  const PlaneWords w = plane_words(state_.plane);
  if (!v.has(w.radius) && !v.has(w.angle)) return;
  // Setting offsets and machine coordinates, and G28/G30's intermediate points, stay Cartesian.
  for (int code : v.g)
    if (code == 100 || code == 520 || code == 920 || code == 530 || code == 280 || code == 300 ||
        code == 681 || code == 680)
      return;
  const double unit = state_.inch ? 25.4 : 1.0;
  // Fanuc: a radius given under G91 is measured from the current point; otherwise from the work
  // zero. Mach3: always from G16's point.
  Pose pole = polar_pole_;
  if (!dialect_.polar_pole_at_g16) pole = incremental_ && v.has(w.radius) ? pos_ : Pose{};
  const double here_a = pos_.*w.a, here_b = pos_.*w.b;
  const double da = here_a - pole.*w.a, db = here_b - pole.*w.b;
  // A word left out keeps the current point's radius or angle about the pole.
  double radius = std::hypot(da, db);
  const double current_angle = da == 0 && db == 0 ? polar_angle_deg_ : std::atan2(db, da) / kDegree;
  if (v.has(w.radius)) {
    const double r = *v[w.radius] * unit;
    radius = dialect_.polar_pole_at_g16 && incremental_ ? radius + r : r;
  }
  double angle = current_angle;
  if (v.has(w.angle)) angle = incremental_ ? current_angle + *v[w.angle] : *v[w.angle];
  polar_angle_deg_ = angle;
  const double a = pole.*w.a + radius * std::cos(angle * kDegree);
  const double b = pole.*w.b + radius * std::sin(angle * kDegree);
  v.letter[slot(w.radius)] = (incremental_ ? a - here_a : a) / unit;
  v.letter[slot(w.angle)] = (incremental_ ? b - here_b : b) / unit;
}

} // namespace ncjoule::detail
