// A run's logged power as a power log for the power fits of calibrate.hpp: the machine's
// electrical power (WATTAGE), or its spindle load (LOAD, % of the spindle's rating) times the
// rating, timed from the run's start.
#include "ncjoule/calibrate_timing.hpp"

namespace ncjoule {

std::optional<PowerLog> run_power_log(const LogEvidence& evidence, const LoggedRun& run,
                                      double spindle_rated_w) {
  const LogRun& r = evidence.runs[run.run];
  const std::vector<TimedValue>& values = !r.power.empty()      ? r.power
                                          : spindle_rated_w > 0 ? r.spindle_load
                                                                : r.power;
  const double scale = !r.power.empty() ? 1.0 : spindle_rated_w / 100;
  if (values.empty()) return std::nullopt;
  PowerLog log;
  log.path = evidence.log.files.empty() ? "" : evidence.log.files.front().path;
  // Logged on change only: each value holds until the next, read every quarter second so that a
  // long steady stretch weighs in the fit as long as it lasted.
  const double duration = r.end_s - r.start_s;
  std::size_t i = 0;
  for (double t = 0; t <= duration + 1e-9; t += 0.25) {
    while (i + 1 < values.size() && values[i + 1].t_s - r.start_s <= t)
      ++i;
    if (values[i].t_s - r.start_s > t) continue; // nothing logged yet
    log.t_s.push_back(t);
    log.power_w.push_back(values[i].value * scale);
  }
  if (log.t_s.size() < 10) return std::nullopt;
  return log;
}

} // namespace ncjoule
