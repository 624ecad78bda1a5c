// libFuzzer target: arbitrary bytes through the whole pipeline as `ncjoule annotate` runs it
// (interpret, plan, remove from a small stock, integrate power, annotate), then strip. Nothing may
// crash, hang or trip a sanitizer; every number of the estimate is finite; strip gives back the
// input (without annotations it may itself have held).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "ncjoule/annotate.hpp"
#include "ncjoule/profile.hpp"

namespace {

const ncjoule::MachineProfile& machine() {
  static const ncjoule::MachineProfile profile =
      ncjoule::load_profile(NCJOULE_SOURCE_DIR "/samples/machines/generic-3axis.toml");
  return profile;
}

void require(bool condition) {
  if (!condition) __builtin_trap();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  ncjoule::EstimateOptions options;
  options.stock = ncjoule::parse_stock_spec("box:0,0,-5,20,20,0");
  options.removal.grid_mm = 2; // coarse: each sample is cheap, the code paths the same
  options.limits.max_commands = 30;
  options.limits.max_loop_iterations = 10;
  options.limits.max_cycle_repeats = 10;
  options.limits.max_arc_turns = 10;
  // X1e5 at F1 is legal and would be sampled finely for minutes; the code paths are the same
  // with few samples.
  options.max_samples_per_move = 16;
  // The planner's window (commands waiting, items dropped, charges arriving late) reached with a
  // few moves instead of 64: the use-after-free of an arc split by the naive-CAM detector needed
  // about 50 before.
  options.look_ahead_batch = 4;
  const ncjoule::AnnotatedProgram result =
      ncjoule::annotate_program("fuzz.ngc", text, machine(), options);
  const ncjoule::Estimate& e = result.estimate;
  if (e.failed) return 0; // said, with an error: never a crash
  require(std::isfinite(e.time_s) && e.time_s >= 0);
  require(std::isfinite(e.energy.energy_j) && std::isfinite(e.energy.removed_mm3));
  for (const ncjoule::LineSummary& line : e.lines)
    require(std::isfinite(line.time_s) && std::isfinite(line.energy_j) &&
            std::isfinite(line.removed_mm3));
  require(ncjoule::strip(result.text) == ncjoule::strip(text));
  return 0;
}
