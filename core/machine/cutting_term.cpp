// The cutting term of a machine's power model, from a workpiece material, and the spindle's
// rating against speed.
#include <algorithm>
#include <cstdio>

#include "ncjoule/machine.hpp"

namespace ncjoule {

double rated_spindle_power_w(const PowerConstants& power, double rpm) {
  const auto& curve = power.spindle_power_curve;
  if (curve.empty()) return power.spindle_rated_w;
  if (rpm <= curve.front().first) return curve.front().second;
  if (rpm >= curve.back().first) return curve.back().second;
  const auto hi = std::lower_bound(curve.begin(), curve.end(), rpm,
                                   [](const auto& point, double r) { return point.first < r; });
  const auto lo = hi - 1;
  const double w = (rpm - lo->first) / (hi->first - lo->first);
  return lo->second + w * (hi->second - lo->second);
}

PowerConstants with_material(const PowerConstants& power, const Material& material, bool* used) {
  const bool applies = power.cutting_term == CuttingTerm::Material;
  if (used) *used = applies;
  if (!applies) return power;
  PowerConstants p = power;
  p.material = material.name;
  p.cutting_material = material;
  // P_cut = k_c * MRR / efficiency (W), written as Zhou's c3 * n^c4 * MRR (kW): c4 = 0.
  p.zhou.c3 = material.kc_j_mm3 / (1000.0 * p.cutting_efficiency);
  p.zhou.c4 = 0;
  // A fitted model's ranges say nothing of the material term.
  p.zhou.fitted_rpm_min = p.zhou.fitted_rpm_max = 0;
  p.zhou.fitted_mrr_min_mm3_s = p.zhou.fitted_mrr_max_mm3_s = 0;
  char text[96];
  std::snprintf(text, sizeof text, ": k_c %.3g J/mm^3 at the edge, efficiency %.2g; ",
                material.kc_j_mm3, p.cutting_efficiency);
  p.cutting_source = "material " + material.name + text + material.source;
  return p;
}

} // namespace ncjoule
