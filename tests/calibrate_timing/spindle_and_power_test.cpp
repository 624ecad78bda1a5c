// The spindle's run-up from its logged speed; a run's logged power as a power log.
#include "synthetic_log.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

// A run whose spindle runs up at 5000 rpm/s to 10000 rpm, logged every 0.13 s, and whose power
// steps from 1000 W to 3000 W.
LogEvidence spindle_run(int runs) {
  LogEvidence e;
  e.programs.emplace_back();
  for (int k = 0; k < runs; ++k) {
    LogRun run;
    run.start_s = 100.0 * k;
    run.end_s = run.start_s + 10;
    run.ended = "PROGRAM_COMPLETED";
    run.spindle.push_back({run.start_s, 0});
    const double up = run.start_s + 1 + 0.05 * k; // the ramp starts here
    for (double t = up + 0.07; t < up + 3; t += 0.13)
      run.spindle.push_back({t, std::min(10000.0, 5000 * (t - up))});
    run.spindle.push_back({up + 4, 10000}); // logged on change only: one more at the top
    run.power = {{run.start_s, 1000}, {run.start_s + 5, 3000}};
    e.runs.push_back(run);
    LoggedRun lr;
    lr.run = std::size_t(k);
    lr.usable = true;
    e.program_runs.push_back(lr);
  }
  return e;
}

} // namespace

TEST_CASE("spindle run-up: times to each 1000 rpm from the logged speed") {
  const SpindleRunUp r = measure_spindle_run_up(spindle_run(4));
  CHECK(r.run_ups == 4);
  REQUIRE(r.points.size() == 9); // 1000 to 9000 rpm (up to 500 below the top)
  CHECK(r.points[0].first == 1000);
  CHECK(r.points[0].second == doctest::Approx(0.2).epsilon(0.05));
  CHECK(r.points[8].second == doctest::Approx(1.8).epsilon(0.02));
  CHECK(r.rpm_per_s == doctest::Approx(5000).epsilon(0.1));
  // Fewer than three run-ups tell nothing.
  CHECK(measure_spindle_run_up(spindle_run(2)).points.empty());
}

TEST_CASE("run power: the logged power held between changes, read every quarter second") {
  const LogEvidence e = spindle_run(1);
  const auto log = run_power_log(e, e.program_runs[0]);
  REQUIRE(log);
  CHECK(log->t_s.front() == 0);
  CHECK(log->t_s.back() == doctest::Approx(10));
  CHECK(log->power_w.front() == 1000);
  CHECK(log->power_w.back() == 3000);
  CHECK(log->t_s.size() == 41);
  const MeasuredEnergy m = measure_energy(*log);
  CHECK(m.energy_j == doctest::Approx(5 * 1000 + 5 * 3000).epsilon(0.02));
}
