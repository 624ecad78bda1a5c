// Energy per command and per program: the trapezoid rule over every segment of the operating
// trace, component by component, so the components add up to the total by construction.
#include <algorithm>

#include "ncjoule/energy.hpp"

namespace ncjoule {
namespace {

constexpr double kJoulesPerKwh = 3.6e6;

// Power of a command that has no duration: its modal state, nothing moving.
double instantaneous_power(const CanonCommand& cmd, const PowerConstants& constants) {
  OperatingPoint op;
  const ModalState& s = cmd.state;
  const bool on = s.spindle != SpindleDir::Off && s.spindle_rpm > 0;
  op.spindle_on = on ? 1.0 : 0.0;
  op.spindle_rpm = on ? s.spindle_rpm : 0.0;
  op.coolant_on = (s.mist || s.flood) ? 1.0 : 0.0;
  return component_sum(component_power_w(constants, op));
}

} // namespace

EnergyResult integrate_energy(const std::vector<OperatingSegment>& trace, const Timeline& timeline,
                              const RemovalResult* removal, const PowerConstants& constants,
                              const EnergyOptions& options) {
  EnergyResult result;
  result.model_description = describe_power_constants(constants);
  result.commands.resize(timeline.commands.size());
  for (std::size_t i = 0; i < timeline.commands.size(); ++i) {
    const TimedCommand& tc = timeline.commands[i];
    CommandEnergy& ce = result.commands[i];
    ce.command = i;
    ce.line = tc.line;
    ce.duration_s = tc.duration_s;
    if (removal && i < removal->commands.size()) ce.removed_mm3 = removal->commands[i].removed_mm3;
  }
  std::vector<bool> has_power(timeline.commands.size(), false);
  for (const OperatingSegment& seg : trace) {
    if (seg.command >= result.commands.size()) continue;
    CommandEnergy& ce = result.commands[seg.command];
    const double dt = seg.t1_s - seg.t0_s;
    const ComponentValues a = component_power_w(constants, seg.start);
    const ComponentValues b = component_power_w(constants, seg.end);
    for (std::size_t c = 0; c < kPowerComponentCount; ++c)
      ce.components_j[c] += 0.5 * (a[c] + b[c]) * dt;
    const double peak = std::max(component_sum(a), component_sum(b));
    ce.peak_power_w = has_power[seg.command] ? std::max(ce.peak_power_w, peak) : peak;
    has_power[seg.command] = true;
  }
  for (std::size_t i = 0; i < result.commands.size(); ++i) {
    CommandEnergy& ce = result.commands[i];
    ce.energy_j = component_sum(ce.components_j);
    if (ce.duration_s > 0) {
      ce.mean_power_w = ce.energy_j / ce.duration_s;
    }
    if (ce.removed_mm3 > 0) ce.sec_j_mm3 = ce.energy_j / ce.removed_mm3;
    for (std::size_t c = 0; c < kPowerComponentCount; ++c)
      result.components_j[c] += ce.components_j[c];
    result.peak_power_w = std::max(result.peak_power_w, ce.peak_power_w);
    result.duration_s += ce.duration_s;
  }
  result.energy_j = component_sum(result.components_j);
  if (removal) result.removed_mm3 = removal->removed_mm3;
  if (result.removed_mm3 <= 0)
    for (const CommandEnergy& ce : result.commands)
      result.removed_mm3 += ce.removed_mm3;
  if (result.removed_mm3 > 0) result.sec_j_mm3 = result.energy_j / result.removed_mm3;
  if (timeline.total_s > 0) result.duration_s = timeline.total_s;
  if (result.duration_s > 0) result.mean_power_w = result.energy_j / result.duration_s;
  const double kwh = result.energy_j / kJoulesPerKwh;
  result.co2_kg = kwh * options.co2_kg_per_kwh.value_or(constants.co2_kg_per_kwh);
  result.cost = kwh * options.price_per_kwh.value_or(constants.price_per_kwh);
  result.currency = options.currency.value_or(constants.currency);
  return result;
}

EnergyResult estimate_energy(const std::vector<CanonCommand>& commands, const Timeline& timeline,
                             const RemovalResult* removal, const PowerConstants& constants,
                             const EnergyOptions& options) {
  std::vector<Diagnostic> diagnostics;
  const auto trace = operating_trace(commands, timeline, removal, &diagnostics);
  EnergyResult result = integrate_energy(trace, timeline, removal, constants, options);
  // Commands without duration report the power of their state.
  for (CommandEnergy& ce : result.commands) {
    if (ce.duration_s > 0) continue;
    const std::size_t c = timeline.commands[ce.command].command;
    if (c >= commands.size()) continue;
    ce.mean_power_w = instantaneous_power(commands[c], constants);
    ce.peak_power_w = std::max(ce.peak_power_w, ce.mean_power_w);
  }
  result.diagnostics = std::move(diagnostics);
  return result;
}

} // namespace ncjoule
