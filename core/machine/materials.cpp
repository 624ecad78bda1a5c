// Workpiece materials: the energy it takes to cut them, with where each number comes from.
//
// Metals: Kienzle's law, k_c = k_c1.1 * h^-m_c (N/mm^2 = 1e-3 J/mm^3 at the cutting edge, h the
// chip thickness in mm), with the constants of one catalogue for every group so that the groups
// compare: ISCAR's table of material groups to DIN/ISO 513 and VDI 3323 (kc1 at 1 mm^2 of chip,
// mc, for a 0 deg rake). They agree within about 5% with Mitsubishi's and Tungaloy's milling
// tables at 0.1 mm for steels and cast iron; for aluminium other sources are up to 1.7x lower
// (the Tabellenbuch Zerspantechnik gives 470 / 0.27 for soft wrought alloys), and the two ISCAR
// editions differ for titanium (1245 / 0.24 in 2022, 2110 / 0.22 in 2017; the 2017 value is kept,
// as Kalpakjian & Schmid and Groover put titanium with the alloy steels). The typical value is
// k_c at a 0.05 mm chip, the range k_c from 0.3 mm down to 0.01 mm chips.
// Magnesium and nickel alloys keep Kalpakjian & Schmid's unit power (Table 21.2, at the motor for
// 80% efficiency; the range here is the table's times 0.8, at the edge): no Kienzle constants
// were found for them, so they get no chip-thickness correction.
// Wood and MDF: Ettelt's F_c = k * b * sqrt(h), Kienzle's form with m_c = 0.5, for cutting across
// the grain (the hardest direction: an upper bound), as Zerspanung von Holz und Holzwerkstoffen
// (Hanser, 2nd ed., p. 120) quotes it; particleboard milling measured at 32-38 N/mm^2 (Palubicki,
// Materials 14:2208, 2021) agrees. Plastics: no published Kienzle constants; an ESTIMATE from
// the metals' ratio of k_c1.1 to tensile strength (2.3-3.6) and 65-80 MPa for POM, PA6, PMMA,
// marked as such wherever it is used.
#include <algorithm>
#include <cctype>
#include <cmath>

#include "ncjoule/material.hpp"

namespace ncjoule {
namespace {

constexpr const char* kKalpakjian =
    "Kalpakjian & Schmid, Manufacturing Engineering and Technology, Table 21.2 (unit power at the "
    "drive motor, 80% efficiency)";
constexpr const char* kIscar = "ISCAR, material groups to DIN/ISO 513 and VDI 3323 (kc1, mc)";
constexpr const char* kEttelt = "Ettelt (1987) in Zerspanung von Holz und Holzwerkstoffen, Hanser, "
                                "2nd ed., p. 120 (across the grain: an upper bound)";

// The chip thicknesses a row's typical value and range are given at (mm).
constexpr double kTypicalChipMm = 0.05, kThickChipMm = 0.3, kThinChipMm = 0.01;

std::vector<Material> make_materials() {
  std::vector<Material> m;
  // A row of Kienzle constants.
  auto kienzle = [&m](std::string name, std::vector<std::string> aliases, double kc11, double mc,
                      std::string source, bool estimate = false) {
    Material x;
    x.name = std::move(name);
    x.aliases = std::move(aliases);
    x.kc11_n_mm2 = kc11;
    x.mc = mc;
    x.kc_j_mm3 = x.kc_at(kTypicalChipMm);
    x.kc_min_j_mm3 = x.kc_at(kThickChipMm);
    x.kc_max_j_mm3 = x.kc_at(kThinChipMm);
    x.source = std::move(source);
    x.estimate = estimate;
    m.push_back(std::move(x));
  };
  // A row of Kalpakjian & Schmid's unit power (no chip-thickness correction).
  auto unit_power = [&m](std::string name, std::vector<std::string> aliases, double lo, double hi) {
    Material x;
    x.name = std::move(name);
    x.aliases = std::move(aliases);
    x.kc_min_j_mm3 = 0.8 * lo; // at the cutting edge: the motor values times their 80%
    x.kc_max_j_mm3 = 0.8 * hi;
    x.kc_j_mm3 = std::sqrt(x.kc_min_j_mm3 * x.kc_max_j_mm3);
    x.source = kKalpakjian;
    m.push_back(std::move(x));
  };
  const std::string iscar = kIscar;
  kienzle("aluminium-alloy",
          {"aluminium", "aluminum", "aluminum-alloy", "al", "6061", "7075", "alu"}, 800, 0.25,
          iscar + ", group 22 (wrought, age-hardened, 100 HB); other sources to 1.7x lower");
  kienzle("cast-aluminium", {"cast-aluminum", "al-si", "alsi", "a356", "alsi10mg"}, 700, 0.25,
          iscar + ", groups 23-24 (cast Al-Si, up to 12% Si)");
  unit_power("magnesium-alloy", {"magnesium"}, 0.3, 0.6);
  kienzle("brass", {"copper-alloy", "bronze", "copper"}, 700, 0.27,
          iscar + ", group 27 (brass); pure copper likely higher");
  kienzle("cast-iron", {"grey-cast-iron", "gray-cast-iron", "castiron"}, 1150, 0.20,
          iscar + ", group 15 (grey cast iron, 180 HB)");
  kienzle("mild-steel", {"steel", "carbon-steel", "s235", "1018", "c15"}, 1350, 0.21,
          iscar + ", group 1 (C < 0.25%, 125 HB)");
  kienzle("medium-carbon-steel", {"c45", "1045", "ck45"}, 1500, 0.22,
          iscar + ", group 2 (C >= 0.25%, annealed, 190 HB)");
  kienzle("alloy-steel", {"4140", "42crmo4", "tool-steel"}, 1775, 0.24,
          iscar + ", group 6 (low-alloy, annealed)");
  kienzle("stainless-steel", {"stainless", "304", "316", "inox"}, 2150, 0.20,
          iscar + ", group 14 (austenitic, 180 HB)");
  kienzle("titanium-alloy", {"titanium", "ti6al4v", "ti-6al-4v"}, 2110, 0.22,
          iscar + " (2017 edition), group 37 (alpha+beta); the 2022 edition gives 1245 / 0.24");
  unit_power("nickel-alloy", {"inconel", "nickel"}, 4.8, 6.7);
  kienzle("plastic", {"plastics", "acrylic", "pmma", "pom", "delrin", "nylon", "polyamide", "hdpe"},
          200, 0.25,
          "ESTIMATE: k_c1.1 2.5-3.5 times the tensile strength (65-80 MPa), as for the metals; m_c "
          "as the metals'; no published Kienzle constants",
          true);
  kienzle("wood", {"hardwood", "beech", "oak", "plywood"}, 42, 0.5,
          std::string(kEttelt) + ", beech and oak");
  kienzle("softwood", {"pine", "spruce"}, 29.5, 0.5, std::string(kEttelt) + ", pine and spruce");
  kienzle("mdf", {"fibreboard", "fiberboard", "particleboard"}, 25, 0.5,
          std::string(kEttelt) + ", MDF; particleboard milling measured at 32-38 N/mm^2 "
                                 "(Palubicki 2021) agrees");
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
