// The planner's work stays linear in the program: counted (Planner::work()), not timed, so that
// a quadratic case fails the same on any machine. A run of zero-length moves behind a move that
// waits for the next one (a loop around "G1 X5" at X5) made every command scan the whole run,
// and held the whole run in memory.
#include <doctest/doctest.h>
#include <string>

#include "test_helpers.hpp"

using namespace ncjoule;

namespace {

std::vector<MachineProfile> machines() {
  MachineProfile trapezoid = test::round_machine();
  MachineProfile s_curve = test::round_machine();
  s_curve.kinematics.rapid_mode = RapidMode::DogLeg;
  s_curve.kinematics.feed_profile = FeedProfile::SCurve;
  for (AxisLimits& a : s_curve.kinematics.axes)
    a.jerk_mm_s3 = 10000;
  MachineProfile linuxcnc = test::round_machine();
  linuxcnc.kinematics.junction_rule = JunctionRule::LinuxCnc29;
  return {trapezoid, s_curve, linuxcnc};
}

// `head`, then `body` repeated `count` times in an o-word loop.
std::vector<CanonCommand> looped(const std::string& head, const std::string& body, int count) {
  const std::string text = "G21 G90\n" + head + "\no100 repeat [" + std::to_string(count) + "]\n" +
                           body + "\no100 endrepeat\nM2\n";
  InterpreterOptions options;
  options.max_loop_iterations = 0;
  Toolpath path = interpret(make_source("loop.ngc", text), options);
  REQUIRE(path.result.completed);
  return std::move(path.commands);
}

struct Run {
  Planner::Work work;
  std::size_t commands = 0;
  Timeline streamed;
};

Run run(const std::vector<CanonCommand>& commands, const MachineProfile& machine) {
  Run r;
  r.commands = commands.size();
  Planner planner(machine, {}, [&](const CanonCommand&, TimedCommand& timed) {
    r.streamed.commands.push_back(std::move(timed));
  });
  for (const CanonCommand& c : commands)
    planner.add(c);
  r.streamed.total_s = planner.finish();
  r.work = planner.work();
  return r;
}

struct Case {
  const char* name;
  const char* head;
  const char* body;
};

constexpr Case kCases[] = {
    {"G1 to the point it is at", "G1 X5 F600", "G1 X5"},
    {"G1 at the origin", "G1 X0 F600", "G1 X0"},
    {"G0 to the point it is at", "G0 X5", "G0 X5"},
    {"G1 in G64 P", "G64 P0.01\nG1 X5 F600", "G1 X5"},
    {"G0 in G64 P", "G64 P0.01\nG0 X5", "G0 X5"},
    {"in exact stop", "G61\nG1 X5 F600", "G1 X5"},
    {"moves shorter than the smallest", "G1 X5 F600", "G1 X5.0000000001\nG1 X5"},
    {"after an arc", "G1 X5 F600\nG2 X10 I2.5", "G1 X10"},
};

} // namespace

TEST_CASE("zero-length moves in a loop: the planner's work grows linearly with the moves") {
  for (const MachineProfile& machine : machines()) {
    CAPTURE(machine.kinematics.junction_rule);
    CAPTURE(machine.kinematics.feed_profile);
    for (const Case& c : kCases) {
      const std::string name = c.name;
      CAPTURE(name);
      const Run small = run(looped(c.head, c.body, 2'000), machine);
      const Run large = run(looped(c.head, c.body, 20'000), machine);
      const auto per_command = [](const Run& r) {
        return double(r.work.commands_examined + r.work.items_planned) / double(r.commands);
      };
      CAPTURE(small.work.commands_examined);
      CAPTURE(large.work.commands_examined);
      CAPTURE(large.work.items_planned);
      // A few looks per command, whatever the length of the run (the quadratic scan made it
      // thousands, growing ten times with the loop).
      CHECK(per_command(large) < 8);
      CHECK(per_command(large) < 1.2 * per_command(small) + 1);
      // The moves of the loop take no room in the look-ahead, and past
      // PlanOptions::max_commands_off_path of them none in memory either.
      CHECK(large.work.most_items <= 4);
      CHECK(large.work.most_waiting <= PlanOptions{}.max_commands_off_path + 2);
      // Timed as the whole program planned at once times them.
      PlanOptions whole;
      whole.look_ahead_whole_program = true;
      const Timeline at_once = plan(looped(c.head, c.body, 2'000), machine, whole);
      REQUIRE(small.streamed.commands.size() == at_once.commands.size());
      CHECK(small.streamed.total_s == at_once.total_s);
      std::size_t differing = 0;
      for (std::size_t i = 0; i < at_once.commands.size(); ++i) {
        const TimedCommand& a = small.streamed.commands[i];
        const TimedCommand& b = at_once.commands[i];
        if (a.start_s != b.start_s || a.duration_s != b.duration_s ||
            a.entry_speed_mm_s != b.entry_speed_mm_s || a.exit_speed_mm_s != b.exit_speed_mm_s)
          ++differing;
      }
      CHECK(differing == 0);
    }
  }
}

TEST_CASE("a long stretch with no point of known speed is planned in linear work") {
  // Collinear moves at a speed the path never has to leave: no item's entry speed is fixed by
  // its own limits until the end, so the window keeps growing; it is looked at again only once
  // it has doubled.
  for (const MachineProfile& machine : machines()) {
    CAPTURE(machine.kinematics.junction_rule);
    const Run small = run(looped("G64\nG1 X0 F600", "G91 G1 X0.5", 2'000), machine);
    const Run large = run(looped("G64\nG1 X0 F600", "G91 G1 X0.5", 20'000), machine);
    CAPTURE(large.work.items_planned);
    CHECK(double(large.work.items_planned) / double(large.commands) < 16);
    CHECK(double(large.work.commands_examined) / double(large.commands) < 8);
    CHECK(double(large.work.items_planned) / double(small.work.items_planned) < 14);
  }
}

TEST_CASE("a long run off the path brings the path to rest, the same streamed as planned whole") {
  // With the run cut at 50 commands: moves before and after runs of 10, 50 and 300 zero-length
  // moves and feed changes, timed bit for bit as the whole program planned at once times them.
  const std::string text = "G21 G90 G64 P0.01\nG1 X0 Y0 F3000\n"
                           "o1 repeat [3]\n"
                           "G1 X10\no2 repeat [10]\nG1 X10\no2 endrepeat\nG1 X20 Y1\n"
                           "o3 repeat [50]\nG1 X20 Y1\no3 endrepeat\nG2 X30 Y1 I5\n"
                           "o4 repeat [300]\nF[3000+#5]\nG0 X30 Y1\no4 endrepeat\nG1 X0 Y0\n"
                           "o1 endrepeat\nM2\n";
  InterpreterOptions io;
  const Toolpath path = interpret(make_source("runs.ngc", text), io);
  REQUIRE(path.result.completed);
  for (const MachineProfile& machine : machines()) {
    CAPTURE(machine.kinematics.junction_rule);
    PlanOptions whole;
    whole.look_ahead_whole_program = true;
    whole.max_commands_off_path = 50;
    PlanOptions streamed = whole;
    streamed.look_ahead_whole_program = false;
    streamed.look_ahead_batch = 3;
    const Timeline a = plan(path.commands, machine, whole);
    const Timeline b = plan(path.commands, machine, streamed);
    REQUIRE(a.commands.size() == b.commands.size());
    CHECK(a.total_s == b.total_s);
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.commands.size(); ++i)
      if (a.commands[i].start_s != b.commands[i].start_s ||
          a.commands[i].duration_s != b.commands[i].duration_s ||
          a.commands[i].entry_speed_mm_s != b.commands[i].entry_speed_mm_s ||
          a.commands[i].exit_speed_mm_s != b.commands[i].exit_speed_mm_s ||
          a.commands[i].samples.size() != b.commands[i].samples.size())
        ++differing;
    CHECK(differing == 0);
    // The cut brings the path to rest where it flowed on: uncut, the program takes less.
    const Timeline c = plan(path.commands, machine, PlanOptions{});
    CHECK(c.total_s < a.total_s);
  }
}
