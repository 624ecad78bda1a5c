// ncjoule stage 2: kinematics. Turns the canonical command stream into time, block by block, on
// a described machine (see machine.hpp).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ncjoule/gcode.hpp"
#include "ncjoule/machine.hpp"

namespace ncjoule {

// One point of the sampled path of a move.
struct MotionSample {
  double t_s = 0;        // time since program start
  double u = 0;          // parameter along the move, 0 at its start, 1 at its end
  Pose position;         // mm, program coordinates
  double speed_mm_s = 0; // path speed at this instant
};

// The timing of one canonical command.
struct TimedCommand {
  std::size_t command = 0; // index into Toolpath::commands
  int line = 0;            // 0-based source line (copied from the command)
  CanonKind kind = CanonKind::Comment;
  double start_s = 0;
  double duration_s = 0;
  double length_mm = 0;
  double entry_speed_mm_s = 0;
  double exit_speed_mm_s = 0;
  double peak_speed_mm_s = 0;
  std::vector<MotionSample> samples; // moves only; first at u=0, last at u=1
  std::string note;                  // e.g. "M0 program stop: counted as zero time"
};

struct PlanOptions {
  // Upper bound on the distance between two samples of a move (mm). Removal asks for a
  // fraction of the tool radius and of its grid spacing; 0 means "only the end points".
  double max_sample_step_mm = 0;
  // Upper bound on the time between two samples (s); 0 = none.
  double max_sample_dt_s = 0;
  // Samples of one move at most, whatever the steps ask: guards against a step so small, or a
  // move so long (X1e100), that one move would fill memory. 100,000 samples (6 MB) cover a 5 m
  // move at a 0.05 mm grid; beyond that they thin out.
  std::size_t max_samples_per_move = 100'000;
  // Time nothing before the end of the program (the look-ahead sees it all at once). The result
  // is the same; tests compare the two.
  bool look_ahead_whole_program = false;
  // Moves waiting for their speeds before the planner looks ahead again (at least 1). Smaller
  // sends commands out sooner for more planning work; the result is the same. The fuzz target
  // sets it small so that a short program reaches the window's every path.
  std::size_t look_ahead_batch = 64;
  // Commands in a row that are no part of the path (zero-length moves, feed changes) after which
  // the path comes to rest, as a control whose read-ahead runs dry stops. Until then they wait,
  // in memory, for the move after them, which decides the speed of the move before them; a loop
  // of zero-length moves held them all (400 bytes each). Real programs never come near.
  std::size_t max_commands_off_path = 10'000;
};

// The planner as a stream, for programs of any length: commands go in one at a time and come
// out timed, in order, as soon as nothing later can change their timing (the look-ahead has
// reached a point whose speed no later move can change: a stop, a sharp corner, a speed limit).
// Memory holds only the commands and moves between that point and the newest command.
class Planner {
public:
  // Called once per command, in order, with its timing (which the sink may move from).
  using Sink = std::function<void(const CanonCommand& command, TimedCommand& timed)>;
  Planner(const MachineProfile& machine, const PlanOptions& options, Sink sink);
  ~Planner();
  Planner(const Planner&) = delete;
  Planner& operator=(const Planner&) = delete;

  void add(const CanonCommand& command);
  // The end of the program: times what is still waiting; returns the program's total time.
  double finish();
  // Warnings about moves and codes so far (each kind once, with a count).
  std::vector<Diagnostic> take_diagnostics();
  // A samples vector of a command the caller is done with, for a later move's samples to use
  // its memory: a stream that hands them back allocates nothing per move once it runs (at most
  // kMaxSpareSamples are kept). Its contents do not matter.
  void reuse_samples(std::vector<MotionSample>&& spent);
  static constexpr std::size_t kMaxSpareSamples = 4096;

  // The work done so far, counted, for tests that it stays linear in the program whatever the
  // program (a run of zero-length moves, a long stretch with no point of known speed).
  struct Work {
    std::size_t items_planned = 0;     // look-ahead items visited by the passes over the window
    std::size_t commands_examined = 0; // waiting commands looked at to time or release them
    std::size_t most_items = 0;        // look-ahead items held at once
    std::size_t most_waiting = 0;      // commands held at once
  };
  Work work() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct Timeline {
  std::vector<TimedCommand> commands; // one per canonical command, same order
  double total_s = 0;
  std::vector<Diagnostic> diagnostics;
};

// The whole program at once (through a Planner).
Timeline plan(const std::vector<CanonCommand>& commands, const MachineProfile& machine,
              const PlanOptions& options = {});

} // namespace ncjoule
