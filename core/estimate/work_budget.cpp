// The budgets of path samples and removal work (work_budget.hpp).
#include "work_budget.hpp"

#include <algorithm>
#include <cmath>

namespace ncjoule::estimate_detail {

WorkBudget::WorkBudget(std::size_t max_path_samples, double max_removal_work,
                       const std::vector<RemovalSimulator*>& removals,
                       const std::map<int, Tool>& tools, std::string file)
    : max_path_samples_(max_path_samples), max_removal_work_(max_removal_work), tools_(tools),
      file_(std::move(file)) {
  for (const RemovalSimulator* removal : removals) {
    if (!removal || !removal->ready()) continue;
    const double area = removal->grid().dx * removal->grid().dy;
    cell_area_mm2_ = cell_area_mm2_ > 0 ? std::min(cell_area_mm2_, area) : area;
    if (removal->sample_step_mm() > 0)
      sample_step_mm_ = std::min(sample_step_mm_, removal->sample_step_mm());
  }
}

void WorkBudget::count(const CanonCommand& command, const TimedCommand& timed) {
  path_samples_ += timed.samples.size();
  if (max_path_samples_ && path_samples_ > max_path_samples_)
    throw BudgetExceeded({Severity::Error, file_, timed.line + 1, 0,
                          budget_message("path samples", double(max_path_samples_),
                                         "max-path-samples", "max_path_samples")});
  if (cell_area_mm2_ <= 0 || !is_move(command.kind)) return;
  const auto tool = tools_.find(command.state.tool);
  if (tool == tools_.end()) return;
  // Removal sweeps the tool along each step between two path samples (or, where the planner
  // gave none, steps of its sample step): each step covers its length plus one diameter, one
  // diameter wide.
  const double length = std::isfinite(timed.length_mm) ? timed.length_mm : 0;
  const double steps = timed.samples.size() >= 2
                           ? double(timed.samples.size() - 1)
                           : std::max(1.0, std::ceil(length / sample_step_mm_));
  const double d = tool->second.diameter_mm;
  removal_work_ += (length + steps * d) * d / cell_area_mm2_;
  if (max_removal_work_ > 0 && !(removal_work_ <= max_removal_work_))
    throw BudgetExceeded({Severity::Error, file_, timed.line + 1, 0,
                          budget_message("removal column visits", max_removal_work_,
                                         "max-removal-work", "max_removal_work")});
}

} // namespace ncjoule::estimate_detail
