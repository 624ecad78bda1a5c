#include <array>
#include <cmath>

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

// A table of (rpm, seconds) points, both rising: a spindle's run-up or run-down time from rest.
std::vector<std::pair<double, double>> read_spindle_times(TableReader& t, std::string_view key) {
  std::vector<std::pair<double, double>> points;
  const toml::node* node = t.raw(key);
  if (!node) return points;
  const std::string rule = "must be [[RPM, SECONDS], ...]: the time from rest to each speed, "
                           "both rising (e.g. [[3000, 0.0], [7500, 3.0], [12000, 7.0]])";
  const toml::array* list = node->as_array();
  if (!list || list->empty()) t.fail(key, rule);
  for (const toml::node& item : *list) {
    const toml::array* pair = item.as_array();
    const std::optional<double> rpm =
        pair && pair->size() == 2 ? (*pair)[0].value<double>() : std::nullopt;
    const std::optional<double> s =
        pair && pair->size() == 2 ? (*pair)[1].value<double>() : std::nullopt;
    if (!rpm || !s || !std::isfinite(*rpm) || !std::isfinite(*s) || *rpm <= 0 || *s < 0 ||
        *rpm > 3e5 || *s > 600 ||
        (!points.empty() && (*rpm <= points.back().first || *s < points.back().second)))
      t.fail(key, rule);
    points.emplace_back(*rpm, *s);
  }
  return points;
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
  k.spindle_waits = t.optional_boolean("spindle_waits").value_or(true);
  k.air_feed_mm_s =
      t.optional_quantity("air_feed", Dimension::Speed, Range::Positive).value_or(0.0);
  k.tool_change_first_extra_s =
      t.optional_quantity("tool_change_first_extra", Dimension::Time, Range::NonNegative)
          .value_or(0.0);
  k.tool_change_same_tool_s =
      t.optional_quantity("tool_change_same_tool", Dimension::Time, Range::NonNegative);
  k.tool_change_spindle_stop_s =
      t.optional_quantity("tool_change_spindle_stop", Dimension::Time, Range::NonNegative)
          .value_or(0.0);
  k.spindle_run_up = read_spindle_times(t, "spindle_run_up_rpm_s");
  k.spindle_run_down = read_spindle_times(t, "spindle_run_down_rpm_s");
  // A measured run-up replaces the straight ramp, which is then not needed.
  k.spindle_s_per_1000rpm =
      k.spindle_run_up.empty()
          ? t.quantity("spindle_ramp", Dimension::RampTime, Range::NonNegative)
          : t.optional_quantity("spindle_ramp", Dimension::RampTime, Range::NonNegative)
                .value_or(0.0);
  if (k.spindle_run_up.empty() && !k.spindle_run_down.empty())
    t.fail("spindle_run_down_rpm_s", "needs spindle_run_up_rpm_s (a run-down alone is not used)");
  k.settle_s = t.optional_quantity("settle", Dimension::Time, Range::NonNegative).value_or(0.0);
  k.settle_rapid_s = t.optional_quantity("settle_rapid", Dimension::Time, Range::NonNegative);
  if (const auto ratio = t.optional_number("transition_speed_ratio", Range::Positive)) {
    if (*ratio > 1)
      t.fail("transition_speed_ratio", "must be above 0 and at most 1 (a fraction of the feed)");
    k.transition_speed_ratio = *ratio;
  }
  if (const auto blocks = t.optional_number("lookahead_blocks", Range::Positive)) {
    if (*blocks != std::floor(*blocks) || *blocks > 1e6)
      t.fail("lookahead_blocks", "must be a whole number of blocks, 1 to 1000000");
    k.lookahead_blocks = static_cast<std::size_t>(*blocks);
  }
  k.arc_accel_mm_s2 = t.optional_quantity("arc_accel", Dimension::Acceleration, Range::Positive);
  if (auto waits = t.optional_table("waits")) {
    read_source(*waits, "kinematics.waits", sources);
    auto wait = [&](const char* stem) {
      return waits->optional_quantity(stem, Dimension::Time, Range::NonNegative).value_or(0.0);
    };
    k.waits.optional_stop_s = wait("optional_stop");
    k.waits.program_stop_s = wait("program_stop");
    k.waits.program_end_s = wait("program_end");
    k.waits.coolant_on_s = wait("coolant_on");
    waits->finish();
  }

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
  if (k.junction_rule == JunctionRule::LinuxCnc29 && k.lookahead_blocks > 0)
    t.fail("lookahead_blocks", "junction_rule \"linuxcnc-2.9\" plans as LinuxCNC 2.9 does: "
                               "leave lookahead_blocks out");
  if (k.junction_rule == JunctionRule::LinuxCnc29 && k.transition_speed_ratio < 1)
    t.fail("transition_speed_ratio", "junction_rule \"linuxcnc-2.9\" takes its transitions as "
                                     "LinuxCNC 2.9 does: leave transition_speed_ratio out");
  if (auto rotary = t.optional_table("rotary")) {
    k.rotary_rapid_deg_s = rotary->quantity("rapid", Dimension::AngularSpeed, Range::Positive);
    k.rotary_accel_deg_s2 = rotary->quantity("accel", Dimension::AngularAccel, Range::Positive);
    rotary->finish();
  }
  t.finish();
  return k;
}

} // namespace ncjoule::profile_detail
