#include "machine_moves.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ncjoule/machine.hpp"

namespace ncjoule::estimate_detail {
namespace {

constexpr std::uint8_t kZ = 4;

} // namespace

MachineMoves::MachineMoves(const WorkSetup& setup, bool offsets_given, std::optional<double> home_z,
                           std::string file)
    : setup_(setup), offsets_given_(offsets_given), home_z_(home_z), file_(std::move(file)) {
  // G54 is in force from the start.
  if (const auto g54 = setup.work_offsets.find(1); g54 != setup.work_offsets.end())
    work_offset_ = g54->second;
}

double MachineMoves::home_z() const {
  return home_z_ ? *home_z_ : std::max(highest_z_, 0.0) + setup_.z_home_above_work_mm;
}

CanonCommand MachineMoves::view(const CanonCommand& command) {
  CanonCommand c = command;
  const double home = home_z(); // above what came before this command
  switch (c.kind) {
  case CanonKind::WorkOffset: {
    const int index = int(c.value);
    work_offset_ = c.end;
    if (first_offset_ == 0) first_offset_ = index;
    if (!offsets_given_ && index != first_offset_ && !warned_offsets_) {
      warned_offsets_ = true;
      diagnostics_.push_back(
          {Severity::Warning, file_, c.line + 1, 0,
           "the program switches from " + work_offset_name(first_offset_) + " to " +
               work_offset_name(index) +
               " here; nothing describes where they are (work_offsets_mm under [setup] in the "
               "profile, or in a job file): both are taken at one place, so no travel between "
               "them is timed"});
    }
    return c;
  }
  case CanonKind::AxisOffset:
    axis_offset_ = c.end;
    return c;
  case CanonKind::ToolLengthOffset:
    tool_length_ = c.end.z;
    return c;
  default:
    break;
  }
  if (!is_move(c.kind)) return c;
  if (!(c.machine_axes & kZ)) highest_z_ = std::max({highest_z_, c.start.z, c.end.z});
  if (!offsets_given_) {
    // Without offsets, Z home is above the work, and X/Y home where the profile puts it: the
    // tool stays at such a position until the program moves that axis again.
    double* start[3] = {&c.start.x, &c.start.y, &c.start.z};
    double* end[3] = {&c.end.x, &c.end.y, &c.end.z};
    for (std::size_t i = 0; i < 3; ++i) {
      const bool machine = c.machine_axes & (1u << i);
      Held& h = held_[i];
      if (h.on) {
        *start[i] = i == 2 ? home : h.at;
        if (*end[i] == h.programmed && !machine)
          *end[i] = i == 2 ? home : h.at;
        else
          h.on = false;
      }
      if (!machine) continue;
      if (i == 2) {
        h = {true, *end[i], home};
      } else if (setup_.xy_home_in_work_mm) {
        // The interpreter put the axis at its machine coordinate as if the work were at home.
        const double home_xy =
            i == 0 ? setup_.xy_home_in_work_mm->first : setup_.xy_home_in_work_mm->second;
        h = {true, *end[i], home_xy + *end[i]};
      } else {
        continue;
      }
      *end[i] = h.at;
    }
    if (setup_.travel) check_extent(c);
  } else if (setup_.travel) {
    check_travel(c);
  }
  return c;
}

void MachineMoves::check_travel(const CanonCommand& c) {
  if (warned_travel_) return;
  const double machine[3] = {c.end.x + work_offset_.x + axis_offset_.x,
                             c.end.y + work_offset_.y + axis_offset_.y,
                             c.end.z + work_offset_.z + axis_offset_.z + tool_length_};
  static const char* const names = "XYZ";
  for (int i = 0; i < 3; ++i) {
    const auto [low, high] = (*setup_.travel)[std::size_t(i)];
    constexpr double kSlackMm = 1e-6;
    if (machine[i] >= low - kSlackMm && machine[i] <= high + kSlackMm) continue;
    warned_travel_ = true;
    char text[240];
    std::snprintf(text, sizeof text,
                  "this move takes %c to %.3f mm in machine coordinates, past the machine's "
                  "travel (%.3f to %.3f mm): the controller would stop with an over-travel alarm "
                  "(is the work offset right?)",
                  names[i], machine[i], low, high);
    diagnostics_.push_back({Severity::Warning, file_, c.line + 1, 0, text});
    return;
  }
}

void MachineMoves::check_extent(const CanonCommand& c) {
  static const char* const names = "XYZ";
  const double end[3] = {c.end.x, c.end.y, c.end.z};
  for (int i = 0; i < 3; ++i) {
    Extent& e = extent_[std::size_t(i)];
    // A machine position (Z home, X/Y home) is the machine's, not the program's extent.
    if (e.warned || (c.machine_axes & (1u << i)) || held_[std::size_t(i)].on) continue;
    if (!e.seen) {
      e = {true, false, end[i], end[i], c.line, c.line};
      continue;
    }
    if (end[i] < e.low) e.low = end[i], e.low_line = c.line;
    if (end[i] > e.high) e.high = end[i], e.high_line = c.line;
    const auto [low, high] = (*setup_.travel)[std::size_t(i)];
    constexpr double kSlackMm = 1e-6;
    if (e.high - e.low <= high - low + kSlackMm) continue;
    e.warned = true;
    // In the program's units: a programmer reads `Y18` against 16 in of travel.
    const double scale = c.state.inch ? 1 / 25.4 : 1.0;
    const char* unit = c.state.inch ? "in" : "mm";
    const int here = c.line, other = end[i] == e.high ? e.low_line : e.high_line;
    char text[400];
    std::snprintf(text, sizeof text,
                  "%c reaches %.4g %s here and %.4g %s at line %d: %.4g %s apart, more than the "
                  "machine's %c travel of %.4g %s (travel_mm under [setup] in the profile): no "
                  "work offset fits it in; is a decimal point missing?",
                  names[i], end[i] * scale, unit, (end[i] == e.high ? e.low : e.high) * scale, unit,
                  other + 1, (e.high - e.low) * scale, unit, names[i], (high - low) * scale, unit);
    diagnostics_.push_back({Severity::Warning, file_, here + 1, 0, text});
  }
}

} // namespace ncjoule::estimate_detail
