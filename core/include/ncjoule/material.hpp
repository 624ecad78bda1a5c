// ncjoule workpiece materials: how much energy it takes to cut them, with the source of every
// number (core/machine/materials.cpp holds the table). The combined power model can take its
// cutting term from the material: P_cut = k_c * MRR / efficiency, written in Zhou's form as
// c3 * n^c4 * MRR with c3 = k_c / (1000 * efficiency) kW per mm^3/s and c4 = 0; where the material
// has Kienzle's constants the energy stage scales it by k_c(h) / k_c for the cut's chip.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ncjoule {

struct Material {
  std::string name;                 // "aluminium-alloy", "mild-steel", ...
  std::vector<std::string> aliases; // other names it is found by ("aluminium", "6061", ...)
  // Specific cutting energy at the cutting edge (J/mm^3 = W per mm^3/s): typical, and the
  // published range.
  double kc_j_mm3 = 0;
  double kc_min_j_mm3 = 0, kc_max_j_mm3 = 0;
  // Kienzle's specific cutting force at 1 mm chip thickness (N/mm^2) and exponent, when the
  // source gives them (0: no chip-thickness correction).
  double kc11_n_mm2 = 0;
  double mc = 0;
  std::string source;
  bool estimate = false; // no handbook value: an estimate, said wherever it is used

  // k_c at chip thickness h (mm): Kienzle's law where its constants are known, else kc_j_mm3.
  double kc_at(double chip_thickness_mm) const;
};

// The built-in table (names, typical values, ranges and sources: docs/models.md).
const std::vector<Material>& materials();
// By name or alias, any case, '-', '_' or ' ' alike; std::nullopt when unknown.
std::optional<Material> find_material(std::string_view name);

} // namespace ncjoule
