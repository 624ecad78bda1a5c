#include <array>

#include "sections.hpp"

namespace ncjoule::profile_detail {
namespace {

AxisLimits read_axis(TableReader axis) {
  AxisLimits limits;
  limits.rapid_mm_s = axis.quantity("rapid", Dimension::Speed, Range::Positive);
  limits.max_feed_mm_s = axis.quantity("max_feed", Dimension::Speed, Range::Positive);
  limits.accel_mm_s2 = axis.quantity("accel", Dimension::Acceleration, Range::Positive);
  // 0 = no jerk limit; optional because only the S-curve profile uses it.
  limits.jerk_mm_s3 =
      axis.optional_quantity("jerk", Dimension::Jerk, Range::NonNegative).value_or(0.0);
  if (limits.max_feed_mm_s > limits.rapid_mm_s)
    axis.fail("max_feed_mm_min", "the maximum feed is above the rapid rate");
  axis.finish();
  return limits;
}

} // namespace

Kinematics read_kinematics(TableReader t, std::vector<std::string>& sources) {
  Kinematics k;
  read_source(t, "kinematics", sources);
  k.rapid_mode = t.choice("rapid_mode", {"linear", "dog-leg"}) == "linear" ? RapidMode::Linear
                                                                           : RapidMode::DogLeg;
  k.feed_profile = t.choice("feed_profile", {"trapezoid", "s-curve"}) == "trapezoid"
                       ? FeedProfile::Trapezoid
                       : FeedProfile::SCurve;
  const std::string rule = t.choice("junction_rule", {"tolerance", "next-feed", "linuxcnc-2.9"});
  k.junction_rule = rule == "tolerance"   ? JunctionRule::Tolerance
                    : rule == "next-feed" ? JunctionRule::NextFeed
                                          : JunctionRule::LinuxCnc29;
  k.path_tolerance_mm = t.quantity("path_tolerance", Dimension::Length, Range::NonNegative);
  k.exact_stop_every_block = t.boolean("exact_stop_every_block");
  k.placeholder_rates = t.optional_boolean("placeholder_rates").value_or(false);
  k.tool_change_s = t.quantity("tool_change", Dimension::Time, Range::NonNegative);
  k.settle_s = t.optional_quantity("settle", Dimension::Time, Range::NonNegative).value_or(0.0);
  k.spindle_s_per_1000rpm = t.quantity("spindle_ramp", Dimension::RampTime, Range::NonNegative);

  if (const auto z = t.optional_string("z_positive")) {
    if (*z == "up")
      k.z_positive = ZDirection::Up;
    else if (*z == "down")
      k.z_positive = ZDirection::Down;
    else
      t.fail("z_positive", "must be \"up\" (+Z moves the tool away from the work) or \"down\" "
                           "(into it); leave it out to have it read from each program");
  }

  constexpr std::array<const char*, 3> names{"x", "y", "z"};
  for (std::size_t i = 0; i < names.size(); ++i)
    k.axes[i] = read_axis(t.table(names[i]));
  if (k.feed_profile == FeedProfile::SCurve) {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (k.axes[i].jerk_mm_s3 <= 0)
        t.fail(std::string(names[i]) + ".jerk_mm_s3",
               "feed_profile \"s-curve\" needs a jerk limit greater than zero on every axis");
  }
  if (k.junction_rule == JunctionRule::LinuxCnc29 && k.feed_profile == FeedProfile::SCurve)
    t.fail("feed_profile", "junction_rule \"linuxcnc-2.9\" plans trapezoids, as LinuxCNC 2.9 "
                           "does (it has no jerk limit): use feed_profile = \"trapezoid\"");
  if (auto rotary = t.optional_table("rotary")) {
    k.rotary_rapid_deg_s = rotary->quantity("rapid", Dimension::AngularSpeed, Range::Positive);
    k.rotary_accel_deg_s2 = rotary->quantity("accel", Dimension::AngularAccel, Range::Positive);
    rotary->finish();
  }
  t.finish();
  return k;
}

} // namespace ncjoule::profile_detail
