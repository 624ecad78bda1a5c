// A power log synthesized from a program and known constants, shifted in time and with noise
// and spikes, is fitted back: offset and constants, for every model.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "ncjoule/calibrate.hpp"
#include "program_builder.hpp"

using namespace ncjoule;
using ncjoule::test::ProgramBuilder;

namespace {

// Every axis alone at two feeds, cuts along each axis at two MRRs, two spindle speeds, coolant
// on and off, a tool change: enough for every constant to show in the trace.
ProgramBuilder calibration_program() {
  ProgramBuilder b;
  b.sample_dt_s = 0.05;
  const double a = 800;
  b.dwell(2);
  b.spindle(3000, 1.5);
  b.coolant(true);
  b.traverse({100, 0, 0}, 200, 2000);
  b.traverse({100, 80, 0}, 150, 2000);
  b.traverse({100, 80, -30}, 100, 2000);
  b.feed({40, 80, -30}, 8, 4, a);
  b.feed({100, 80, -30}, 15, 2, a);
  b.feed({100, 40, -30}, 6, 5, a);
  b.feed({100, 80, -30}, 12, 1.5, a);
  b.feed({100, 80, -35}, 1, 20, a);
  b.feed({100, 80, -30}, 3, 0, a);
  b.feed({100, 80, -36}, 2, 12, a);
  b.feed({100, 80, -30}, 5, 0, a);
  b.spindle(6000, 1.0);
  b.feed({40, 80, -30}, 10, 3, a);
  b.feed({10, 40, -30}, 10, 2, a);
  b.feed({80, 40, -30}, 20, 0, a);
  b.feed({80, 90, -30}, 25, 0, a);
  b.feed({80, 90, -10}, 5, 0, a);
  b.coolant(false);
  b.tool_change(2, 6);
  b.spindle(4500, 1.2);
  b.feed({40, 90, -10}, 12, 2.5, a);
  b.feed({40, 60, -10}, 9, 0, a);
  b.spindle(0, 1.0);
  b.dwell(1);
  return b;
}

PowerConstants true_constants(PowerModel model) {
  PowerConstants k;
  k.model = model;
  auto& p = k.pavanaskar;
  p.tare_w = 420;
  p.coolant_w = 110;
  p.spindle_ka_w = 95;
  p.spindle_kb_w_per_rpm = 0.21;
  p.move_ka_w = {60, 80, 110};
  p.move_kb_w_per_mm_s = {0.9, 1.4, 3.0};
  p.cut_ka_w = {30, 45, 60};
  p.cut_kb_w_per_mm3_s = {6, 8, 10};
  k.zhou = {0.9, 0.00018, 8e-7, 1.13, 0, 0, 0, 0};
  k.tool_change_w = 650;
  return k;
}

PowerConstants perturbed(PowerConstants k) {
  for (PowerParameter p : model_parameters(k.model))
    if (p != PowerParameter::ZhouC4) set_parameter(k, p, 0.75 * get_parameter(k, p));
  return k;
}

} // namespace

TEST_CASE("a shifted, noisy power log is fitted back: offset and constants") {
  for (PowerModel model : {PowerModel::Combined, PowerModel::Pavanaskar, PowerModel::Zhou}) {
    CAPTURE(model_name(model));
    const ProgramBuilder b = calibration_program();
    const auto trace = operating_trace(b.commands, b.timeline, &b.removal);
    const PowerConstants truth = true_constants(model);
    const double offset = 6.37; // the program starts 6.37 s into the log
    std::mt19937 rng(12345);
    std::normal_distribution<double> noise(0.0, 8.0);
    PowerLog log;
    log.path = "synthetic.csv";
    for (double t = 0; t <= b.timeline.total_s + offset + 12; t += 0.1) {
      double p = component_sum(component_power_w(truth, operating_point_at(trace, t - offset)));
      p += noise(rng);
      log.t_s.push_back(t);
      log.power_w.push_back(p);
    }
    // Spikes where motors start (Pavanaskar's figures 3.2 and 3.3): outliers for the loss.
    for (double t_spike : {offset + 2.0, offset + 40.0, offset + 75.0}) {
      const auto i = static_cast<std::size_t>(t_spike / 0.1);
      log.power_w[i] += 1500;
      log.power_w[i + 1] += 700;
    }
    LogFitOptions options;
    options.max_offset_s = 20;
    const LogFitResult fit = fit_power_log(log, trace, perturbed(truth), options);
    MESSAGE(model_name(model) << ": offset " << fit.offset_s << " s (true " << offset << "), RMSE "
                              << fit.report.rmse << " W, R^2 " << fit.report.r_squared);
    CHECK(fit.offset_s == doctest::Approx(offset).epsilon(0.005 / offset));
    // The fitted constants reproduce the noise-free trace (the spikes and noise are gone).
    double worst = 0;
    for (double t : log.t_s) {
      const OperatingPoint op = operating_point_at(trace, t - offset);
      worst = std::max(worst, std::abs(component_sum(component_power_w(fit.constants, op)) -
                                       component_sum(component_power_w(truth, op))));
    }
    MESSAGE("worst difference from the noise-free trace: " << worst << " W");
    CHECK(worst < 15.0);
    for (const FittedConstant& c : fit.report.constants) {
      CAPTURE(parameter_info(c.parameter).key);
      const double t = get_parameter(truth, c.parameter);
      if (c.held) {
        // The exponent, and the n^2 term of a straight spindle line, by default.
        CHECK((c.parameter == PowerParameter::ZhouC4 || c.parameter == PowerParameter::SpindleKC));
        continue;
      }
      CHECK(std::isfinite(c.std_error));
      CHECK(std::abs(c.value - t) <= 5 * c.std_error + 1e-12);
      MESSAGE("  " << parameter_info(c.parameter).key << " = " << c.value << " +- " << c.std_error
                   << " (true " << t << ")");
    }
  }
}
