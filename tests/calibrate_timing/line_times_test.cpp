// Predicted line times follow the overrides a run was logged at.
#include "synthetic_log.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("line times: the rapid part scales with 1/rapid override, exact at 50%") {
  const MachineProfile m = shipped_profile("hurco-vmx24");
  LoggedProgram p;
  p.source = make_source("synthetic.nc", kSyntheticProgram);
  p.options.simulate_removal = false;
  const LineTimes t = plan_line_times(p, m, true);
  MachineProfile half = m;
  for (AxisLimits& a : half.kinematics.axes)
    a.rapid_mm_s *= 0.5;
  const Estimate full = estimate_program(p.source, m, p.options);
  const Estimate slow = estimate_program(p.source, half, p.options);
  CHECK(t.total() == doctest::Approx(full.time_s));
  CHECK(t.between(1, 1 << 30, 0.5) == doctest::Approx(slow.time_s).epsilon(1e-9));
  // A feed line has no rapid part; a long rapid has one.
  CHECK(t.b[9] == 0); // N70 G1 Z-.1 F40.
  CHECK(t.b[25] > 0); // N230 X4. Y3. (a rapid)
  CHECK(t.feed[9] == 1);
  // Feed moves follow the feed override.
  CHECK(t.between(9, 10, 1, 0.5) == doctest::Approx(2 * t.between(9, 10)));
  const LineTimes only = plan_line_times(p, m, false);
  CHECK(only.total() == doctest::Approx(full.time_s));
  CHECK(only.between(25, 26, 0.5) == doctest::Approx(only.between(25, 26)));
}

TEST_CASE("runs at a logged rapid override are predicted at it") {
  const MachineProfile m = shipped_profile("hurco-vmx24");
  LogEvidence evidence = synthetic_evidence(m, m, 2, 0, 50);
  CHECK(needs_rapid_override(evidence, 0));
  const auto times = plan_all(evidence, m);
  judge_runs(evidence, times);
  REQUIRE(evidence.program_runs.size() == 2);
  CHECK(evidence.program_runs[0].usable);
  CHECK(evidence.alignments[0].rapid_override_min == doctest::Approx(0.5));
  const auto checks = check_programs(evidence, times);
  CHECK(checks[0].predicted_s == doctest::Approx(checks[0].measured.median).epsilon(1e-3));
  CHECK(checks[0].predicted_s > times[0].total() + 0.1); // slower than at 100%
}
