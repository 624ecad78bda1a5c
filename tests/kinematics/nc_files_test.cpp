// Every program LinuxCNC ships (Debian package linuxcnc-uspace), interpreted and planned: no
// block may take negative or NaN time, and the blocks add up to the program.
#include <cmath>
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "test_helpers.hpp"

namespace fs = std::filesystem;
using namespace ncjoule;

TEST_CASE("LinuxCNC's nc_files plan with finite, non-negative block times") {
  const fs::path folder = "/usr/share/linuxcnc/ncfiles";
  if (!fs::is_directory(folder)) {
    MESSAGE("linuxcnc-uspace is not installed: skipped");
    return;
  }
  int programs = 0;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (entry.path().extension() != ".ngc") continue;
    CAPTURE(entry.path().string());
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    InterpreterOptions options;
    options.max_commands = 2'000'000;
    const Toolpath toolpath = interpret(make_source(entry.path().string(), text.str()), options);
    for (const MachineProfile& machine : {test::round_machine(),
                                          [] {
                                            MachineProfile m = test::round_machine();
                                            m.kinematics.rapid_mode = RapidMode::DogLeg;
                                            m.kinematics.feed_profile = FeedProfile::SCurve;
                                            for (AxisLimits& a : m.kinematics.axes)
                                              a.jerk_mm_s3 = 10000;
                                            return m;
                                          }(),
                                          [] {
                                            MachineProfile m = test::round_machine();
                                            m.kinematics.junction_rule = JunctionRule::LinuxCnc29;
                                            return m;
                                          }()}) {
      const Timeline t = plan(toolpath.commands, machine);
      double sum = 0;
      bool all_valid = true;
      for (const TimedCommand& c : t.commands) {
        all_valid &= std::isfinite(c.duration_s) && c.duration_s >= 0;
        sum += c.duration_s;
      }
      CHECK(all_valid);
      CHECK(std::isfinite(t.total_s));
      CHECK(t.total_s == doctest::Approx(sum));
    }
    ++programs;
  }
  CHECK(programs > 10);
}
