#include "units.hpp"

#include <array>

namespace ncjoule::profile_detail {
namespace {

constexpr double kInch = 25.4;

constexpr std::array kSpeed{UnitSuffix{"mm_min", 1.0 / 60}, UnitSuffix{"mm_s", 1.0},
                            UnitSuffix{"m_min", 1000.0 / 60}, UnitSuffix{"in_min", kInch / 60}};
constexpr std::array kAcceleration{UnitSuffix{"mm_s2", 1.0}, UnitSuffix{"m_s2", 1000.0},
                                   UnitSuffix{"in_s2", kInch}};
constexpr std::array kJerk{UnitSuffix{"mm_s3", 1.0}, UnitSuffix{"m_s3", 1000.0},
                           UnitSuffix{"in_s3", kInch}};
constexpr std::array kLength{UnitSuffix{"mm", 1.0}, UnitSuffix{"um", 0.001},
                             UnitSuffix{"in", kInch}};
constexpr std::array kTime{UnitSuffix{"s", 1.0}, UnitSuffix{"ms", 0.001}, UnitSuffix{"min", 60.0}};
constexpr std::array kRampTime{UnitSuffix{"s_per_1000rpm", 1.0}};
constexpr std::array kAngularSpeed{UnitSuffix{"deg_min", 1.0 / 60}, UnitSuffix{"deg_s", 1.0}};
constexpr std::array kAngularAccel{UnitSuffix{"deg_s2", 1.0}};
constexpr std::array kPower{UnitSuffix{"w", 1.0}, UnitSuffix{"kw", 1000.0}};
constexpr std::array kPowerPerRpm{UnitSuffix{"w_per_rpm", 1.0}, UnitSuffix{"kw_per_rpm", 1000.0}};
constexpr std::array kPowerPerRpm2{UnitSuffix{"w_per_rpm2", 1.0}};
// P = kb * F: a constant per mm/min is 60 times larger per mm/s.
constexpr std::array kPowerPerSpeed{UnitSuffix{"w_per_mm_s", 1.0}, UnitSuffix{"w_per_mm_min", 60.0},
                                    UnitSuffix{"w_per_in_min", 60.0 / kInch}};
constexpr std::array kPowerPerMrr{UnitSuffix{"w_per_mm3_s", 1.0}, UnitSuffix{"w_per_mm3_min", 60.0},
                                  UnitSuffix{"w_per_cm3_min", 60.0 / 1000}};
constexpr std::array kKiloWatt{UnitSuffix{"kw", 1.0}};
constexpr std::array kKiloWattPerRpm{UnitSuffix{"kw_per_rpm", 1.0}};

} // namespace

std::span<const UnitSuffix> units_of(Dimension dimension) {
  switch (dimension) {
  case Dimension::Speed:
    return kSpeed;
  case Dimension::Acceleration:
    return kAcceleration;
  case Dimension::Jerk:
    return kJerk;
  case Dimension::Length:
    return kLength;
  case Dimension::Time:
    return kTime;
  case Dimension::RampTime:
    return kRampTime;
  case Dimension::AngularSpeed:
    return kAngularSpeed;
  case Dimension::AngularAccel:
    return kAngularAccel;
  case Dimension::Power:
    return kPower;
  case Dimension::PowerPerRpm:
    return kPowerPerRpm;
  case Dimension::PowerPerRpm2:
    return kPowerPerRpm2;
  case Dimension::PowerPerSpeed:
    return kPowerPerSpeed;
  case Dimension::PowerPerMrr:
    return kPowerPerMrr;
  case Dimension::KiloWatt:
    return kKiloWatt;
  case Dimension::KiloWattPerRpm:
    return kKiloWattPerRpm;
  }
  return {};
}

Plausible plausible(Dimension dimension) {
  switch (dimension) {
  case Dimension::Speed: // 0.06 mm/min to 600 m/min
    return {0.001, 1e4, 0, "speed"};
  case Dimension::Acceleration: // 0.001 g to 10 g
    return {1, 1e5, 0, "acceleration"};
  case Dimension::Jerk:
    return {1, 1e9, 0, "jerk"};
  case Dimension::Length: // a micrometre's thousandth to 100 m
    return {1e-6, 1e5, 1e5, "length"};
  case Dimension::Time: // up to an hour for one event (a tool change, a wait)
    return {1e-6, 3600, 0, "time"};
  case Dimension::RampTime:
    return {1e-6, 600, 0, "spindle ramp"};
  case Dimension::AngularSpeed:
    return {0.001, 1e5, 0, "angular speed"};
  case Dimension::AngularAccel:
    return {0.01, 1e7, 0, "angular acceleration"};
  // Powers: up to a megawatt (the largest machining centres draw a few hundred kW); a fitted
  // line's intercept may be a little negative, never tens of kW.
  case Dimension::Power:
    return {1e-6, 1e6, 1e4, "power"};
  case Dimension::PowerPerRpm: // 100 W per rpm is a megawatt at 10,000 rpm
    return {1e-9, 100, 100, "power per rpm"};
  case Dimension::PowerPerRpm2:
    return {1e-15, 0.01, 0.01, "power per rpm^2"};
  case Dimension::PowerPerSpeed: // a megawatt at 100 mm/s
    return {1e-9, 1e4, 1e4, "power per mm/s"};
  case Dimension::PowerPerMrr: // a specific cutting energy, J/mm^3: tens at most
    return {1e-9, 1000, 1000, "power per mm^3/s"};
  case Dimension::KiloWatt:
    return {1e-9, 1000, 10, "power"};
  case Dimension::KiloWattPerRpm:
    return {1e-12, 0.1, 0.1, "power per rpm"};
  }
  return {0, 1e12, 1e12, "value"};
}

} // namespace ncjoule::profile_detail
