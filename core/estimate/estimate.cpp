// The pipeline: interpret, plan, remove material, integrate power, summarise per line.
#include "ncjoule/log.hpp"
#include <chrono>
#include <exception>

#include "line_summary.hpp"

namespace ncjoule {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

} // namespace

Estimate estimate_program(const SourceFile& source, const MachineProfile& machine,
                          const EstimateOptions& options) {
  Estimate e;
  e.file = source.path;
  InterpreterOptions interpreter;
  interpreter.dialect = options.dialect;
  if (!interpreter.dialect && !options.detect_dialect)
    interpreter.dialect = find_dialect(machine.dialect); // "auto" finds none: detected
  interpreter.fallback_dialect = find_dialect(machine.fallback_dialect);
  interpreter.tools = options.tool_table;

  // Stage times go to the log (-v): the benchmarks read them.
  auto t = Clock::now();
  e.toolpath = interpret(source, interpreter);
  e.dialect = e.toolpath.result.dialect;
  e.diagnostics = e.toolpath.result.diagnostics;
  logger().info("interpret: {} blocks, {} commands in {:.3f} s", e.toolpath.result.blocks,
                e.toolpath.commands.size(), seconds_since(t));

  // Tools: the tool table, then the program's header comments, then the job file and the
  // command line, each replacing the one before for the same number.
  std::map<int, Tool> described =
      tools_from_table(options.tool_table, e.diagnostics, options.tool_table_path);
  for (auto& [number, tool] : parse_tool_comments(source, e.diagnostics))
    described[number] = tool;
  for (const auto& [number, tool] : options.tools)
    described[number] = tool;
  std::optional<StockSpec> stock;
  if (options.simulate_removal) {
    ToolAssignment assignment = assign_tools(
        e.toolpath.commands, described,
        options.default_tool ? options.default_tool : machine.default_tool, source.path);
    e.tools = std::move(assignment.tools);
    e.unsimulated_tools = std::move(assignment.unsimulated);
    e.diagnostics.insert(e.diagnostics.end(), assignment.diagnostics.begin(),
                         assignment.diagnostics.end());
    stock = options.stock ? *options.stock : StockSpec{};
  } else {
    e.tools = std::move(described);
  }
  PlanOptions plan_options;
  if (stock && !e.tools.empty()) {
    const double grid =
        options.removal.grid_mm > 0 ? options.removal.grid_mm : default_grid_spacing(e.tools);
    plan_options.max_sample_step_mm = recommended_sample_step(e.tools, grid);
  }
  t = Clock::now();
  e.timeline = plan(e.toolpath.commands, machine, plan_options);
  logger().info("plan: {} commands in {:.3f} s", e.toolpath.commands.size(), seconds_since(t));
  for (Diagnostic d : e.timeline.diagnostics) {
    d.file = source.path;
    e.diagnostics.push_back(std::move(d));
  }

  if (stock) {
    RemovalOptions removal_options = options.removal;
    removal_options.source_path = source.path;
    t = Clock::now();
    try {
      e.removal =
          simulate_removal(e.toolpath.commands, e.timeline, e.tools, *stock, removal_options);
    } catch (const std::exception& ex) {
      e.diagnostics.push_back({Severity::Error, source.path, 0, 0,
                               std::string("material removal failed: ") + ex.what()});
      e.failed = true;
      return e;
    }
    logger().info("removal: {:.1f} mm^3 in {:.3f} s", e.removal->removed_mm3, seconds_since(t));
    e.diagnostics.insert(e.diagnostics.end(), e.removal->diagnostics.begin(),
                         e.removal->diagnostics.end());
  }
  e.energy = estimate_energy(e.toolpath.commands, e.timeline, e.removal ? &*e.removal : nullptr,
                             machine.power, options.energy);
  e.diagnostics.insert(e.diagnostics.end(), e.energy.diagnostics.begin(),
                       e.energy.diagnostics.end());
  e.lines =
      summarise_lines(source, e.dialect, e.timeline, e.removal ? &*e.removal : nullptr, e.energy);
  return e;
}

} // namespace ncjoule
