// What the optimize tests share: the machine they run on, and ways to look at a plan and a text.
#pragma once

#include <string>
#include <vector>

#include "ncjoule/optimize.hpp"
#include "ncjoule/profile.hpp"

namespace ncjoule::test {

inline const MachineProfile& machine() {
  static const MachineProfile profile =
      load_profile(std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/generic-3axis.toml");
  return profile;
}

// The edit the plan makes on a 0-based source line; null when none.
inline const BlockEdit* edit_on(const OptimizePlan& plan, int line) {
  for (const BlockEdit& e : plan.edits)
    if (e.line == line) return &e;
  return nullptr;
}

// The text's lines, without their line ends.
inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = text.find('\n', at);
    out.push_back(text.substr(at, end - at));
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return out;
}

} // namespace ncjoule::test
