// The figures a guessed stock sets, as ranges from no removal to the guess (estimate.hpp).
#include <algorithm>

#include "ncjoule/estimate.hpp"

namespace ncjoule {

GuessedFigures guessed_figures(const Estimate& e) {
  GuessedFigures g;
  const StockGuessRange& range = e.stock_guess;
  if (!range.guessed) return g;
  g.guessed = true;
  const EnergyResult& energy = e.energy;
  g.removed_mm3 = {std::max(0.0, energy.removed_mm3 - range.removed_mm3), energy.removed_mm3};
  const double floor_j = std::max(0.0, energy.energy_j - range.cutting_energy_j);
  g.energy_j = {floor_j, energy.energy_j};
  g.peak_power_w = {std::min(range.peak_power_floor_w, energy.peak_power_w), energy.peak_power_w};
  g.peak_with_overloads_w = range.peak_power_guess_w;
  // CO2 and electricity follow the energy; the machine-hour cost does not depend on it.
  const double share = energy.energy_j > 0 ? floor_j / energy.energy_j : 1.0;
  g.co2_kg = {energy.co2_kg * share, energy.co2_kg};
  g.cost = {energy.machine_cost + energy.electricity_cost * share, energy.cost};
  return g;
}

} // namespace ncjoule
