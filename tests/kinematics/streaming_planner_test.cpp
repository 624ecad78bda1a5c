// The planner as a stream: commands timed as soon as the look-ahead allows come out exactly as
// when the whole program is planned at once, and a long program goes out as it comes in.
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "test_helpers.hpp"

namespace fs = std::filesystem;
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

// Every field of every timed command, bit for bit.
void check_same(const Timeline& streamed, const Timeline& whole) {
  REQUIRE(streamed.commands.size() == whole.commands.size());
  CHECK(streamed.total_s == whole.total_s);
  std::size_t differing = 0;
  for (std::size_t i = 0; i < whole.commands.size(); ++i) {
    const TimedCommand& a = streamed.commands[i];
    const TimedCommand& b = whole.commands[i];
    bool same = a.command == b.command && a.start_s == b.start_s && a.duration_s == b.duration_s &&
                a.entry_speed_mm_s == b.entry_speed_mm_s &&
                a.exit_speed_mm_s == b.exit_speed_mm_s && a.peak_speed_mm_s == b.peak_speed_mm_s &&
                a.samples.size() == b.samples.size();
    for (std::size_t j = 0; same && j < a.samples.size(); ++j)
      same = a.samples[j].t_s == b.samples[j].t_s &&
             a.samples[j].speed_mm_s == b.samples[j].speed_mm_s;
    if (!same && differing++ == 0) {
      CAPTURE(i);
      CAPTURE(a.duration_s);
      CAPTURE(b.duration_s);
      CHECK(same);
    }
  }
  CHECK(differing == 0);
}

} // namespace

TEST_CASE("streamed timing equals whole-program timing on LinuxCNC's nc_files, the samples and "
          "the planner's test programs") {
  std::vector<fs::path> programs;
  for (const fs::path folder :
       {fs::path("/usr/share/linuxcnc/ncfiles"), fs::path(NCJOULE_SOURCE_DIR) / "samples",
        fs::path(NCJOULE_SOURCE_DIR) / "tests" / "kinematics" / "linuxcnc"})
    if (fs::is_directory(folder))
      for (const auto& entry : fs::recursive_directory_iterator(folder))
        if (entry.path().extension() == ".ngc" || entry.path().extension() == ".nc")
          programs.push_back(entry.path());
  REQUIRE(programs.size() > 10);
  PlanOptions whole_options;
  whole_options.look_ahead_whole_program = true;
  whole_options.max_sample_step_mm = 0.5;
  PlanOptions stream_options = whole_options;
  stream_options.look_ahead_whole_program = false;
  // Looking ahead every third move: commands go out sooner, timed the same.
  PlanOptions eager_options = stream_options;
  eager_options.look_ahead_batch = 3;
  for (const fs::path& path : programs) {
    CAPTURE(path.string());
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    InterpreterOptions options;
    options.max_commands = 2'000'000;
    const Toolpath toolpath = interpret(make_source(path.string(), text.str()), options);
    for (const MachineProfile& machine : machines()) {
      CAPTURE(machine.kinematics.junction_rule);
      CAPTURE(machine.kinematics.feed_profile);
      const Timeline whole = plan(toolpath.commands, machine, whole_options);
      check_same(plan(toolpath.commands, machine, stream_options), whole);
      check_same(plan(toolpath.commands, machine, eager_options), whole);
    }
  }
}

TEST_CASE("a long program goes out while it comes in") {
  // 20,000 short moves in G64 with a stop (a corner of 90 degrees) every 10.
  std::ostringstream program;
  program << "G21 G90 G64\nF3000\n";
  for (int i = 0; i < 20000; ++i) {
    const int leg = i / 10;
    program << "G1 X" << (leg % 2 ? 10 - (i % 10) : i % 10) << " Y" << leg * 0.5 << "\n";
  }
  program << "M2\n";
  const Toolpath toolpath = interpret(make_source("long.ngc", program.str()));
  for (const MachineProfile& machine : machines()) {
    std::size_t out_before_end = 0, added = 0, most_waiting = 0;
    Planner planner(machine, {}, [&](const CanonCommand&, TimedCommand& timed) {
      CHECK(timed.command == out_before_end); // in order, each once
      ++out_before_end;
    });
    for (const CanonCommand& c : toolpath.commands) {
      planner.add(c);
      ++added;
      most_waiting = std::max(most_waiting, added - out_before_end);
    }
    planner.finish();
    CHECK(out_before_end == toolpath.commands.size());
    CAPTURE(most_waiting);
    CHECK(most_waiting < 400); // a window, not the program
  }
}

TEST_CASE("samples vectors handed back are filled again, and every sample is the same") {
  // A stream hands each move's samples back once it is done with them (Planner::reuse_samples),
  // dirty; later moves' samples must go into their memory and come out as a fresh planner's.
  std::ostringstream program;
  program << "G21 G90 G64\nF2000\n";
  for (int i = 0; i < 3000; ++i) {
    if (i % 50 == 0) program << "G3 X" << (i % 7) << " Y" << i * 0.01 << " R4\n";
    program << "G1 X" << (i % 7) * 1.5 << " Y" << i * 0.01 << " Z" << -(i % 3) * 0.2 << "\n";
  }
  program << "M2\n";
  const Toolpath toolpath = interpret(make_source("reuse.ngc", program.str()));
  PlanOptions options;
  options.max_sample_step_mm = 0.3;
  for (const MachineProfile& machine : machines()) {
    CAPTURE(machine.kinematics.junction_rule);
    const Timeline fresh = plan(toolpath.commands, machine, options);
    std::vector<TimedCommand> timed;
    std::vector<std::vector<MotionSample>> spent;
    std::set<const MotionSample*> handed_back;
    std::size_t reused = 0, sampled = 0;
    Planner planner(machine, options, [&](const CanonCommand&, TimedCommand& t) {
      sampled += !t.samples.empty();
      reused += handed_back.count(t.samples.data());
      timed.push_back(t); // a copy: this one's samples go back
      for (MotionSample& s : t.samples)
        s.t_s = s.speed_mm_s = -1; // what a reused vector held must not matter
      spent.push_back(std::move(t.samples));
    });
    for (const CanonCommand& c : toolpath.commands) {
      for (std::vector<MotionSample>& samples : spent) {
        handed_back.insert(samples.data());
        planner.reuse_samples(std::move(samples));
      }
      spent.clear();
      planner.add(c);
    }
    const double total_s = planner.finish();
    CHECK(total_s == fresh.total_s);
    REQUIRE(timed.size() == fresh.commands.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < timed.size(); ++i) {
      const std::vector<MotionSample>& a = timed[i].samples;
      const std::vector<MotionSample>& b = fresh.commands[i].samples;
      bool same = a.size() == b.size() && timed[i].duration_s == fresh.commands[i].duration_s;
      for (std::size_t j = 0; same && j < a.size(); ++j)
        same = a[j].t_s == b[j].t_s && a[j].u == b[j].u && a[j].speed_mm_s == b[j].speed_mm_s &&
               a[j].position.x == b[j].position.x && a[j].position.y == b[j].position.y &&
               a[j].position.z == b[j].position.z;
      differing += !same;
    }
    CHECK(differing == 0);
    CAPTURE(sampled);
    CHECK(reused * 10 > sampled * 9); // nearly every move's samples went into given memory
  }
}
