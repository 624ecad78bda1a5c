// Shared by the estimate tests: the generic sample machine and a look for a warning.
#pragma once

#include <string>
#include <string_view>

#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"

namespace estimate_test {

inline ncjoule::MachineProfile generic() {
  return ncjoule::load_profile(std::string(NCJOULE_SOURCE_DIR) +
                               "/samples/machines/generic-3axis.toml");
}

// Whether a warning of the estimate holds `words`.
inline bool warned(const ncjoule::Estimate& e, std::string_view words) {
  for (const ncjoule::Diagnostic& d : e.diagnostics)
    if (d.severity == ncjoule::Severity::Warning && d.message.find(words) != std::string::npos)
      return true;
  return false;
}

// Whether any diagnostic of the estimate (error, warning or note) holds `words`.
inline bool mentioned(const ncjoule::Estimate& e, std::string_view words) {
  for (const ncjoule::Diagnostic& d : e.diagnostics)
    if (d.message.find(words) != std::string::npos) return true;
  return false;
}

} // namespace estimate_test
