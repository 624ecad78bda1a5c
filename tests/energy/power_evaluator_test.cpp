// PowerEvaluator, the estimator's way to evaluate power at many points, gives component_power_w's
// numbers bit for bit: every model, every parameter set, at points on and between the states.
#include <doctest/doctest.h>

#include <cstring>
#include <random>
#include <vector>

#include "ncjoule/energy.hpp"

using namespace ncjoule;

namespace {

// Every parameter a value of its own, some of them zero (a term a profile leaves out).
PowerConstants random_constants(PowerModel model, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> value(0.0, 500.0);
  PowerConstants k;
  k.model = model;
  for (std::size_t i = 0; i < kPowerParameterCount; ++i)
    set_parameter(k, static_cast<PowerParameter>(i), rng() % 5 == 0 ? 0.0 : value(rng));
  k.zhou.c3 = value(rng) * 1e-8;
  k.zhou.c4 = 0.5 + value(rng) / 500;
  return k;
}

// Switches at 0 or 1 mostly, and in between as inside a ramp; cutting or not.
OperatingPoint random_point(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto share = [&] { return rng() % 3 == 0 ? unit(rng) : double(rng() % 2); };
  OperatingPoint op;
  op.spindle_on = share();
  op.spindle_rpm = op.spindle_on > 0 ? 24000 * unit(rng) : 0.0;
  op.coolant_on = share();
  for (int i = 0; i < 3; ++i) {
    op.axis_moving[i] = share();
    op.axis_speed_mm_s[i] = 200 * unit(rng);
    op.cut_share[i] = unit(rng);
  }
  op.mrr_mm3_s = rng() % 2 == 0 ? 0.0 : 3000 * unit(rng);
  op.tool_change = rng() % 10 == 0 ? 1.0 : 0.0;
  op.cutting_factor = 0.5 + unit(rng);
  return op;
}

bool same_bits(const ComponentValues& a, const ComponentValues& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

} // namespace

TEST_CASE("PowerEvaluator gives component_power_w's numbers bit for bit") {
  std::mt19937_64 rng(43);
  for (const PowerModel model : {PowerModel::Combined, PowerModel::Pavanaskar, PowerModel::Zhou}) {
    CAPTURE(model_name(model));
    int nonzero = 0, differ = 0;
    for (int set = 0; set < 50; ++set) {
      const PowerConstants k = random_constants(model, rng);
      const PowerEvaluator evaluate(k);
      for (int i = 0; i < 400; ++i) {
        const OperatingPoint op = random_point(rng);
        const ComponentValues expected = component_power_w(k, op);
        differ += !same_bits(evaluate(op), expected);
        nonzero += component_sum(expected) > 0;
      }
    }
    CHECK(differ == 0);
    CHECK(nonzero > 15000); // the points exercise the terms, not only zeros
  }
}

TEST_CASE("PowerEvaluator keeps the constants it was made with") {
  std::mt19937_64 rng(7);
  PowerConstants k = random_constants(PowerModel::Pavanaskar, rng);
  set_parameter(k, PowerParameter::Tare, 250);
  const PowerEvaluator evaluate(k);
  const OperatingPoint idle;
  const double tare = evaluate(idle)[static_cast<std::size_t>(PowerComponent::Tare)];
  CHECK(tare == 250);
  set_parameter(k, PowerParameter::Tare, 400); // a copy: the evaluator does not follow
  CHECK(evaluate(idle)[static_cast<std::size_t>(PowerComponent::Tare)] == tare);
}

TEST_CASE("EnergyIntegrator's energy and segment powers are the model's at every segment end") {
  // The integrator evaluates a point once when a segment starts where the last one ended. A
  // chain where half the starts are the last end and half are new points (some differing only
  // in one field) must give what evaluating every end afresh gives, bit for bit.
  std::mt19937_64 rng(11);
  for (const PowerModel model : {PowerModel::Combined, PowerModel::Pavanaskar, PowerModel::Zhou}) {
    CAPTURE(model_name(model));
    const PowerConstants k = random_constants(model, rng);
    EnergyIntegrator integrator(k);
    std::vector<OperatingSegment> chain;
    OperatingPoint end = random_point(rng);
    double t = 0;
    for (int i = 0; i < 3000; ++i) {
      OperatingSegment seg;
      seg.t0_s = t;
      seg.t1_s = t += 0.01 * double(1 + rng() % 7);
      switch (rng() % 4) {
      case 0:
        seg.start = random_point(rng);
        break;
      case 1: // the last end, one field off: it must not be taken for it
        seg.start = end;
        seg.start.mrr_mm3_s = end.mrr_mm3_s + 1;
        break;
      default:
        seg.start = end;
      }
      seg.end = rng() % 5 == 0 ? seg.start : random_point(rng);
      end = seg.end;
      chain.push_back(seg);
    }
    std::vector<SegmentPower> powers;
    const TimedCommand timed{};
    const CommandEnergy ce = integrator.integrate(0, CanonCommand{}, timed, chain.data(),
                                                  chain.data() + chain.size(), 0.0, &powers);
    REQUIRE(powers.size() == chain.size());
    ComponentValues expected_j{};
    int differ = 0;
    for (std::size_t i = 0; i < chain.size(); ++i) {
      const ComponentValues a = component_power_w(k, chain[i].start);
      const ComponentValues b = component_power_w(k, chain[i].end);
      differ += powers[i].start_w != component_sum(a) || powers[i].end_w != component_sum(b);
      for (std::size_t c = 0; c < kPowerComponentCount; ++c)
        expected_j[c] += 0.5 * (a[c] + b[c]) * (chain[i].t1_s - chain[i].t0_s);
    }
    CHECK(differ == 0);
    CHECK(same_bits(ce.components_j, expected_j));
    CHECK(component_sum(expected_j) > 0);
  }
}
