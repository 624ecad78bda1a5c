// libFuzzer target: arbitrary bytes as a job file (TOML: stock, material, work offsets, tools).
// A job is either refused with an error diagnostic, or read with tools of positive, finite sizes
// and numbers in 0..1000000 and finite work offsets; nothing else.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "ncjoule/estimate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<ncjoule::Diagnostic> diagnostics;
  // A folder that does not exist: an STL stock the job names is looked for there, and missing.
  const auto job =
      ncjoule::parse_job_file(text, "fuzz-no-such-folder/job.ncjoule.toml", diagnostics);
  if (!job) {
    bool said = false;
    for (const ncjoule::Diagnostic& d : diagnostics)
      said = said || d.severity == ncjoule::Severity::Error;
    if (!said) __builtin_trap(); // refused without saying why
    return 0;
  }
  for (const auto& [number, tool] : job->tools) {
    if (number < 0 || number > 1000000 || tool.number != number) __builtin_trap();
    if (!(tool.diameter_mm > 0) || !std::isfinite(tool.diameter_mm)) __builtin_trap();
  }
  for (const auto& [index, origin] : job->work_offsets)
    if (!std::isfinite(origin.x) || !std::isfinite(origin.y) || !std::isfinite(origin.z))
      __builtin_trap();
  return 0;
}
