// libFuzzer target: arbitrary bytes as a machine profile (TOML). A profile is either read, with
// every number finite, or refused with a ProfileError that names the file; nothing else.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "ncjoule/profile.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const ncjoule::MachineProfile m = ncjoule::parse_profile(text, "fuzz.toml");
    const auto& p = m.power.pavanaskar;
    bool finite = std::isfinite(p.tare_w) && std::isfinite(p.spindle_ka_w) &&
                  std::isfinite(p.spindle_kb_w_per_rpm) &&
                  std::isfinite(m.kinematics.tool_change_s);
    for (int a = 0; a < 3; ++a)
      finite = finite && std::isfinite(p.move_ka_w[a]) && std::isfinite(p.move_kb_w_per_mm_s[a]) &&
               std::isfinite(m.kinematics.axes[a].rapid_mm_s) &&
               std::isfinite(m.kinematics.axes[a].accel_mm_s2);
    if (!finite) __builtin_trap();
  } catch (const ncjoule::ProfileError&) {
  }
  return 0;
}
