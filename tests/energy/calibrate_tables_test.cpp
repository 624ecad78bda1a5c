// Steady-state fits recover known constants from synthetic readings with noise, within a few
// of their reported standard errors (fixed seeds).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "ncjoule/calibrate.hpp"

using namespace ncjoule;

namespace {

constexpr double kSigmas = 4.0;

void check_recovered(const FitReport& fit, PowerParameter p, double truth) {
  CAPTURE(parameter_info(p).key);
  const FittedConstant* c = fit.find(p);
  REQUIRE(c != nullptr);
  CHECK_FALSE(c->held);
  CHECK(std::isfinite(c->std_error));
  CHECK(c->std_error > 0);
  CHECK(std::abs(c->value - truth) <= kSigmas * c->std_error);
  MESSAGE(parameter_info(p).key << ": fitted " << c->value << " +- " << c->std_error << ", true "
                                << truth);
}

} // namespace

TEST_CASE("spindle, axis-motion and cutting lines are recovered from noisy readings") {
  std::mt19937 rng(20240501);
  std::normal_distribution<double> noise(0.0, 6.0);
  PowerConstants known;
  known.pavanaskar.tare_w = 410;
  known.pavanaskar.spindle_ka_w = 120;
  known.pavanaskar.spindle_kb_w_per_rpm = 0.18;
  known.pavanaskar.move_ka_w = {60, 75, 90};
  known.pavanaskar.move_kb_w_per_mm_s = {1.2, 2.1, 3.3};
  const auto& p = known.pavanaskar;

  std::vector<SteadyStateReading> spindle;
  for (double n = 1000; n <= 8000; n += 500)
    spindle.push_back(
        {n, 0, 0, p.tare_w + p.spindle_ka_w + p.spindle_kb_w_per_rpm * n + noise(rng)});
  const FitReport s = fit_spindle(spindle, p.tare_w);
  CHECK(s.converged);
  CHECK(s.r_squared > 0.99);
  CHECK(s.rmse == doctest::Approx(6.0).epsilon(0.5));
  check_recovered(s, PowerParameter::SpindleKA, 120);
  check_recovered(s, PowerParameter::SpindleKB, 0.18);
  // The table's straight line replaces a base profile's curve whole, its n^2 term included.
  PowerConstants bent = known;
  bent.pavanaskar.spindle_kc_w_per_rpm2 = 2e-5;
  apply_fit(bent, s);
  CHECK(bent.pavanaskar.spindle_kc_w_per_rpm2 == 0);
  CHECK(bent.pavanaskar.spindle_kb_w_per_rpm == doctest::Approx(0.18).epsilon(0.05));

  std::vector<SteadyStateReading> axis_y;
  for (double f = 5; f <= 150; f += 10)
    axis_y.push_back({0, f, 0, p.tare_w + 75 + 2.1 * f + noise(rng)});
  const FitReport m = fit_axis_move(axis_y, Axis::Y, known);
  check_recovered(m, PowerParameter::MoveKAY, 75);
  check_recovered(m, PowerParameter::MoveKBY, 2.1);

  // A cut state holds its axis feeding (the model draws the cut line in place of the move line):
  // above tare and spindle, Z feeding at 2 mm/s (90 + 3.3 * 2 W) and cutting (25 + 4.5 * MRR W)
  // make one line, KA_cut = 121.6 W, not the 25 W left after taking the move off.
  std::vector<SteadyStateReading> cut_z;
  for (double mrr = 2; mrr <= 60; mrr += 4) {
    const double rpm = 3000, feed = 2;
    cut_z.push_back({rpm, feed, mrr,
                     p.tare_w + p.spindle_ka_w + p.spindle_kb_w_per_rpm * rpm + 90 + 3.3 * feed +
                         25 + 4.5 * mrr + noise(rng)});
  }
  const FitReport c = fit_axis_cut(cut_z, Axis::Z, known);
  check_recovered(c, PowerParameter::CutKAZ, 121.6);
  check_recovered(c, PowerParameter::CutKBZ, 4.5);
}

TEST_CASE("Zhou's power and SEC models are recovered, all coefficients >= 0") {
  const ZhouConstants truth{0.78, 0.00017, 8.06e-7, 1.13, 5.39e-6, 1.82, 0.15, 779};
  std::mt19937 rng(7);
  std::normal_distribution<double> noise_kw(0.0, 0.01);
  std::vector<SteadyStateReading> readings;
  for (double n : {500.0, 900.0, 1300.0, 1700.0, 2100.0})
    for (double mrr : {3.0, 9.0, 18.0, 27.0, 36.0, 42.0, 48.0})
      readings.push_back({n, 0, mrr, 1000 * (zhou_power_kw(truth, n, mrr) + noise_kw(rng))});
  REQUIRE(readings.size() == 35);
  const FitReport power = fit_zhou_power(readings);
  CHECK(power.converged);
  CHECK(power.dof == 31);
  CHECK(power.rmse == doctest::Approx(0.01).epsilon(0.5));
  check_recovered(power, PowerParameter::ZhouC1, truth.c1_kw);
  check_recovered(power, PowerParameter::ZhouC2, truth.c2_kw_per_rpm);
  check_recovered(power, PowerParameter::ZhouC3, truth.c3);
  check_recovered(power, PowerParameter::ZhouC4, truth.c4);
  for (const auto& c : power.constants)
    CHECK(c.value >= 0);

  std::normal_distribution<double> noise_sec(0.0, 1.5);
  std::vector<SteadyStateReading> sec_readings;
  for (const auto& r : readings) {
    const double sec = zhou_sec_model_j_mm3(truth, r.rpm, r.mrr_mm3_s) + noise_sec(rng);
    sec_readings.push_back({r.rpm, 0, r.mrr_mm3_s, sec * r.mrr_mm3_s});
  }
  const FitReport sec = fit_zhou_sec(sec_readings);
  CHECK(sec.converged);
  CHECK(sec.r_squared > 0.99);
  check_recovered(sec, PowerParameter::ZhouD1, truth.d1);
  check_recovered(sec, PowerParameter::ZhouD2, truth.d2);
  check_recovered(sec, PowerParameter::ZhouD3, truth.d3);
  check_recovered(sec, PowerParameter::ZhouD4, truth.d4);
}

TEST_CASE("Zhou's fit keeps a coefficient at 0 rather than going negative") {
  // Power falls slightly with speed: unconstrained least squares would give c2 < 0.
  std::vector<SteadyStateReading> readings;
  for (double n : {500.0, 1300.0, 2100.0})
    for (double mrr : {5.0, 20.0, 40.0})
      readings.push_back({n, 0, mrr, 1000 * (0.9 - 2e-5 * n + 1e-6 * std::pow(n, 1.1) * mrr)});
  const FitReport fit = fit_zhou_power(readings);
  const FittedConstant* c2 = fit.find(PowerParameter::ZhouC2);
  REQUIRE(c2 != nullptr);
  CHECK(c2->value >= 0);
  CHECK(c2->value < 1e-9);
  for (const auto& c : fit.constants)
    CHECK(c.value >= 0);
}

TEST_CASE("fits refuse what they cannot determine, and numbers no solver can take, without a "
          "crash") {
  // One row: a line through it is any line.
  const FitReport one = fit_spindle({{3000, 0, 0, 900}}, 400);
  CHECK(one.refused.find("1 usable row") != std::string::npos);
  CHECK(one.constants.empty());
  PowerConstants k;
  k.pavanaskar.spindle_kb_w_per_rpm = 0.25;
  apply_fit(k, one);
  CHECK(k.pavanaskar.spindle_kb_w_per_rpm == 0.25); // nothing applied
  // Three rows at one speed: no slope.
  const FitReport flat =
      fit_spindle({{3000, 0, 0, 900}, {3000, 0, 0, 910}, {3000, 0, 0, 905}}, 400);
  CHECK(flat.refused.find("same spindle speed") != std::string::npos);
  // Zhou: cuts at a single speed cannot give the speed exponent.
  std::vector<SteadyStateReading> one_speed;
  for (double mrr : {0.0, 5.0, 10.0, 20.0, 40.0})
    one_speed.push_back({2000, 0, mrr, 900 + 3 * mrr});
  CHECK_FALSE(fit_zhou_power(one_speed).refused.empty());
  CHECK_FALSE(fit_zhou_sec(one_speed).refused.empty());
  // 1e300 W readings (past the CSV's checks, as a library caller may pass them): refused, where
  // 1e308 once crashed inside Eigen's SVD under Ceres' covariance.
  for (double huge : {1e300, 1e308, std::numeric_limits<double>::infinity()}) {
    CAPTURE(huge);
    std::vector<SteadyStateReading> r;
    for (double n = 1000; n <= 5000; n += 1000)
      r.push_back({n, 0, n / 100, huge});
    CHECK_FALSE(fit_spindle(r, 0).refused.empty());
    CHECK_FALSE(fit_zhou_power(r).refused.empty());
    CHECK_FALSE(fit_zhou_sec(r).refused.empty());
  }
}
