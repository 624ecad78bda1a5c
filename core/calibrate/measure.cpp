// Energy of a logged run: the trapezoidal integral of power over time, and, as Mora did, the
// same with the idle power (measured before the run, or given) taken off.
#include <algorithm>

#include "ncjoule/calibrate.hpp"

namespace ncjoule {

MeasuredEnergy measure_energy(const PowerLog& log, const MeasureOptions& options) {
  MeasuredEnergy m;
  const auto& t = log.t_s;
  const auto& p = log.power_w;
  m.samples = std::min(t.size(), p.size());
  if (m.samples == 0) return m;
  m.peak_power_w = p[0];
  for (std::size_t i = 1; i < m.samples; ++i) {
    m.energy_j += 0.5 * (p[i] + p[i - 1]) * (t[i] - t[i - 1]);
    m.peak_power_w = std::max(m.peak_power_w, p[i]);
  }
  m.duration_s = t[m.samples - 1] - t[0];
  if (m.duration_s > 0) m.mean_power_w = m.energy_j / m.duration_s;
  if (options.idle_w) {
    m.idle_w = *options.idle_w;
  } else if (options.idle_from_first_s) {
    // Mean of the first seconds by the same trapezoid rule (a plain average when too short).
    const double t_end = t[0] + *options.idle_from_first_s;
    double energy = 0, span = 0, sum = p[0];
    std::size_t n = 1;
    for (std::size_t i = 1; i < m.samples && t[i] <= t_end; ++i, ++n) {
      energy += 0.5 * (p[i] + p[i - 1]) * (t[i] - t[i - 1]);
      span = t[i] - t[0];
      sum += p[i];
    }
    m.idle_w = span > 0 ? energy / span : sum / static_cast<double>(n);
  }
  m.net_energy_j = m.energy_j - m.idle_w * m.duration_s;
  return m;
}

} // namespace ncjoule
