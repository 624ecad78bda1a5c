#include <array>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "sections.hpp"

namespace ncjoule::profile_detail {
namespace {

// An optional range [<stem>_min, <stem>_max] of non-negative numbers (0: not declared), its
// maximum not below its minimum.
std::pair<double, double> optional_range(TableReader& t, const std::string& stem) {
  const double lo = t.optional_number(stem + "_min", Range::NonNegative, 0, 3e5).value_or(0);
  const double hi = t.optional_number(stem + "_max", Range::NonNegative, 0, 3e5).value_or(0);
  if (hi > 0 && hi < lo) t.fail(stem + "_max", "must not be below " + stem + "_min");
  return {lo, hi};
}

PavanaskarConstants read_pavanaskar(TableReader t, std::vector<std::string>& sources) {
  PavanaskarConstants p;
  read_source(t, "power.pavanaskar", sources);
  p.tare_w = t.quantity("tare", Dimension::Power, Range::NonNegative);
  p.coolant_w = t.quantity("coolant", Dimension::Power, Range::NonNegative);
  p.spindle_ka_w = t.quantity("spindle_ka", Dimension::Power, Range::Any);
  p.spindle_kb_w_per_rpm = t.quantity("spindle_kb", Dimension::PowerPerRpm, Range::NonNegative);
  p.spindle_kc_w_per_rpm2 =
      t.optional_quantity("spindle_kc", Dimension::PowerPerRpm2, Range::NonNegative).value_or(0);
  std::tie(p.spindle_fitted_rpm_min, p.spindle_fitted_rpm_max) =
      optional_range(t, "spindle_fitted_rpm");
  constexpr std::array<const char*, 3> names{"x", "y", "z"};
  for (std::size_t i = 0; i < names.size(); ++i) {
    TableReader axis = t.table(names[i]);
    p.move_ka_w[i] = axis.quantity("move_ka", Dimension::Power, Range::Any);
    p.move_kb_w_per_mm_s[i] = axis.quantity("move_kb", Dimension::PowerPerSpeed, Range::Any);
    p.cut_ka_w[i] = axis.quantity("cut_ka", Dimension::Power, Range::Any);
    p.cut_kb_w_per_mm3_s[i] = axis.quantity("cut_kb", Dimension::PowerPerMrr, Range::Any);
    axis.finish();
  }
  t.finish();
  return p;
}

ZhouConstants read_zhou(TableReader t, std::vector<std::string>& sources) {
  ZhouConstants z;
  read_source(t, "power.zhou", sources);
  z.c1_kw = t.quantity("c1", Dimension::KiloWatt, Range::NonNegative);
  z.c2_kw_per_rpm = t.quantity("c2", Dimension::KiloWattPerRpm, Range::NonNegative);
  z.c3 = t.number("c3", Range::NonNegative, 0, 1e3);
  z.c4 = t.number("c4", Range::NonNegative, 0, 5); // an exponent of rpm
  z.d1 = t.number("d1", Range::NonNegative);
  z.d2 = t.number("d2", Range::NonNegative, 0, 5); // an exponent of rpm
  z.d3 = t.number("d3", Range::NonNegative);
  z.d4 = t.number("d4", Range::NonNegative);
  std::tie(z.fitted_rpm_min, z.fitted_rpm_max) = optional_range(t, "fitted_rpm");
  // Its keys carry the unit after min/max: fitted_mrr_min_mm3_s.
  z.fitted_mrr_min_mm3_s =
      t.optional_number("fitted_mrr_min_mm3_s", Range::NonNegative, 0, 1e7).value_or(0);
  z.fitted_mrr_max_mm3_s =
      t.optional_number("fitted_mrr_max_mm3_s", Range::NonNegative, 0, 1e7).value_or(0);
  if (z.fitted_mrr_max_mm3_s > 0 && z.fitted_mrr_max_mm3_s < z.fitted_mrr_min_mm3_s)
    t.fail("fitted_mrr_max_mm3_s", "must not be below fitted_mrr_min_mm3_s");
  t.finish();
  return z;
}

// [power.profile_material]: a material of the profile's own, with its specific cutting energy
// (kc_j_mm3, with an optional range) or Kienzle's constants (kc11_n_mm2, mc), and its source.
Material read_material(TableReader t, std::vector<std::string>& sources) {
  Material m;
  read_source(t, "power.profile_material", sources);
  m.name = t.string("name");
  if (m.name.empty()) t.fail("name", "must not be empty");
  m.source = sources.back(); // "power.profile_material: <its source>", where its k_c is from
  m.kc11_n_mm2 = t.optional_number("kc11_n_mm2", Range::Positive, 50, 2e4).value_or(0);
  m.mc = t.optional_number("mc", Range::NonNegative, 0, 1).value_or(0);
  const auto kc = t.optional_number("kc_j_mm3", Range::Positive, 0.01, 200);
  if (!kc && !(m.kc11_n_mm2 > 0)) t.fail("kc_j_mm3", "give kc_j_mm3, or kc11_n_mm2 and mc");
  // Without a unit power, Kienzle's at a 0.1 mm chip stands for it.
  m.kc_j_mm3 = kc ? *kc : 1e-3 * m.kc11_n_mm2 * std::pow(0.1, -m.mc);
  m.kc_min_j_mm3 =
      t.optional_number("kc_min_j_mm3", Range::Positive, 0.01, 200).value_or(m.kc_j_mm3);
  m.kc_max_j_mm3 =
      t.optional_number("kc_max_j_mm3", Range::Positive, 0.01, 200).value_or(m.kc_j_mm3);
  t.finish();
  return m;
}

std::vector<std::pair<double, double>> read_power_curve(TableReader& t, std::string_view key) {
  std::vector<std::pair<double, double>> curve;
  const toml::node* node = t.raw(key);
  if (!node) return curve;
  const toml::array* list = node->as_array();
  if (!list) t.fail(key, "expected an array of [rpm, watts] pairs");
  for (const toml::node& item : *list) {
    const toml::array* pair = item.as_array();
    if (!pair || pair->size() != 2 || !(*pair)[0].is_number() || !(*pair)[1].is_number())
      t.fail(key, "expected [rpm, watts] pairs, e.g. [[1000, 3000], [8000, 7500]]");
    const double rpm = *(*pair)[0].value<double>(), w = *(*pair)[1].value<double>();
    if (!(rpm >= 0) || !(w > 0) || !std::isfinite(rpm) || !std::isfinite(w))
      t.fail(key, "speeds must be >= 0 and powers > 0");
    if (rpm > 3e5 || w > 1e6)
      t.fail(key, "speeds up to 300000 rpm and powers up to 1000000 W: what a spindle can be");
    if (!curve.empty() && rpm <= curve.back().first)
      t.fail(key, "speeds must increase from pair to pair");
    curve.emplace_back(rpm, w);
  }
  return curve;
}

} // namespace

PowerConstants read_power(TableReader t, std::vector<std::string>& sources) {
  PowerConstants p;
  read_source(t, "power", sources);
  const std::string model = t.choice("model", {"combined", "pavanaskar", "zhou"});
  p.model = model == "combined"     ? PowerModel::Combined
            : model == "pavanaskar" ? PowerModel::Pavanaskar
                                    : PowerModel::Zhou;
  p.tool_change_w = t.quantity("tool_change", Dimension::Power, Range::NonNegative);
  p.co2_kg_per_kwh = t.number("co2_kg_per_kwh", Range::NonNegative, 0, 3);
  p.price_per_kwh = t.number("price_per_kwh", Range::NonNegative, 0, 1000);
  p.machine_rate_per_hour =
      t.optional_number("machine_rate_per_hour", Range::NonNegative, 0, 1e6).value_or(0.0);
  p.currency = t.string("currency");
  // Each model needs its own table; the combined model needs both, or only Pavanaskar's when its
  // cutting term is the material's (Zhou's table gives nothing else to it).
  const bool needs_pavanaskar = p.model != PowerModel::Zhou;
  if (auto pav =
          needs_pavanaskar ? std::optional(t.table("pavanaskar")) : t.optional_table("pavanaskar"))
    p.pavanaskar = read_pavanaskar(*pav, sources);
  // The cutting term: fitted (the Zhou table's c3, c4) or from the workpiece material.
  const std::string cutting =
      t.optional_string("cutting_term").value_or("fitted") == "material" ? "material" : "fitted";
  if (auto raw = t.optional_string("cutting_term"); raw && *raw != "fitted" && *raw != "material")
    t.fail("cutting_term", "must be \"fitted\" or \"material\"");
  p.cutting_term = cutting == "material" ? CuttingTerm::Material : CuttingTerm::Fitted;
  if (p.cutting_term == CuttingTerm::Material && p.model == PowerModel::Pavanaskar)
    t.fail("cutting_term", "the pavanaskar model has its own cutting constants per axis");
  const bool needs_zhou = p.model == PowerModel::Zhou || (p.model == PowerModel::Combined &&
                                                          p.cutting_term == CuttingTerm::Fitted);
  p.cutting_efficiency = t.optional_number("cutting_efficiency", Range::Positive, 0.05, 1)
                             .value_or(p.cutting_efficiency);
  if (p.cutting_efficiency > 1) t.fail("cutting_efficiency", "must be at most 1");
  if (auto material = t.optional_table("profile_material"))
    p.profile_material = read_material(*material, sources);
  p.material = t.optional_string("material")
                   .value_or(p.profile_material ? p.profile_material->name : std::string());
  if (!p.material.empty() && !find_material(p.material) &&
      !(p.profile_material && p.profile_material->name == p.material))
    t.fail("material", "\"" + p.material + "\" is not a material ncjoule knows (docs/models.md)");
  if (p.cutting_term == CuttingTerm::Material && p.material.empty())
    t.fail("material", "the material cutting term needs a default material");
  if (const auto rated = t.optional_quantity("spindle_rated", Dimension::Power, Range::Positive))
    p.spindle_rated_w = *rated;
  p.spindle_power_curve = read_power_curve(t, "spindle_power_curve_rpm_w");
  if (const auto rpm = t.optional_number("hand_spindle_rpm", Range::Positive, 1, 3e5))
    p.hand_spindle_rpm = *rpm;
  if (const auto rpm = t.optional_number("spindle_max_rpm", Range::Positive, 1, 3e5))
    p.spindle_max_rpm = *rpm;
  p.placeholder_spindle = t.optional_boolean("placeholder_spindle").value_or(false);
  if (p.placeholder_spindle &&
      !(p.spindle_rated_w > 0 || !p.spindle_power_curve.empty() || p.spindle_max_rpm > 0))
    t.fail("placeholder_spindle", "says the spindle's rating is a placeholder, but the profile "
                                  "gives no spindle_rated_w, spindle power curve or "
                                  "spindle_max_rpm");
  if (auto zhou = needs_zhou ? std::optional(t.table("zhou")) : t.optional_table("zhou"))
    p.zhou = read_zhou(*zhou, sources);
  t.finish();
  if (p.model != PowerModel::Pavanaskar && p.cutting_term == CuttingTerm::Fitted)
    p.cutting_source = "fitted: " + (sources.empty() ? std::string() : sources.back());
  if (p.cutting_term == CuttingTerm::Material) {
    const Material m = p.profile_material && p.profile_material->name == p.material
                           ? *p.profile_material
                           : *find_material(p.material);
    p = with_material(p, m);
  }
  return p;
}

} // namespace ncjoule::profile_detail
