#include "program_builder.hpp"

#include <algorithm>
#include <cmath>

namespace ncjoule::test {

void ProgramBuilder::append(CanonCommand command, TimedCommand timed, CommandRemoval removed) {
  command.line = static_cast<int>(commands.size());
  command.call_line = command.line;
  command.state = state_;
  timed.command = commands.size();
  timed.line = command.line;
  timed.kind = command.kind;
  timed.start_s = now_;
  now_ += timed.duration_s;
  timeline.total_s = now_;
  removal.removed_mm3 += removed.removed_mm3;
  commands.push_back(std::move(command));
  timeline.commands.push_back(std::move(timed));
  removal.commands.push_back(std::move(removed));
}

void ProgramBuilder::spindle(double rpm, double ramp_s) {
  CanonCommand c;
  if (rpm > 0) {
    c.kind = CanonKind::SpindleClockwise;
    state_.spindle = SpindleDir::Clockwise;
    state_.spindle_rpm = rpm;
  } else {
    c.kind = CanonKind::SpindleStop;
    state_.spindle = SpindleDir::Off;
  }
  c.value = rpm;
  TimedCommand t;
  t.duration_s = ramp_s;
  append(c, t, {});
}

void ProgramBuilder::coolant(bool on) {
  CanonCommand c;
  c.kind = on ? CanonKind::FloodOn : CanonKind::FloodOff;
  state_.flood = on;
  append(c, {}, {});
}

void ProgramBuilder::dwell(double seconds) {
  CanonCommand c;
  c.kind = CanonKind::Dwell;
  c.value = seconds;
  TimedCommand t;
  t.duration_s = seconds;
  append(c, t, {});
}

void ProgramBuilder::tool_change(int tool, double seconds) {
  CanonCommand c;
  c.kind = CanonKind::ChangeTool;
  c.value = tool;
  state_.tool = tool;
  TimedCommand t;
  t.duration_s = seconds;
  append(c, t, {});
}

void ProgramBuilder::move(CanonKind kind, const Pose& to, double feed, double area_mm2,
                          double accel) {
  CanonCommand c;
  c.kind = kind;
  c.start = position_;
  c.end = to;
  const double dx = to.x - position_.x, dy = to.y - position_.y, dz = to.z - position_.z;
  const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
  // Trapezoidal (or triangular) profile from rest to rest, or constant speed.
  double peak = feed, t_acc = 0, s_acc = 0;
  if (accel > 0) {
    t_acc = feed / accel;
    s_acc = 0.5 * feed * t_acc;
    if (2 * s_acc > length) {
      peak = std::sqrt(accel * length);
      t_acc = peak / accel;
      s_acc = 0.5 * length;
    }
  }
  const double t_cruise = (length - 2 * s_acc) / peak;
  const double duration = 2 * t_acc + t_cruise;
  auto distance_at = [&](double t, double& v) {
    if (t < t_acc) {
      v = accel * t;
      return 0.5 * accel * t * t;
    }
    if (t <= t_acc + t_cruise) {
      v = peak;
      return s_acc + peak * (t - t_acc);
    }
    const double r = std::max(0.0, duration - t);
    v = accel * r;
    return length - 0.5 * accel * r * r;
  };
  TimedCommand timed;
  timed.duration_s = duration;
  timed.length_mm = length;
  timed.peak_speed_mm_s = peak;
  CommandRemoval removed;
  const int steps = std::max(1, static_cast<int>(std::ceil(duration / sample_dt_s)));
  double previous_s = 0;
  for (int k = 0; k <= steps; ++k) {
    const double t = duration * k / steps;
    double v = 0;
    const double s = k == steps ? length : distance_at(t, v);
    if (k == steps) distance_at(t, v);
    const double u = length > 0 ? s / length : 1.0;
    MotionSample sample;
    sample.t_s = now_ + t;
    sample.u = u;
    sample.position = {position_.x + dx * u, position_.y + dy * u, position_.z + dz * u};
    sample.speed_mm_s = v;
    timed.samples.push_back(sample);
    if (k > 0) {
      const double volume = area_mm2 * (s - previous_s);
      removed.step_volume_mm3.push_back(volume);
      removed.removed_mm3 += volume;
      removed.mrr_peak_mm3_s = std::max(removed.mrr_peak_mm3_s, volume / (duration / steps));
    }
    previous_s = s;
  }
  removed.mrr_mean_mm3_s = duration > 0 ? removed.removed_mm3 / duration : 0;
  append(c, timed, removed);
  position_ = to;
}

} // namespace ncjoule::test
