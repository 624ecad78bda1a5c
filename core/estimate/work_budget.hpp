// Internal: the budgets of path samples and of removal work (ncjoule/budget.hpp), counted per
// command as the planner hands it on, before removal cuts it: a run that would pass one stops
// there with BudgetExceeded. Counted per command, never per column, so that it costs nothing
// next to the work it bounds.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "ncjoule/budget.hpp"
#include "ncjoule/gcode.hpp"
#include "ncjoule/kinematics.hpp"
#include "ncjoule/removal.hpp"
#include "ncjoule/tool.hpp"

namespace ncjoule::estimate_detail {

class WorkBudget {
public:
  // `removals`: the setups' stock models (those not ready are left out); the removal work is
  // counted on the finest grid and the shortest sample step among them. `tools` by number.
  WorkBudget(std::size_t max_path_samples, double max_removal_work,
             const std::vector<RemovalSimulator*>& removals, const std::map<int, Tool>& tools,
             std::string file);
  // Counts one timed command; throws BudgetExceeded (at its line) when a budget is passed.
  void count(const CanonCommand& command, const TimedCommand& timed);
  std::size_t path_samples() const { return path_samples_; }
  double removal_work() const { return removal_work_; }

private:
  std::size_t max_path_samples_;
  double max_removal_work_;
  double cell_area_mm2_ = 0; // 0: no removal
  double sample_step_mm_ = 1;
  const std::map<int, Tool>& tools_;
  std::string file_;
  std::size_t path_samples_ = 0;
  double removal_work_ = 0;
};

} // namespace ncjoule::estimate_detail
