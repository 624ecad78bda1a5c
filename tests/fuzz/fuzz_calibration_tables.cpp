// libFuzzer target: arbitrary bytes as a calibration table (CSV), read as `calibrate --spindle`
// and `calibrate --zhou` read them and fitted (Ceres). A table is refused with a diagnostic, or a
// fit refuses it (FitReport::refused), or every fitted constant is finite; never a crash inside
// the solver or its covariance.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "ncjoule/calibrate.hpp"

namespace {

void check(const ncjoule::FitReport& fit) {
  if (!fit.refused.empty()) return;
  for (const ncjoule::FittedConstant& c : fit.constants)
    if (!c.held && !std::isfinite(c.value)) __builtin_trap();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<ncjoule::Diagnostic> diagnostics;
  const auto csv = ncjoule::parse_numeric_csv("fuzz.csv", text, diagnostics);
  if (!csv) return 0;
  // The spindle table (rpm, power), as --spindle reads it: above a tare of 300 W.
  std::vector<ncjoule::Diagnostic> spindle_problems;
  const auto spindle = ncjoule::readings_from_csv(*csv, ncjoule::kFieldRpm, spindle_problems);
  if (!spindle.empty()) check(ncjoule::fit_spindle(spindle, 300));
  // The Zhou table (rpm, MRR, power), as --zhou reads it.
  std::vector<ncjoule::Diagnostic> zhou_problems;
  const auto zhou =
      ncjoule::readings_from_csv(*csv, ncjoule::kFieldRpm | ncjoule::kFieldMrr, zhou_problems);
  if (!zhou.empty()) {
    check(ncjoule::fit_zhou_power(zhou));
    check(ncjoule::fit_zhou_sec(zhou));
  }
  return 0;
}
