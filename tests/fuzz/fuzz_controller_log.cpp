// libFuzzer target: arbitrary bytes as a controller log (MTConnect SHDR lines or a Streams XML
// document, told apart by content), read, finished and cut into runs as `check-log` and
// `calibrate-timing` do. Never a crash, a hang or a sanitizer report; observations in time order
// with finite times; every run ends no earlier than it starts.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "ncjoule/logs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  ncjoule::ControllerLog log;
  std::vector<ncjoule::Diagnostic> diagnostics;
  if (!ncjoule::parse_controller_log(text, "fuzz.log", log, {}, diagnostics)) return 0;
  ncjoule::finish_controller_log(log, diagnostics);
  for (std::size_t i = 0; i < log.observations.size(); ++i) {
    if (!std::isfinite(log.observations[i].t_s)) __builtin_trap();
    if (i > 0 && log.observations[i].t_s < log.observations[i - 1].t_s) __builtin_trap();
    if (log.observations[i].text >= log.texts.size()) __builtin_trap();
  }
  for (const ncjoule::LogRun& run : ncjoule::find_runs(log))
    if (!(run.end_s >= run.start_s)) __builtin_trap();
  return 0;
}
