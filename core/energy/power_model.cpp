// The three power models evaluated at one operating point. All of them go through
// power_features(), which calibration uses too, so a fitted constant means what the
// estimator does with it.
#include <cmath>
#include <cstdio>
#include <string>

#include "ncjoule/energy.hpp"

namespace ncjoule {
namespace {

using P = PowerParameter;

constexpr double kWattsPerKilowatt = 1000.0;

std::size_t index(PowerParameter p) {
  return static_cast<std::size_t>(p);
}

void add_axis_motion_features(const OperatingPoint& op, PowerFeatures& f) {
  constexpr P ka[3] = {P::MoveKAX, P::MoveKAY, P::MoveKAZ};
  constexpr P kb[3] = {P::MoveKBX, P::MoveKBY, P::MoveKBZ};
  for (int i = 0; i < 3; ++i) {
    f.linear[index(ka[i])] = op.axis_moving[i];
    f.linear[index(kb[i])] = op.axis_speed_mm_s[i];
  }
}

void drop_axis_motion_features(PowerFeatures& f) {
  for (P p : {P::MoveKAX, P::MoveKAY, P::MoveKAZ, P::MoveKBX, P::MoveKBY, P::MoveKBZ})
    f.linear[index(p)] = 0.0;
}

void add_shared_pavanaskar_features(const OperatingPoint& op, PowerFeatures& f) {
  f.linear[index(P::Tare)] = 1.0;
  f.linear[index(P::Coolant)] = op.coolant_on;
  f.linear[index(P::SpindleKA)] = op.spindle_on;
  f.linear[index(P::SpindleKB)] = op.spindle_on * op.spindle_rpm;
  f.linear[index(P::SpindleKC)] = op.spindle_on * op.spindle_rpm * op.spindle_rpm;
  add_axis_motion_features(op, f);
}

} // namespace

PowerFeatures power_features(PowerModel model, const OperatingPoint& op) {
  PowerFeatures f;
  switch (model) {
  case PowerModel::Pavanaskar: {
    add_shared_pavanaskar_features(op, f);
    constexpr P ka[3] = {P::CutKAX, P::CutKAY, P::CutKAZ};
    constexpr P kb[3] = {P::CutKBX, P::CutKBY, P::CutKBZ};
    for (int i = 0; i < 3; ++i) {
      f.linear[index(ka[i])] = op.cut_share[i];
      f.linear[index(kb[i])] = op.cut_share[i] * op.mrr_mm3_s;
    }
    // A cut state was measured with its axis feeding (Table 4.1: a cut cannot run without it),
    // so while the tool cuts, the cut lines stand for the axes too: adding the move lines as
    // well counts the axis drives twice (docs/models.md).
    if (op.mrr_mm3_s > 0) drop_axis_motion_features(f);
    break;
  }
  case PowerModel::Combined:
    add_shared_pavanaskar_features(op, f);
    f.zhou_mrr_weight_w = kWattsPerKilowatt * op.spindle_on * op.mrr_mm3_s;
    f.zhou_rpm = op.spindle_rpm;
    break;
  case PowerModel::Zhou:
    f.linear[index(P::ZhouC1)] = kWattsPerKilowatt;
    f.linear[index(P::ZhouC2)] = kWattsPerKilowatt * op.spindle_on * op.spindle_rpm;
    f.zhou_mrr_weight_w = kWattsPerKilowatt * op.spindle_on * op.mrr_mm3_s;
    f.zhou_rpm = op.spindle_rpm;
    break;
  }
  f.linear[index(P::ToolChange)] = op.tool_change;
  return f;
}

// model_parameters() of each model, made once: power is evaluated millions of times.
static const std::vector<PowerParameter>& parameters_of(PowerModel model) {
  static const std::vector<PowerParameter> lists[] = {model_parameters(PowerModel::Combined),
                                                      model_parameters(PowerModel::Pavanaskar),
                                                      model_parameters(PowerModel::Zhou)};
  return lists[static_cast<int>(model)];
}

ComponentValues component_power_w(const PowerConstants& constants, const OperatingPoint& point) {
  ComponentValues power{};
  const PowerFeatures f = power_features(constants.model, point);
  for (PowerParameter p : parameters_of(constants.model)) {
    const double x = f.linear[index(p)];
    if (x == 0.0) continue;
    power[static_cast<std::size_t>(parameter_info(p).component)] += x * get_parameter(constants, p);
  }
  if (f.zhou_mrr_weight_w != 0.0 && f.zhou_rpm > 0.0)
    power[static_cast<std::size_t>(PowerComponent::Cutting)] +=
        f.zhou_mrr_weight_w * constants.zhou.c3 * std::pow(f.zhou_rpm, constants.zhou.c4) *
        point.cutting_factor;
  return power;
}

PowerEvaluator::PowerEvaluator(const PowerConstants& constants)
    : model_(constants.model), zhou_c3_(constants.zhou.c3), zhou_c4_(constants.zhou.c4) {
  for (PowerParameter p : parameters_of(model_))
    terms_[term_count_++] = {p, parameter_info(p).component, get_parameter(constants, p)};
}

ComponentValues PowerEvaluator::operator()(const OperatingPoint& point) const {
  ComponentValues power{};
  const PowerFeatures f = power_features(model_, point);
  for (std::size_t i = 0; i < term_count_; ++i) {
    const Term& t = terms_[i];
    const double x = f.linear[index(t.parameter)];
    if (x == 0.0) continue;
    power[static_cast<std::size_t>(t.component)] += x * t.value;
  }
  // n^0 is 1 for every n (the material's cutting term has no speed exponent): no pow.
  if (f.zhou_mrr_weight_w != 0.0 && f.zhou_rpm > 0.0)
    power[static_cast<std::size_t>(PowerComponent::Cutting)] +=
        f.zhou_mrr_weight_w * zhou_c3_ * (zhou_c4_ == 0 ? 1.0 : std::pow(f.zhou_rpm, zhou_c4_)) *
        point.cutting_factor;
  return power;
}

double zhou_power_kw(const ZhouConstants& z, double rpm, double mrr_mm3_s) {
  const double cutting = rpm > 0 ? z.c3 * std::pow(rpm, z.c4) * mrr_mm3_s : 0.0;
  return z.c1_kw + z.c2_kw_per_rpm * rpm + cutting;
}

double zhou_sec_model_j_mm3(const ZhouConstants& z, double rpm, double mrr_mm3_s) {
  return z.d1 * std::pow(rpm, z.d2) + z.d3 * rpm / mrr_mm3_s + z.d4 / mrr_mm3_s;
}

// Every constant the model's formula uses, with its unit; per-axis values as X/Y/Z. Numbers are
// printed with %g so that they read back as the profile wrote them.
std::string describe_power_constants(const PowerConstants& k) {
  char text[640];
  const auto& p = k.pavanaskar;
  char spindle_text[96];
  if (p.spindle_kc_w_per_rpm2 != 0)
    std::snprintf(spindle_text, sizeof spindle_text, "%g W + %g W/rpm*n + %g W/rpm^2*n^2",
                  p.spindle_ka_w, p.spindle_kb_w_per_rpm, p.spindle_kc_w_per_rpm2);
  else
    std::snprintf(spindle_text, sizeof spindle_text, "%g W + %g W/rpm*n", p.spindle_ka_w,
                  p.spindle_kb_w_per_rpm);
  const std::string spindle = spindle_text;
  const auto& z = k.zhou;
  switch (k.model) {
  case PowerModel::Zhou:
    std::snprintf(text, sizeof text,
                  "Zhou: P = %g kW + %g kW/rpm*n + %g*n^%g*MRR kW (n rpm, MRR mm^3/s); "
                  "tool change %g W",
                  z.c1_kw, z.c2_kw_per_rpm, z.c3, z.c4, k.tool_change_w);
    break;
  case PowerModel::Pavanaskar:
    std::snprintf(text, sizeof text,
                  "Pavanaskar Eq. 3.12: tare %g W, coolant %g W, spindle %s, "
                  "move X/Y/Z KA %g/%g/%g W KB %g/%g/%g W/(mm/s), "
                  "cut X/Y/Z KA %g/%g/%g W KB %g/%g/%g W/(mm^3/s); tool change %g W",
                  p.tare_w, p.coolant_w, spindle.c_str(), p.move_ka_w[0], p.move_ka_w[1],
                  p.move_ka_w[2], p.move_kb_w_per_mm_s[0], p.move_kb_w_per_mm_s[1],
                  p.move_kb_w_per_mm_s[2], p.cut_ka_w[0], p.cut_ka_w[1], p.cut_ka_w[2],
                  p.cut_kb_w_per_mm3_s[0], p.cut_kb_w_per_mm3_s[1], p.cut_kb_w_per_mm3_s[2],
                  k.tool_change_w);
    break;
  case PowerModel::Combined:
    std::snprintf(text, sizeof text,
                  "Combined (Pavanaskar Eq. 3.12 with Zhou's cutting term): tare %g W, "
                  "coolant %g W, spindle %s, "
                  "move X/Y/Z KA %g/%g/%g W KB %g/%g/%g W/(mm/s), "
                  "cutting %g*n^%g*MRR kW (n rpm, MRR mm^3/s); tool change %g W",
                  p.tare_w, p.coolant_w, spindle.c_str(), p.move_ka_w[0], p.move_ka_w[1],
                  p.move_ka_w[2], p.move_kb_w_per_mm_s[0], p.move_kb_w_per_mm_s[1],
                  p.move_kb_w_per_mm_s[2], z.c3, z.c4, k.tool_change_w);
    break;
  }
  std::string out = text;
  // Where the cutting term comes from: the machine's fit or the workpiece material's table.
  if (k.model != PowerModel::Pavanaskar && k.cutting_term == CuttingTerm::Material)
    out += "; cutting term from the " + k.cutting_source;
  return out;
}

} // namespace ncjoule
