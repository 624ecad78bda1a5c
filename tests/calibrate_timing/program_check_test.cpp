// NIST's cover run against the Hurco profile: the run's totals, operation and worst blocks.
#include "synthetic_log.hpp"

#include "ncjoule/text_file.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("program check: NIST's cover on the Hurco profile") {
  const std::string data = std::string(NCJOULE_SOURCE_DIR) + "/tests/logs/data/";
  std::vector<Diagnostic> d;
  auto devices = read_device_file(data + "Devices-Hurco04.xml", d);
  REQUIRE(devices);
  LogEvidence evidence;
  LogReadOptions read;
  read.devices = &*devices;
  REQUIRE(read_controller_log(data + "cover-run.shdr", evidence.log, read, d));
  finish_controller_log(evidence.log, d);
  evidence.runs = find_runs(evidence.log);
  const MachineProfile m = shipped_profile("hurco-vmx24");
  auto text = read_text_file(data + "cover.nc", "a program", d, kDefaultMaxProgramBytes);
  REQUIRE(text);
  LoggedProgram p;
  p.source = make_source(data + "cover.nc", *text);
  p.outline = outline_program(p.source);
  p.options.simulate_removal = false;
  p.estimate = estimate_program(p.source, m, p.options);
  evidence.programs.push_back(std::move(p));
  gather_runs(evidence);
  const auto times = plan_all(evidence, m);
  judge_runs(evidence, times);
  const auto checks = check_programs(evidence, times, 5);
  REQUIRE(checks.size() == 1);
  const ProgramCheck& c = checks[0];
  CHECK(c.usable_runs == 1);
  CHECK(c.measured.median == doctest::Approx(80.14).epsilon(1e-3));
  CHECK(c.predicted_s == doctest::Approx(times[0].total()));
  REQUIRE(c.operations.size() == 1);
  CHECK(c.operations[0].tool == 23);
  CHECK(c.operations[0].measured.median == doctest::Approx(c.measured.median));
  CHECK(c.operations[0].predicted_s == doctest::Approx(c.predicted_s));
  REQUIRE(c.worst_blocks.size() == 5);
  // The worst: the M6 of the tool already in the spindle, timed as a whole change.
  CHECK(c.worst_blocks[0].first == 1);
  CHECK(c.worst_blocks[0].next == 7);
  CHECK(c.worst_blocks[0].predicted_s > c.worst_blocks[0].measured.median + 4);
  for (std::size_t i = 1; i < c.worst_blocks.size(); ++i)
    CHECK(std::abs(c.worst_blocks[i].predicted_s - c.worst_blocks[i].measured.median) <=
          std::abs(c.worst_blocks[i - 1].predicted_s - c.worst_blocks[i - 1].measured.median));
}
