// The first pass's commands held for the second (command_tape.hpp): replayed bit for bit, and an
// estimate that replays them gives the numbers of one that interprets the text again.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <fstream>
#include <sstream>

#include "command_tape.hpp"
#include "estimate_checks.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/report.hpp"

using namespace ncjoule;
using namespace estimate_test;
using estimate_detail::CommandTape;

namespace {

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
bool same_pose(const Pose& a, const Pose& b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z) && same_bits(a.a, b.a) &&
         same_bits(a.b, b.b) && same_bits(a.c, b.c);
}
// Every field, doubles bit for bit.
bool same_command(const CanonCommand& a, const CanonCommand& b) {
  const ModalState &s = a.state, &t = b.state;
  return a.kind == b.kind && a.line == b.line && a.call_line == b.call_line &&
         same_pose(a.start, b.start) && same_pose(a.end, b.end) && a.start_known == b.start_known &&
         a.machine_axes == b.machine_axes && same_bits(a.centre_first, b.centre_first) &&
         same_bits(a.centre_second, b.centre_second) && a.rotation == b.rotation &&
         a.plane == b.plane && same_bits(a.value, b.value) && a.text == b.text &&
         s.feed_mode == t.feed_mode && same_bits(s.feed, t.feed) &&
         same_bits(s.spindle_rpm, t.spindle_rpm) && s.spindle == t.spindle && s.mist == t.mist &&
         s.flood == t.flood && s.tool == t.tool && s.inch == t.inch && s.path_mode == t.path_mode &&
         same_bits(s.path_tolerance, t.path_tolerance) && s.plane == t.plane;
}

// Records `commands`, replays them twice (kept, then freed), and says how many came back
// different (or missing) over both.
std::size_t replay_differences(const std::vector<CanonCommand>& commands) {
  CommandTape tape(std::size_t(1) << 30);
  for (const CanonCommand& c : commands)
    tape.record(c);
  REQUIRE(tape.complete());
  CHECK(tape.commands() == commands.size());
  std::size_t differ = 0;
  for (const bool release : {false, true}) {
    std::size_t i = 0;
    tape.replay(
        [&](const CanonCommand& c) {
          if (i >= commands.size() || !same_command(c, commands[i])) ++differ;
          ++i;
        },
        release);
    differ += i > commands.size() ? i - commands.size() : commands.size() - i;
    CHECK((tape.bytes() == 0) == release); // freed as it was read the last time
  }
  return differ;
}

std::string read_sample(const std::string& name) {
  std::ifstream in(std::string(NCJOULE_SOURCE_DIR) + "/samples/" + name, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A program with a bit of everything the tape writes: units and plane changes, arcs in three
// planes and a helix, a subprogram called twice (call lines other than the line), a rotary
// axis, comments and a message, coolant, dwell, a canned cycle, G53 (machine axes), -0 and
// the same line giving several commands.
const char* kMixedProgram = "%\n"
                            "(a long comment to outgrow the small-string buffer of std::string)\n"
                            "G21 G90 G17 G94\nT1 M6\nS8000 M3\nM8\n"
                            "G0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X10 Y-0.0\nG2 X20 Y0 I5 J0\n"
                            "G18 G3 X25 Z-2 I2.5 K0\nG19 G2 Y5 Z-1 J2.5 K0\nG17\n"
                            "G2 X25 Y5 Z-3 I0 J-5 P2\nG0 A90\nG1 X30 A45 F500\n"
                            "o100 call\no100 call\n(MSG, halfway)\nG4 P0.5\n"
                            "G81 X40 Y40 Z-5 R2 F200\nG80\nG53 G0 Z0\nG20\nG1 X2 Y2 F10\n"
                            "G21\nM9\nM5\nM30\n"
                            "o100 sub\nG91 G1 X1 Y1\nG90\no100 endsub\n%\n";

// Two passes of a 6 mm slot, for a machine whose +Z points into the work (Z negated).
const char* kZDownProgram = "G21 G90 G17\n(T1 D=6. CR=0. - ZMIN=-3. - FLAT END MILL)\nT1 M6\n"
                            "S8000 M3\nG0 Z-5\nG0 X-10 Y0\nG1 Z1.5 F100\nG1 X60 F600\nG0 Z-5\n"
                            "G0 X-10\nG1 Z3 F100\nG1 X60 F600\nG0 Z-5\nM5\nM30\n";

} // namespace

TEST_CASE("the commands of real posts come back from the tape bit for bit") {
  for (const char* name : {"programs/bracket-linuxcnc.ngc", "programs/pavanaskar-facing-x.ngc",
                           "programs/pavanaskar-pocket-spiral-out.ngc", "freecad/fanuc.nc",
                           "freecad/grbl.nc", "freecad/mach3_mach4.nc"}) {
    const std::string text = read_sample(name);
    CAPTURE(std::string(name));
    REQUIRE_FALSE(text.empty());
    const Toolpath path = interpret(make_source(name, text), {});
    REQUIRE(path.commands.size() > 25);
    CHECK(replay_differences(path.commands) == 0);
  }
}

TEST_CASE("every field of a command comes back from the tape") {
  const Toolpath path = interpret(make_source("mixed.ngc", kMixedProgram), {});
  REQUIRE(path.commands.size() > 30);
  CHECK(replay_differences(path.commands) == 0);

  SUBCASE("fields changed one at a time, and -0 against 0") {
    std::vector<CanonCommand> commands(path.commands.begin(), path.commands.begin() + 20);
    CanonCommand c = commands.back();
    auto vary = [&](auto change) {
      CanonCommand next = c;
      change(next);
      commands.push_back(next);
      commands.push_back(c); // and back
    };
    vary([](CanonCommand& x) { x.end.x = -0.0; });
    vary([](CanonCommand& x) { x.end.x = 0.0; });
    vary([](CanonCommand& x) { x.start.c = -0.0; });
    vary([](CanonCommand& x) { x.end.b = 1e-300; });
    vary([](CanonCommand& x) { x.line = 7; });
    vary([](CanonCommand& x) { x.call_line = x.line + 3; });
    vary([](CanonCommand& x) { x.start_known = !x.start_known; });
    vary([](CanonCommand& x) { x.machine_axes = 5; });
    vary([](CanonCommand& x) { x.centre_first = -0.0; });
    vary([](CanonCommand& x) { x.rotation = -3; });
    vary([](CanonCommand& x) { x.plane = Plane::XZ; });
    vary([](CanonCommand& x) { x.value = std::nan(""); });
    vary([](CanonCommand& x) { x.text = std::string(3 << 20, 'x'); }); // over a chunk
    vary([](CanonCommand& x) { x.text.clear(); });
    vary([](CanonCommand& x) { x.state.feed = -0.0; });
    vary([](CanonCommand& x) { x.state.spindle = SpindleDir::CounterClockwise; });
    vary([](CanonCommand& x) { x.state.tool = 99; });
    vary([](CanonCommand& x) { x.state.path_tolerance = 0.01; });
    vary([](CanonCommand& x) { x.state.plane = Plane::YZ; });
    vary([](CanonCommand& x) { x.state.inch = !x.state.inch; });
    vary([](CanonCommand& x) { x.kind = CanonKind::PlannerHint; });
    // 0 then -0 in every kind of field: equal as numbers, not as bits.
    CanonCommand zero = c;
    zero.end.y = zero.start.z = zero.value = zero.centre_second = zero.state.feed = 0.0;
    commands.push_back(zero);
    zero.end.y = zero.start.z = zero.value = zero.centre_second = zero.state.feed = -0.0;
    commands.push_back(zero);
    CHECK(replay_differences(commands) == 0);
  }
}

TEST_CASE("a tape over its bytes holds nothing, and says so") {
  const Toolpath path = interpret(make_source("mixed.ngc", kMixedProgram), {});
  CommandTape tape(200);
  for (const CanonCommand& c : path.commands)
    tape.record(c);
  CHECK_FALSE(tape.complete());
  CHECK(tape.bytes() == 0);
}

TEST_CASE("an estimate that replays the first pass gives the numbers of one that reads again") {
  const MachineProfile machine = generic();
  for (const char* name :
       {"programs/bracket-linuxcnc.ngc", "programs/pavanaskar-pocket-spiral-in.ngc",
        "freecad/fanuc.nc", "freecad/grbl.nc", "mixed", "z-down"}) {
    CAPTURE(std::string(name));
    // z-down: posted for a machine whose +Z points into the work; the estimate goes over its
    // commands a third time to size the stock as removal sees them (mirrored).
    const std::string text = std::string(name) == "mixed"    ? kMixedProgram
                             : std::string(name) == "z-down" ? kZDownProgram
                                                             : read_sample(name);
    const SourceFile source = make_source(name, text);
    EstimateOptions replayed, read_again;
    read_again.replay_first_pass = false;
    const Estimate a = estimate_program(source, machine, replayed);
    const Estimate b = estimate_program(source, machine, read_again);
    REQUIRE_FALSE(a.failed);
    CHECK(a.time_s > 0);
    if (std::string(name) == "z-down") {
      REQUIRE(a.removal);
      CHECK(a.removal->stock_description.find("Z mirrored") != std::string::npos);
      CHECK(a.energy.removed_mm3 > 100);
    }
    CHECK(estimate_json(a, machine) == estimate_json(b, machine));
  }
}
