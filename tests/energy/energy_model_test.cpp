// The power models and their integration: components, air cuts, spindle and coolant states,
// multi-axis moves, tool changes, ramps, totals.
#include <doctest/doctest.h>

#include <cmath>

#include "ncjoule/energy.hpp"
#include "program_builder.hpp"

using namespace ncjoule;
using ncjoule::test::ProgramBuilder;

namespace {

std::size_t idx(PowerComponent c) {
  return static_cast<std::size_t>(c);
}

PowerConstants distinct_constants(PowerModel model) {
  PowerConstants k;
  k.model = model;
  auto& p = k.pavanaskar;
  p.tare_w = 300;
  p.coolant_w = 90;
  p.spindle_ka_w = 80;
  p.spindle_kb_w_per_rpm = 0.2;
  p.move_ka_w = {40, 55, 70};
  p.move_kb_w_per_mm_s = {1.5, 2.5, 4.0};
  p.cut_ka_w = {20, 30, 45};
  p.cut_kb_w_per_mm3_s = {3.0, 5.0, 8.0};
  k.zhou = {0.78, 0.00017, 8.06e-7, 1.13, 5.39e-6, 1.82, 0.15, 779};
  k.tool_change_w = 400;
  k.co2_kg_per_kwh = 0.4;
  k.price_per_kwh = 0.25;
  return k;
}

ProgramBuilder everything_program() {
  ProgramBuilder b;
  b.dwell(1);
  b.spindle(3000, 1.5);
  b.coolant(true);
  b.traverse({50, 20, 5}, 200, 2000);
  b.feed({50, 20, -2}, 2, 8, 500);
  b.feed({90, 50, -2}, 10, 3, 500);
  b.spindle(6000, 0.8);
  b.feed({90, 10, -2}, 12, 2.5, 500);
  b.coolant(false);
  b.tool_change(2, 5);
  b.spindle(0, 1);
  b.dwell(0.5);
  return b;
}

} // namespace

TEST_CASE("energy components add up to the total, per command and per program") {
  for (PowerModel model : {PowerModel::Combined, PowerModel::Pavanaskar, PowerModel::Zhou}) {
    CAPTURE(model_name(model));
    const ProgramBuilder b = everything_program();
    const auto k = distinct_constants(model);
    const EnergyResult r = estimate_energy(b.commands, b.timeline, &b.removal, k);
    REQUIRE(r.commands.size() == b.timeline.commands.size());
    double sum_commands = 0;
    for (const CommandEnergy& ce : r.commands) {
      CHECK(component_sum(ce.components_j) == doctest::Approx(ce.energy_j).epsilon(1e-12));
      sum_commands += ce.energy_j;
    }
    CHECK(r.energy_j > 0);
    CHECK(component_sum(r.components_j) == doctest::Approx(r.energy_j).epsilon(1e-12));
    CHECK(sum_commands == doctest::Approx(r.energy_j).epsilon(1e-12));
    CHECK(r.duration_s == doctest::Approx(b.timeline.total_s));
    CHECK(r.mean_power_w == doctest::Approx(r.energy_j / r.duration_s));
    CHECK(r.sec_j_mm3 == doctest::Approx(r.energy_j / b.removal.removed_mm3));
    CHECK(r.co2_kg == doctest::Approx(r.energy_j / 3.6e6 * 0.4));
    CHECK(r.cost == doctest::Approx(r.energy_j / 3.6e6 * 0.25));
    CHECK(r.components_j[idx(PowerComponent::Cutting)] > 0);
    CHECK(r.components_j[idx(PowerComponent::ToolChange)] == doctest::Approx(5 * 400.0));
  }
}

TEST_CASE("CO2 and price overrides replace the profile's values") {
  const ProgramBuilder b = everything_program();
  EnergyOptions o;
  o.co2_kg_per_kwh = 0.1;
  o.price_per_kwh = 2;
  o.currency = "USD";
  const auto r = estimate_energy(b.commands, b.timeline, &b.removal,
                                 distinct_constants(PowerModel::Combined), o);
  CHECK(r.co2_kg == doctest::Approx(r.energy_j / 3.6e6 * 0.1));
  CHECK(r.cost == doctest::Approx(r.energy_j / 3.6e6 * 2));
  CHECK(r.currency == "USD");
}

TEST_CASE("zero MRR gives the air-cut power: the Zhou air cut is c1 + c2*n") {
  ProgramBuilder b;
  b.spindle(1300);
  b.feed({100, 0, 0}, 3.0); // no material
  auto k = distinct_constants(PowerModel::Zhou);
  const auto r = estimate_energy(b.commands, b.timeline, &b.removal, k);
  const CommandEnergy& cut = r.commands.back();
  CHECK(cut.components_j[idx(PowerComponent::Cutting)] == 0);
  CHECK(cut.mean_power_w == doctest::Approx(1000 * (0.78 + 0.00017 * 1300)));
  CHECK(cut.mean_power_w == doctest::Approx(1001.0));

  k.model = PowerModel::Combined;
  const auto rc = estimate_energy(b.commands, b.timeline, nullptr, k);
  const auto& p = k.pavanaskar;
  CHECK(rc.commands.back().mean_power_w ==
        doctest::Approx(p.tare_w + p.spindle_ka_w + p.spindle_kb_w_per_rpm * 1300 + p.move_ka_w[0] +
                        p.move_kb_w_per_mm_s[0] * 3.0));
  CHECK(rc.commands.back().components_j[idx(PowerComponent::Cutting)] == 0);
}

TEST_CASE("a program with the spindle off draws no spindle power, coolant off no coolant") {
  ProgramBuilder b;
  b.feed({100, 0, 0}, 5.0, 2.0);
  b.dwell(2);
  for (PowerModel model : {PowerModel::Combined, PowerModel::Pavanaskar, PowerModel::Zhou}) {
    const auto r = estimate_energy(b.commands, b.timeline, &b.removal, distinct_constants(model));
    CHECK(r.components_j[idx(PowerComponent::Spindle)] == 0);
    CHECK(r.components_j[idx(PowerComponent::Coolant)] == 0);
    CHECK(r.components_j[idx(PowerComponent::Tare)] > 0);
    if (model != PowerModel::Pavanaskar) CHECK(r.components_j[idx(PowerComponent::Cutting)] == 0);
  }
}

TEST_CASE("a move along several axes splits its feed among them by the velocity vector") {
  ProgramBuilder b;
  b.spindle(2000);
  b.feed({30, 40, 0}, 10.0); // direction (0.6, 0.8, 0): Fx = 6, Fy = 8 mm/s
  const auto k = distinct_constants(PowerModel::Pavanaskar);
  const auto& p = k.pavanaskar;
  const auto r = estimate_energy(b.commands, b.timeline, nullptr, k);
  const CommandEnergy& ce = r.commands.back();
  REQUIRE(ce.duration_s == doctest::Approx(5.0));
  CHECK(ce.components_j[idx(PowerComponent::AxisX)] / ce.duration_s ==
        doctest::Approx(p.move_ka_w[0] + p.move_kb_w_per_mm_s[0] * 6.0));
  CHECK(ce.components_j[idx(PowerComponent::AxisY)] / ce.duration_s ==
        doctest::Approx(p.move_ka_w[1] + p.move_kb_w_per_mm_s[1] * 8.0));
  // Z does not move: not even its KA is drawn.
  CHECK(ce.components_j[idx(PowerComponent::AxisZ)] == 0);
}

TEST_CASE("Pavanaskar's cut terms: each axis by its share of the path, only while cutting") {
  ProgramBuilder b;
  b.spindle(2000);
  b.feed({30, 40, 0}, 10.0, 2.0); // MRR 20 mm^3/s, shares 3/7 and 4/7
  const auto k = distinct_constants(PowerModel::Pavanaskar);
  const auto& p = k.pavanaskar;
  const auto r = estimate_energy(b.commands, b.timeline, &b.removal, k);
  const CommandEnergy& ce = r.commands.back();
  const double mrr = 20.0;
  const double expected = 3.0 / 7 * (p.cut_ka_w[0] + p.cut_kb_w_per_mm3_s[0] * mrr) +
                          4.0 / 7 * (p.cut_ka_w[1] + p.cut_kb_w_per_mm3_s[1] * mrr);
  CHECK(ce.components_j[idx(PowerComponent::Cutting)] / ce.duration_s == doctest::Approx(expected));

  // Material only in the first half of the block: KA_cut is drawn for half the time, which an
  // MRR averaged over the block first would not give.
  ProgramBuilder half;
  half.spindle(2000);
  half.feed({100, 0, 0}, 10.0, 2.0);
  auto& steps = half.removal.commands.back().step_volume_mm3;
  half.removal.removed_mm3 = 0;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    if (i >= steps.size() / 2) steps[i] = 0;
    half.removal.removed_mm3 += steps[i];
  }
  half.removal.commands.back().removed_mm3 = half.removal.removed_mm3;
  const auto rh = estimate_energy(half.commands, half.timeline, &half.removal, k);
  const double t = rh.commands.back().duration_s;
  CHECK(rh.commands.back().components_j[idx(PowerComponent::Cutting)] ==
        doctest::Approx(0.5 * t * (p.cut_ka_w[0] + p.cut_kb_w_per_mm3_s[0] * 20.0)));
  CHECK(rh.commands.back().peak_power_w > rh.commands.back().mean_power_w);
  // The cut states hold their axis (Table 4.1 measured them feeding): the X move line is drawn
  // only over the half that cuts nothing.
  const double move_x = p.move_ka_w[0] + p.move_kb_w_per_mm_s[0] * 10.0;
  CHECK(rh.commands.back().components_j[idx(PowerComponent::AxisX)] ==
        doctest::Approx(0.5 * t * move_x).epsilon(0.01));
  CHECK(ce.components_j[idx(PowerComponent::AxisX)] == 0);
  CHECK(ce.components_j[idx(PowerComponent::AxisY)] == 0);
  // The combined model's cutting term is the cut alone: its move lines stay while cutting.
  const auto kc = distinct_constants(PowerModel::Combined);
  const auto rc = estimate_energy(half.commands, half.timeline, &half.removal, kc);
  CHECK(
      rc.commands.back().components_j[idx(PowerComponent::AxisX)] ==
      doctest::Approx(t * (kc.pavanaskar.move_ka_w[0] + kc.pavanaskar.move_kb_w_per_mm_s[0] * 10.0))
          .epsilon(0.01));
}

TEST_CASE("a spindle line that bends: KA + KB n + KC n^2") {
  PowerConstants k = distinct_constants(PowerModel::Pavanaskar);
  k.pavanaskar.spindle_ka_w = 91.67;
  k.pavanaskar.spindle_kb_w_per_rpm = 0.1;
  k.pavanaskar.spindle_kc_w_per_rpm2 = 2e-5;
  OperatingPoint op;
  op.spindle_on = 1;
  op.spindle_rpm = 10000;
  // 91.67 W + 0.1 W/rpm * 10,000 + 2e-5 W/rpm^2 * 10,000^2 = 91.67 + 1000 + 2000 W.
  CHECK(component_power_w(k, op)[idx(PowerComponent::Spindle)] == doctest::Approx(3091.67));
  CHECK(describe_power_constants(k).find("+ 2e-05 W/rpm^2*n^2") != std::string::npos);
  k.pavanaskar.spindle_kc_w_per_rpm2 = 0;
  CHECK(describe_power_constants(k).find("n^2") == std::string::npos);
}

TEST_CASE("tool change and spindle ramps") {
  ProgramBuilder b;
  b.spindle(3000, 2.0); // from off
  b.spindle(6000, 1.0); // between speeds
  b.coolant(true);
  b.tool_change(3, 4.0); // spindle stands, coolant stays on
  b.spindle(0, 1.0);     // the spindle had been at 6000 in the modal state
  const auto k = distinct_constants(PowerModel::Combined);
  const auto& p = k.pavanaskar;
  auto spindle_w = [&](double n) { return p.spindle_ka_w + p.spindle_kb_w_per_rpm * n; };
  const auto r = estimate_energy(b.commands, b.timeline, nullptr, k);
  const auto sp = idx(PowerComponent::Spindle);
  CHECK(r.commands[0].components_j[sp] == doctest::Approx(2.0 * 0.5 * spindle_w(3000)));
  CHECK(r.commands[1].components_j[sp] ==
        doctest::Approx(1.0 * 0.5 * (spindle_w(3000) + spindle_w(6000))));
  const CommandEnergy& change = r.commands[3];
  CHECK(change.components_j[sp] == 0);
  CHECK(change.mean_power_w == doctest::Approx(p.tare_w + p.coolant_w + k.tool_change_w));
  CHECK(r.commands[4].components_j[sp] == doctest::Approx(1.0 * 0.5 * spindle_w(6000)));
  // A dwell-like command with no samples draws its state's constant power.
  ProgramBuilder d;
  d.spindle(1000);
  d.dwell(3);
  const auto rd = estimate_energy(d.commands, d.timeline, nullptr, k);
  CHECK(rd.commands[1].energy_j == doctest::Approx(3 * (p.tare_w + spindle_w(1000))));
  // Zero-duration commands report their state's power, not 0 W.
  CHECK(rd.commands[0].mean_power_w == doctest::Approx(p.tare_w + spindle_w(1000)));
}

TEST_CASE("power is integrated over the samples: a trapezoid profile's energy") {
  ProgramBuilder b;
  b.sample_dt_s = 0.01;
  b.traverse({0, 100, 0}, 50.0, 500.0); // accelerates, cruises, decelerates
  const auto k = distinct_constants(PowerModel::Pavanaskar);
  const auto& p = k.pavanaskar;
  const auto r = estimate_energy(b.commands, b.timeline, nullptr, k);
  const CommandEnergy& ce = r.commands.back();
  // KB * integral of speed = KB * length, exactly, whatever the profile.
  CHECK(ce.components_j[idx(PowerComponent::AxisY)] ==
        doctest::Approx(p.move_ka_w[1] * ce.duration_s + p.move_kb_w_per_mm_s[1] * 100.0));
  CHECK(ce.peak_power_w ==
        doctest::Approx(p.tare_w + p.move_ka_w[1] + p.move_kb_w_per_mm_s[1] * 50));
}

TEST_CASE("the Zhou SEC model and SEC = 1000 P / MRR agree at Anziani's test 2 point") {
  const ZhouConstants z{0.78, 0.00017, 8.06e-7, 1.13, 5.39e-6, 1.82, 0.15, 779};
  CHECK(zhou_power_kw(z, 1300, 18) == doctest::Approx(1.049).epsilon(0.001));
  CHECK(1000 * zhou_power_kw(z, 1300, 18) / 18 == doctest::Approx(58.27).epsilon(0.001));
  CHECK(zhou_sec_model_j_mm3(z, 1300, 18) == doctest::Approx(56.62).epsilon(0.002));
}
