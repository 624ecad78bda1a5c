// The plan's input from a program's estimate on its known stock (optimize.hpp).
#include <stdexcept>

#include "ncjoule/estimate.hpp"
#include "ncjoule/optimize.hpp"

namespace ncjoule {

std::unique_ptr<OptimizeStart> optimize_start(const SourceFile& source, const Estimate& before,
                                              const std::vector<CanonCommand>& commands,
                                              const Kinematics& kinematics) {
  if (!before.removal) throw std::invalid_argument("optimize: the estimate has no removal");
  auto start = std::make_unique<OptimizeStart>();
  start->stock = make_box_stock(before.removal->stock_box, before.removal->stock_description);
  start->rpm_by_line = spindle_rpm_by_line(commands);
  for (const auto& [line, load] : mean_spindle_loads(before, start->rpm_by_line))
    start->loads[line] = LoadAt{load, 0};
  OptimizeInput& in = start->input;
  in.source = &source;
  in.dialect = before.dialect;
  in.commands = &commands;
  in.tools = &before.tools;
  in.stock = start->stock.get();
  in.grid = before.removal->grid;
  in.kinematics = kinematics;
  in.loads = &start->loads;
  return start;
}

} // namespace ncjoule
