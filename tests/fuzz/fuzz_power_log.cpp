// libFuzzer target: arbitrary bytes as a power log (CSV: time_s, power_w), read as `measure` and
// `calibrate --log` read it, then measured. A log is either refused with an error diagnostic or
// read into increasing times and finite powers, and its measured energy is finite; nothing else.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "ncjoule/calibrate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<ncjoule::Diagnostic> diagnostics;
  const auto csv = ncjoule::parse_numeric_csv("fuzz.csv", text, diagnostics);
  if (!csv) return 0;
  const auto log = ncjoule::power_log_from_csv(*csv, diagnostics);
  if (!log) return 0;
  if (log->t_s.size() != log->power_w.size()) __builtin_trap();
  for (std::size_t i = 0; i < log->t_s.size(); ++i) {
    if (!std::isfinite(log->t_s[i]) || !std::isfinite(log->power_w[i])) __builtin_trap();
    if (i > 0 && !(log->t_s[i] > log->t_s[i - 1])) __builtin_trap();
  }
  ncjoule::MeasureOptions options;
  options.idle_from_first_s = 1;
  for (const auto& measure : {ncjoule::MeasureOptions{}, options}) {
    const ncjoule::MeasuredEnergy m = ncjoule::measure_energy(*log, measure);
    if (!std::isfinite(m.energy_j) || !std::isfinite(m.net_energy_j) ||
        !std::isfinite(m.mean_power_w) || !std::isfinite(m.duration_s))
      __builtin_trap();
  }
  return 0;
}
