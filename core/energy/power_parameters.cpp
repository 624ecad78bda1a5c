// The power constants as a flat, named list: one table maps each parameter to its key, unit,
// component and field of PowerConstants.
#include <array>
#include <stdexcept>

#include "ncjoule/energy.hpp"

namespace ncjoule {
namespace {

using P = PowerParameter;
using C = PowerComponent;

constexpr std::array<PowerParameterInfo, kPowerParameterCount> kInfo{{
    {"pavanaskar.tare_w", "W", C::Tare},
    {"pavanaskar.coolant_w", "W", C::Coolant},
    {"pavanaskar.spindle_ka_w", "W", C::Spindle},
    {"pavanaskar.spindle_kb_w_per_rpm", "W/rpm", C::Spindle},
    {"pavanaskar.spindle_kc_w_per_rpm2", "W/rpm^2", C::Spindle},
    {"pavanaskar.x.move_ka_w", "W", C::AxisX},
    {"pavanaskar.y.move_ka_w", "W", C::AxisY},
    {"pavanaskar.z.move_ka_w", "W", C::AxisZ},
    {"pavanaskar.x.move_kb_w_per_mm_s", "W/(mm/s)", C::AxisX},
    {"pavanaskar.y.move_kb_w_per_mm_s", "W/(mm/s)", C::AxisY},
    {"pavanaskar.z.move_kb_w_per_mm_s", "W/(mm/s)", C::AxisZ},
    {"pavanaskar.x.cut_ka_w", "W", C::Cutting},
    {"pavanaskar.y.cut_ka_w", "W", C::Cutting},
    {"pavanaskar.z.cut_ka_w", "W", C::Cutting},
    {"pavanaskar.x.cut_kb_w_per_mm3_s", "W/(mm^3/s)", C::Cutting},
    {"pavanaskar.y.cut_kb_w_per_mm3_s", "W/(mm^3/s)", C::Cutting},
    {"pavanaskar.z.cut_kb_w_per_mm3_s", "W/(mm^3/s)", C::Cutting},
    {"zhou.c1_kw", "kW", C::Tare},
    {"zhou.c2_kw_per_rpm", "kW/rpm", C::Spindle},
    {"zhou.c3", "kW/(rpm^c4 mm^3/s)", C::Cutting},
    {"zhou.c4", "1", C::Cutting},
    {"zhou.d1", "J/mm^3/rpm^d2", C::Cutting},
    {"zhou.d2", "1", C::Cutting},
    {"zhou.d3", "J s/(mm^6 rpm)", C::Cutting},
    {"zhou.d4", "J/s", C::Cutting},
    {"tool_change_w", "W", C::ToolChange},
}};

// Pointer to the field a parameter names.
double* field(PowerConstants& k, PowerParameter p) {
  auto& pv = k.pavanaskar;
  auto& z = k.zhou;
  switch (p) {
  case P::Tare:
    return &pv.tare_w;
  case P::Coolant:
    return &pv.coolant_w;
  case P::SpindleKA:
    return &pv.spindle_ka_w;
  case P::SpindleKB:
    return &pv.spindle_kb_w_per_rpm;
  case P::SpindleKC:
    return &pv.spindle_kc_w_per_rpm2;
  case P::MoveKAX:
    return &pv.move_ka_w[0];
  case P::MoveKAY:
    return &pv.move_ka_w[1];
  case P::MoveKAZ:
    return &pv.move_ka_w[2];
  case P::MoveKBX:
    return &pv.move_kb_w_per_mm_s[0];
  case P::MoveKBY:
    return &pv.move_kb_w_per_mm_s[1];
  case P::MoveKBZ:
    return &pv.move_kb_w_per_mm_s[2];
  case P::CutKAX:
    return &pv.cut_ka_w[0];
  case P::CutKAY:
    return &pv.cut_ka_w[1];
  case P::CutKAZ:
    return &pv.cut_ka_w[2];
  case P::CutKBX:
    return &pv.cut_kb_w_per_mm3_s[0];
  case P::CutKBY:
    return &pv.cut_kb_w_per_mm3_s[1];
  case P::CutKBZ:
    return &pv.cut_kb_w_per_mm3_s[2];
  case P::ZhouC1:
    return &z.c1_kw;
  case P::ZhouC2:
    return &z.c2_kw_per_rpm;
  case P::ZhouC3:
    return &z.c3;
  case P::ZhouC4:
    return &z.c4;
  case P::ZhouD1:
    return &z.d1;
  case P::ZhouD2:
    return &z.d2;
  case P::ZhouD3:
    return &z.d3;
  case P::ZhouD4:
    return &z.d4;
  case P::ToolChange:
    return &k.tool_change_w;
  }
  throw std::logic_error("unknown power parameter");
}

} // namespace

const PowerParameterInfo& parameter_info(PowerParameter parameter) {
  return kInfo.at(static_cast<std::size_t>(parameter));
}

double get_parameter(const PowerConstants& constants, PowerParameter parameter) {
  return *field(const_cast<PowerConstants&>(constants), parameter);
}

void set_parameter(PowerConstants& constants, PowerParameter parameter, double value) {
  *field(constants, parameter) = value;
}

std::vector<PowerParameter> model_parameters(PowerModel model) {
  std::vector<PowerParameter> list;
  auto add_range = [&](PowerParameter first, PowerParameter last) {
    for (auto i = static_cast<int>(first); i <= static_cast<int>(last); ++i)
      list.push_back(static_cast<PowerParameter>(i));
  };
  switch (model) {
  case PowerModel::Pavanaskar:
    add_range(P::Tare, P::CutKBZ);
    break;
  case PowerModel::Combined:
    add_range(P::Tare, P::MoveKBZ);
    add_range(P::ZhouC3, P::ZhouC4);
    break;
  case PowerModel::Zhou:
    add_range(P::ZhouC1, P::ZhouC4);
    break;
  }
  list.push_back(P::ToolChange);
  return list;
}

std::string_view model_name(PowerModel model) {
  switch (model) {
  case PowerModel::Combined:
    return "combined";
  case PowerModel::Pavanaskar:
    return "pavanaskar";
  case PowerModel::Zhou:
    return "zhou";
  }
  return "combined";
}

std::optional<PowerModel> model_from_name(std::string_view name) {
  for (PowerModel m : {PowerModel::Combined, PowerModel::Pavanaskar, PowerModel::Zhou})
    if (model_name(m) == name) return m;
  return std::nullopt;
}

std::string_view component_name(PowerComponent component) {
  static constexpr std::array<std::string_view, kPowerComponentCount> names{
      "tare", "coolant", "spindle", "axis_x", "axis_y", "axis_z", "cutting", "tool_change"};
  return names.at(static_cast<std::size_t>(component));
}

} // namespace ncjoule
