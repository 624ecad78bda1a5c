// What the optimize tests share: the machine they run on, and ways to look at a plan and a text.
#pragma once

#include <doctest/doctest.h>

#include <memory>
#include <string>
#include <vector>

#include "ncjoule/estimate.hpp"
#include "ncjoule/optimize.hpp"
#include "ncjoule/profile.hpp"

namespace ncjoule::test {

inline const MachineProfile& machine() {
  static const MachineProfile profile =
      load_profile(std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/generic-3axis.toml");
  return profile;
}

// What optimize starts from: the program estimated on the stock `stock`, its commands kept,
// and the plan's input made from them (which points into both: keep this while it is used).
struct Started {
  Started(const SourceFile& source, const std::string& stock) {
    EstimateOptions eo;
    eo.stock = parse_stock_spec(stock);
    eo.keep_commands = &commands;
    before = estimate_program(source, machine(), eo);
    REQUIRE(before.removal);
    start = optimize_start(source, before, commands, machine().kinematics);
  }
  Started(const Started&) = delete;
  Started& operator=(const Started&) = delete;
  std::vector<CanonCommand> commands;
  Estimate before;
  std::unique_ptr<OptimizeStart> start;
};

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
