#include <array>

#include "sections.hpp"

namespace ncjoule::profile_detail {
namespace {

PavanaskarConstants read_pavanaskar(TableReader t, std::vector<std::string>& sources) {
  PavanaskarConstants p;
  read_source(t, "power.pavanaskar", sources);
  p.tare_w = t.quantity("tare", Dimension::Power, Range::NonNegative);
  p.coolant_w = t.quantity("coolant", Dimension::Power, Range::NonNegative);
  p.spindle_ka_w = t.quantity("spindle_ka", Dimension::Power, Range::Any);
  p.spindle_kb_w_per_rpm = t.quantity("spindle_kb", Dimension::PowerPerRpm, Range::NonNegative);
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
  z.c3 = t.number("c3", Range::NonNegative);
  z.c4 = t.number("c4", Range::NonNegative);
  z.d1 = t.number("d1", Range::NonNegative);
  z.d2 = t.number("d2", Range::NonNegative);
  z.d3 = t.number("d3", Range::NonNegative);
  z.d4 = t.number("d4", Range::NonNegative);
  t.finish();
  return z;
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
  p.co2_kg_per_kwh = t.number("co2_kg_per_kwh", Range::NonNegative);
  p.price_per_kwh = t.number("price_per_kwh", Range::NonNegative);
  p.currency = t.string("currency");
  // Each model needs its own table; the combined model needs both.
  const bool needs_pavanaskar = p.model != PowerModel::Zhou;
  const bool needs_zhou = p.model != PowerModel::Pavanaskar;
  if (auto pav =
          needs_pavanaskar ? std::optional(t.table("pavanaskar")) : t.optional_table("pavanaskar"))
    p.pavanaskar = read_pavanaskar(*pav, sources);
  if (auto zhou = needs_zhou ? std::optional(t.table("zhou")) : t.optional_table("zhou"))
    p.zhou = read_zhou(*zhou, sources);
  t.finish();
  return p;
}

} // namespace ncjoule::profile_detail
