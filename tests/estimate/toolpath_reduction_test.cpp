// The toolpath kept for drawing stays within its point budget whatever the path, and keeps where
// the tool starts and ends.
#include <doctest/doctest.h>

#include <string>

#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"

using namespace ncjoule;

namespace {

Estimate run(const std::string& text) {
  static const MachineProfile machine =
      load_profile(std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/generic-3axis.toml");
  EstimateOptions options;
  options.simulate_removal = false;
  return estimate_program(make_source("path.ngc", text), machine, options);
}

} // namespace

TEST_CASE("rapid and feed alternating on every move: the path is thinned to its budget") {
  // Every move changes between rapid and feed, so no tolerance can merge two points: thinning
  // must fall back to dropping points (it once re-scanned the whole path on every move).
  std::string program = "G21 G90 F1000 S10000 M3\n";
  const int moves = 60000;
  for (int i = 0; i < moves; ++i)
    program += (i % 2 ? "G1 X" : "G0 X") + std::to_string(i % 80) + " Y" +
               std::to_string((i * 37) % 80) + "\n";
  program += "M2\n";
  const Estimate e = run(program);
  REQUIRE_FALSE(e.failed);
  CHECK(e.path.size() <= 12001);
  CHECK(e.path.size() >= 3000);
  CHECK(e.path.back().line == moves); // the last move (0-based line of the last G-word line)
}

TEST_CASE("a short path is kept point for point") {
  const Estimate e = run("G21 G90 F500\nG0 X0 Y0 Z1\nG1 Z-1\nG1 X10\nG1 Y10\nG0 Z5\nM2\n");
  REQUIRE_FALSE(e.failed);
  REQUIRE(e.path.size() >= 5);
  CHECK(e.path.back().z == doctest::Approx(5));
}
