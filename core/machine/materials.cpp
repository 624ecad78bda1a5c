// Workpiece materials: the energy it takes to cut them, with where each number comes from.
//
// Metals: the unit power ("specific energy") of Kalpakjian & Schmid, Manufacturing Engineering
// and Technology, Table 21.2, "Approximate range of energy requirements in cutting operations",
// in W s/mm^3 (= J/mm^3), given at the drive motor for 80% efficiency. The range kept here is
// the table's times 0.8 (at the cutting edge; the machine profile's cutting efficiency turns it
// back into power drawn), and the typical value is the range's geometric middle. The table gives
// no Kienzle constants, so the built-in materials get no chip-thickness correction; a machine
// profile can define a material of its own with k_c1.1 and m_c ([power.profile_material]).
// Plastics, wood and MDF have no handbook unit power of this kind: their values are estimates
// from their strength (a specific cutting force of about twice the tensile or shear strength, as
// for ductile metals) and are marked as such in the table and in every header that uses them.
#include <algorithm>
#include <cctype>
#include <cmath>

#include "ncjoule/material.hpp"

namespace ncjoule {
namespace {

constexpr const char* kKalpakjian =
    "Kalpakjian & Schmid, Manufacturing Engineering and Technology, Table 21.2 (unit power at the "
    "drive motor, 80% efficiency)";

std::vector<Material> make_materials() {
  std::vector<Material> m;
  auto add = [&m](std::string name, std::vector<std::string> aliases, double lo, double hi,
                  double kc11, double mc, std::string source, bool estimate = false) {
    Material x;
    x.name = std::move(name);
    x.aliases = std::move(aliases);
    // At the cutting edge: the table's motor values times the 80% efficiency they assume.
    x.kc_min_j_mm3 = 0.8 * lo;
    x.kc_max_j_mm3 = 0.8 * hi;
    x.kc_j_mm3 = std::sqrt(x.kc_min_j_mm3 * x.kc_max_j_mm3);
    x.kc11_n_mm2 = kc11;
    x.mc = mc;
    x.source = std::move(source);
    x.estimate = estimate;
    m.push_back(std::move(x));
  };
  add("aluminium-alloy", {"aluminium", "aluminum", "aluminum-alloy", "al", "6061", "7075", "alu"},
      0.4, 1.1, 0, 0, kKalpakjian);
  add("magnesium-alloy", {"magnesium"}, 0.3, 0.6, 0, 0, kKalpakjian);
  add("brass", {"copper-alloy", "bronze", "copper"}, 1.4, 3.2, 0, 0, kKalpakjian);
  add("cast-iron", {"grey-cast-iron", "gray-cast-iron", "castiron"}, 1.1, 5.4, 0, 0, kKalpakjian);
  add("mild-steel", {"steel", "carbon-steel", "c45", "1045", "s235"}, 2.0, 5.0, 0, 0,
      std::string(kKalpakjian) +
          "; the lower half of its steel range (2-9), for plain carbon steels");
  add("alloy-steel", {"4140", "42crmo4", "tool-steel"}, 3.0, 9.0, 0, 0,
      std::string(kKalpakjian) + "; the upper part of its steel range (2-9), for alloy steels");
  add("stainless-steel", {"stainless", "304", "316", "inox"}, 2.0, 5.0, 0, 0, kKalpakjian);
  add("titanium-alloy", {"titanium", "ti6al4v", "ti-6al-4v"}, 2.0, 5.0, 0, 0, kKalpakjian);
  add("nickel-alloy", {"inconel", "nickel"}, 4.8, 6.7, 0, 0, kKalpakjian);
  add("plastic", {"plastics", "acrylic", "pmma", "pom", "delrin", "nylon", "polyamide", "hdpe"},
      0.08 / 0.8, 0.3 / 0.8, 0, 0,
      "ESTIMATE: a specific cutting force of 80-300 N/mm^2, about two to three times the tensile "
      "strength of engineering thermoplastics (40-100 MPa); no handbook unit power",
      true);
  // Estimates are at the cutting edge already: the 0.8 applied below is undone here.
  add("wood", {"hardwood", "softwood", "plywood"}, 0.02 / 0.8, 0.15 / 0.8, 0, 0,
      "ESTIMATE: specific cutting resistance of 20-150 N/mm^2 across and along the grain at "
      "router chip thicknesses; no handbook unit power",
      true);
  add("mdf", {"fibreboard", "fiberboard", "particleboard"}, 0.03 / 0.8, 0.2 / 0.8, 0, 0,
      "ESTIMATE: 30-200 N/mm^2, as wood, a little higher for the resin binder; no handbook unit "
      "power",
      true);
  return m;
}

std::string normalised(std::string_view name) {
  std::string out;
  for (char c : name) {
    const char l = char(std::tolower(static_cast<unsigned char>(c)));
    out += (l == ' ' || l == '_') ? '-' : l;
  }
  return out;
}

} // namespace

const std::vector<Material>& materials() {
  static const std::vector<Material> all = make_materials();
  return all;
}

std::optional<Material> find_material(std::string_view name) {
  const std::string n = normalised(name);
  for (const Material& m : materials()) {
    if (m.name == n) return m;
    if (std::find(m.aliases.begin(), m.aliases.end(), n) != m.aliases.end()) return m;
  }
  return std::nullopt;
}

double Material::kc_at(double chip_thickness_mm) const {
  if (!(kc11_n_mm2 > 0) || !(chip_thickness_mm > 0)) return kc_j_mm3;
  // Kienzle: k_c = k_c1.1 * h^-m_c, in N/mm^2 = 1e-3 J/mm^3; chips thinner than 5 um are taken
  // as 5 um (the law is not fitted below that).
  const double h = std::clamp(chip_thickness_mm, 0.005, 2.0);
  return 1e-3 * kc11_n_mm2 * std::pow(h, -mc);
}

} // namespace ncjoule
