// The unit suffixes a profile key may carry, and their factors to ncjoule's internal units.
//
// A quantity is written as <stem>_<unit>, e.g. rapid_mm_min or accel_m_s2; each dimension
// lists the units a person is likely to have from a data sheet or a paper.
#pragma once

#include <span>
#include <string_view>

namespace ncjoule::profile_detail {

struct UnitSuffix {
  std::string_view suffix; // as written after "<stem>_"
  double to_internal;      // value in this unit * to_internal = value in internal units
};

enum class Dimension {
  Speed,          // mm/s
  Acceleration,   // mm/s^2
  Jerk,           // mm/s^3
  Length,         // mm
  Time,           // s
  RampTime,       // s per 1000 rpm
  AngularSpeed,   // deg/s
  AngularAccel,   // deg/s^2
  Power,          // W
  PowerPerRpm,    // W/rpm
  PowerPerRpm2,   // W/rpm^2
  PowerPerSpeed,  // W/(mm/s)
  PowerPerMrr,    // W/(mm^3/s)
  KiloWatt,       // kW (Zhou's constants are kept as published)
  KiloWattPerRpm, // kW/rpm
};

std::span<const UnitSuffix> units_of(Dimension dimension);

// What a machine's quantity of a dimension can physically be, in internal units: a value outside
// is a slip (of units, of typing: 1e-300 m/s^2, -1e6 W) that would give absurd times and energies
// rather than an error. Zero passes where the key allows it ("none").
struct Plausible {
  double smallest;      // smallest magnitude other than zero
  double largest;       // largest positive value
  double most_negative; // largest magnitude of a negative value, where the key allows one
  const char* what;     // "acceleration", for the message
};
Plausible plausible(Dimension dimension);

} // namespace ncjoule::profile_detail
