// The pipeline: a first pass over the program for what must be known before anything is timed
// (the tools it uses, the extent of its cuts), then the stream: replay the first pass's commands
// (command_tape.hpp), plan, remove material, integrate power, fold into per-line results.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#ifdef _WIN32
#define WIN32_LEAN_AND_MEAN
#ifndef NOMINMAX
#define NOMINMAX
#endif
#include <windows.h> // GlobalMemoryStatusEx
#else
#include <sys/resource.h>
#include <unistd.h>
#endif

#include "cam_stock.hpp"
#include "command_tape.hpp"
#include "long_arc_check.hpp"
#include "machine_moves.hpp"
#include "ncjoule/log.hpp"
#include "ncjoule/text_file.hpp"
#include "result_fold.hpp"
#include "setups.hpp"
#include "stage_queue.hpp"
#include "work_budget.hpp"

namespace ncjoule {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// At most this many diagnostics are kept; the rest are counted (Estimate::diagnostics_dropped).
// Past the cap an error is still kept while none is, so that a failed run says why.
constexpr std::size_t kMaxDiagnostics = 500;

bool holds_error(const std::vector<Diagnostic>& diagnostics) {
  return std::any_of(diagnostics.begin(), diagnostics.end(),
                     [](const Diagnostic& d) { return d.severity == Severity::Error; });
}

void add_diagnostics(Estimate& e, std::vector<Diagnostic> more, const std::string& file) {
  for (Diagnostic& d : more) {
    if (e.diagnostics.size() >= kMaxDiagnostics &&
        (d.severity != Severity::Error || holds_error(e.diagnostics))) {
      ++e.diagnostics_dropped;
      continue;
    }
    if (d.file.empty()) d.file = file;
    e.diagnostics.push_back(std::move(d));
  }
}

// The first pass's commands are held for the second within this many bytes a line of the
// program (and this many bytes in all at least): a move takes about 20 bytes, an arc 45.
constexpr std::size_t kTapeBytesPerLine = 64;
constexpr std::size_t kTapeBytesLeast = std::size_t(4) << 20;

// What the first pass learns.
struct ProgramScan {
  explicit ProgramScan(const SourceFile& source) : setups(source, *find_dialect("linuxcnc")) {}
  ToolUsage tools;
  estimate_detail::SetupScan setups;
  std::vector<StockExtent> extents{1}; // of each setup's cutting moves
  std::size_t commands = 0;
  ToolCommentContext tool_comments; // units and tool changes the comments are read against
  ZDirectionScan z_direction;
  estimate_detail::LongArcCheck long_arcs;
  void add(const CanonCommand& c) {
    setups.add(c, commands);
    ++commands;
    tools.add(c);
    if (extents.size() <= setups.current()) extents.resize(setups.current() + 1);
    extents[setups.current()].add(c);
    tool_comments.add(c);
    z_direction.add(c);
    long_arcs.add(c);
  }
  std::vector<std::size_t> setup_firsts() const {
    std::vector<std::size_t> firsts;
    for (const auto& start : setups.starts())
      firsts.push_back(start.command);
    return firsts;
  }
};

// The stock of setup `k`: the first setup's is the one given (--stock, the job file's), later
// ones the job file's [[setup]] entries; a setup given none is the box of its own cuts.
// The first setup without a stock given takes the one the program's CAM comments state.
StockSpec setup_stock(const EstimateOptions& options, std::size_t k, bool inch,
                      const std::optional<StockSpec>& from_comments) {
  const std::optional<StockSpec>& given =
      k == 0 ? (options.stock ? options.stock : from_comments)
             : (k - 1 < options.setup_stocks.size() ? options.setup_stocks[k - 1] : std::nullopt);
  return given ? given->in_mm(inch) : StockSpec{};
}

// Whether removal reads the program's Z mirrored: as the profile says, else as the program's
// rapids show (with a warning that says what was seen and how to settle it).
bool reads_z_mirrored(const MachineProfile& machine, const ZDirectionScan& scan, Estimate& e) {
  switch (machine.kinematics.z_positive) {
  case ZDirection::Up:
    return false;
  case ZDirection::Down:
    return true;
  case ZDirection::Auto:
    break;
  }
  if (!scan.points_down()) return false;
  char seen[160];
  std::snprintf(seen, sizeof seen, "rapids at Z%.3f and below, cuts at Z%.3f and above",
                scan.highest_rapid_z(), scan.lowest_cut_z());
  e.diagnostics.push_back(
      {Severity::Warning, e.file, 0, 0,
       std::string("every rapid across XY runs below the cuts (") + seen +
           "): it was posted for a machine whose +Z points into the work (a post that scales Z "
           "by -1). Removal reads its Z mirrored; times do not change. Say which way Z points "
           "with z_positive = \"down\" or \"up\" under [kinematics] in the machine profile"});
  return true;
}

// The tools as described by the tool table, then the program's header comments, then the job
// file and the command line, each replacing the one before for the same number.
std::map<int, Tool> described_tools(const SourceFile& source, const ToolCommentContext& context,
                                    const EstimateOptions& options,
                                    std::vector<Diagnostic>& diagnostics) {
  std::map<int, Tool> described =
      tools_from_table(options.tool_table, diagnostics, options.tool_table_path);
  for (auto& [number, tool] : parse_tool_comments(source, context, diagnostics))
    described[number] = tool;
  for (const auto& [number, tool] : options.tools)
    described[number] = tool;
  return described;
}

// The power constants for this program: the profile's, with the cutting term of the workpiece
// material where the profile takes it from the material.
PowerConstants effective_power(const MachineProfile& machine, const EstimateOptions& options,
                               Estimate& e) {
  const PowerConstants& power = machine.power;
  const std::string& name = options.material.empty() ? power.material : options.material;
  if (name.empty()) return power;
  std::optional<Material> material = find_material(name);
  if (!material && power.profile_material && power.profile_material->name == name)
    material = power.profile_material;
  if (!material) {
    e.diagnostics.push_back({Severity::Error, e.file, 0, 0,
                             "material '" + name + "' is not one ncjoule knows (docs/models.md)"});
    return power;
  }
  bool used = false;
  PowerConstants out = with_material(power, *material, &used);
  if (!used && !options.material.empty())
    e.diagnostics.push_back(
        {Severity::Warning, e.file, 0, 0,
         "material '" + material->name + "' is not used: " + machine.name +
             " takes its cutting power from constants fitted on that machine (" +
             std::string(model_name(power.model)) + " model)"});
  if (used && material->estimate)
    e.diagnostics.push_back({Severity::Note, e.file, 0, 0,
                             "material '" + material->name +
                                 "': its cutting energy is an estimate, not a handbook value"});
  return out;
}

// Refuses what is not a G-code program before it is interpreted: bytes in an encoding ncjoule
// does not read (a UTF-16 file would be read as NULs between letters), and a program larger
// than the memory budget allows. True when the program can be run.
bool check_program(const SourceFile& source, std::size_t budget, Estimate& e) {
  if (const std::string what = non_text_encoding(source.text); !what.empty()) {
    const bool binary = what == "binary data";
    e.diagnostics.push_back(
        {Severity::Error, source.path, 0, 0,
         "is " + what + ", not a G-code program" +
             (binary ? std::string()
                     : ": ncjoule reads ASCII or UTF-8, as controllers do; save it so (most "
                       "editors' 'Save as' offers the encoding)")});
    return false;
  }
  if (std::string problem = program_memory_problem(source.text.size(), source.lines.size(), budget);
      !problem.empty()) {
    e.diagnostics.push_back({Severity::Error, source.path, 0, 0, std::move(problem)});
    return false;
  }
  return true;
}

// A text with lines of code but not one word a controller reads (a passwd file, prose) holds no
// G-code: refused rather than annotated as a program that takes no time.
// The interpreter's warnings about each of its words say nothing more: only the first is kept.
//
// A file with no line of code at all, only comments, '%' lines or blank lines (a setup sheet saved
// as .ngc, an empty post), is no program either: there is nothing to estimate, and a controller
// runs nothing from it (LinuxCNC refuses it: "File ended with no percent sign or program end").
// It is refused the same way, exit 2, rather than annotated with a header of zeros.
void check_holds_gcode(const InterpretResult& run, Estimate& e) {
  if (run.word_blocks > 0) return;
  if (run.blocks == 0) {
    e.diagnostics.clear(); // "no M2" and the like say nothing more
    e.diagnostics_dropped = 0;
    e.diagnostics.push_back({Severity::Error, e.file, 0, 0,
                             "holds no block to run: only comments, '%' lines or blank lines (a "
                             "setup sheet, or an empty post?), so there is nothing to estimate"});
    e.failed = true;
    return;
  }
  const auto first = std::find_if(e.diagnostics.begin(), e.diagnostics.end(),
                                  [](const Diagnostic& d) { return d.line > 0; });
  std::vector<Diagnostic> kept;
  if (first != e.diagnostics.end()) kept.push_back(*first);
  kept.push_back({Severity::Error, e.file, 0, 0,
                  "holds no G-code: not one of its " + std::to_string(run.blocks) +
                      " lines of text has a word a controller reads (G1, X10, M3, ...)"});
  e.diagnostics = std::move(kept);
  e.diagnostics_dropped = 0;
  e.failed = true;
}

} // namespace

std::size_t estimated_program_memory(std::size_t bytes, std::size_t lines) {
  // Measured: 145 bytes a line for the estimate of a file of empty lines, 225 for annotating
  // real programs (bench/scale.sh); the annotated copy is about four times the text. The first
  // pass's command tape comes on top, freed as the second pass replays it: about 20 bytes a
  // move, at most kTapeBytesPerLine a line (the 1M-block scale program: 12 MiB).
  constexpr double kPerLine = 240, kPerByte = 5;
  return std::size_t(std::min(kPerLine * double(lines) + kPerByte * double(bytes), 1e18));
}

std::string program_memory_problem(std::size_t bytes, std::size_t lines, std::size_t budget) {
  const std::size_t needed = estimated_program_memory(bytes, lines);
  if (needed <= budget) return {};
  return "its " + std::to_string(lines) + " lines need about " + std::to_string(needed >> 20) +
         " MiB, over the memory budget of " + std::to_string(budget >> 20) +
         " MiB (--memory-limit sets it)";
}

std::size_t default_memory_budget_bytes() {
  std::size_t budget = kDefaultRemovalMemoryBudget;
#ifdef _WIN32
  // A quarter of the physical memory (Windows has no ulimit -v to halve).
  MEMORYSTATUSEX status{};
  status.dwLength = sizeof status;
  if (GlobalMemoryStatusEx(&status)) budget = std::size_t(status.ullTotalPhys / 4);
#else
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page > 0) budget = std::size_t(pages) * std::size_t(page) / 4;
  for (const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    struct rlimit limit {};
    if (getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
      budget = std::min(budget, std::size_t(limit.rlim_cur / 2));
  }
#endif
  return budget;
}

// The estimate, G41/G42 offsetting by `comp_radii` (mm, by tool number; see below).
static Estimate estimate_with(const SourceFile& source, const MachineProfile& machine,
                              const EstimateOptions& options,
                              const std::map<int, double>& comp_radii, bool radii_final);

// Cutter radius compensation needs the radius of each tool a D word names: the job file's and
// --tool's are known now; those the program's comments describe are known after the first pass,
// which then runs again with them (only when a G41/G42 named such a tool).
Estimate estimate_program(const SourceFile& source, const MachineProfile& machine,
                          const EstimateOptions& options) {
  std::map<int, double> radii;
  for (const auto& [number, tool] : options.tools)
    if (tool.diameter_mm > 0) radii[number] = tool.radius();
  return estimate_with(source, machine, options, radii, false);
}

static Estimate estimate_with(const SourceFile& source, const MachineProfile& machine,
                              const EstimateOptions& options,
                              const std::map<int, double>& comp_radii, bool radii_final) {
  Estimate e;
  e.file = source.path;
  e.machine_guessed = machine.by_default;
  if (options.progress) options.progress(0);
  InterpreterOptions interpreter;
  static_cast<InterpreterLimits&>(interpreter) = options.limits;
  interpreter.dialect = options.dialect;
  if (!interpreter.dialect && !options.detect_dialect)
    interpreter.dialect = find_dialect(machine.dialect); // "auto" finds none: detected
  interpreter.fallback_dialect = find_dialect(machine.fallback_dialect);
  interpreter.same_choice_as_before = options.dialect_choice;
  interpreter.tools = options.tool_table;
  // Where the work sits: the profile's setup, with the job file's work offsets in place of its.
  WorkSetup setup = machine.setup;
  for (const auto& [index, origin] : options.work_offsets)
    setup.work_offsets[index] = origin;
  interpreter.work_offsets = setup.work_offsets;
  interpreter.start_inch = setup.power_on_inch.value_or(false);
  interpreter.cutter_compensation = options.cutter_compensation;
  interpreter.default_cutter_compensation = setup.cutter_compensation;
  interpreter.peck_clearance_mm = setup.peck_clearance_mm;
  interpreter.chip_break_retract_mm = setup.chip_break_retract_mm;
  interpreter.comp_radius_mm = comp_radii;
  std::vector<Diagnostic> macro_problems; // control programs that could not be read
  std::vector<std::string> macro_dirs = options.macro_dirs;
  macro_dirs.insert(macro_dirs.end(), setup.macro_dirs.begin(), setup.macro_dirs.end());
  if (!macro_dirs.empty())
    interpreter.control_programs = control_programs_in(std::move(macro_dirs), macro_problems);
  const bool offsets_given = !setup.work_offsets.empty();

  const std::size_t budget = options.removal.memory_budget_bytes
                                 ? options.removal.memory_budget_bytes
                                 : default_memory_budget_bytes();
  if (!check_program(source, budget, e)) {
    e.failed = true;
    return e;
  }
  e.power = effective_power(machine, options, e);

  // 1. The first pass. Stage times go to the log (-v): the benchmarks read them.
  auto t = Clock::now();
  ProgramScan scan(source);
  // Without work offsets, Z home is placed above the highest point seen so far; the second pass
  // places it above the highest point of the whole program.
  estimate_detail::MachineMoves first_view(setup, offsets_given, std::nullopt, source.path);
  // The commands as the interpreter gives them, for the second pass to replay.
  estimate_detail::CommandTape tape(
      options.replay_first_pass ? kTapeBytesPerLine * source.lines.size() + kTapeBytesLeast : 0);
  // The interpreter on a thread of its own, the scan here (stage_queue.hpp).
  InterpretResult run;
  estimate_detail::run_overlapped<CanonCommand>(
      options.overlap_stages,
      [&](estimate_detail::StageQueue<CanonCommand>& commands) {
        run = interpret(source, interpreter,
                        [&](const CanonCommand& c) { commands.push(CanonCommand(c)); });
      },
      [&](const CanonCommand& c) {
        tape.record(c);
        scan.add(first_view.view(c));
      });
  const double home_z = first_view.home_z();
  e.dialect = run.dialect;
  e.dialect_origin = run.dialect_origin;
  e.dialect_reason = run.dialect_reason;
  const DialectChoice first_choice{e.dialect, e.dialect_origin, e.dialect_reason};
  e.blocks = run.blocks;
  e.commands = run.commands;
  e.program_end = run.program_end;
  add_diagnostics(e, std::move(run.diagnostics), source.path);
  add_diagnostics(e, std::move(macro_problems), source.path);
  add_diagnostics(e, first_view.take_diagnostics(), source.path);
  if (!run.units_given && run.word_blocks > 0)
    add_diagnostics(e,
                    {{Severity::Warning, source.path, 0, 0,
                      std::string("the program sets neither G20 nor G21: it runs in the units "
                                  "the control is set to at power-on, taken to be ") +
                          (interpreter.start_inch ? "inches" : "mm") +
                          (setup.power_on_inch ? " (power_on_units in the profile's [setup])"
                                               : " (say which with power_on_units = \"inch\" or "
                                                 "\"mm\" under [setup] in the profile)")}},
                    source.path);
  // Stopped by the budget of moves (its error is among the diagnostics): not a program error.
  if (interpreter.max_commands && run.commands > interpreter.max_commands) {
    e.failed = e.budget_exceeded = true;
    return e;
  }
  check_holds_gcode(run, e);
  if (e.failed) return e;
  if (auto long_arcs = scan.long_arcs.verdict(source.path))
    add_diagnostics(e, {std::move(*long_arcs)}, source.path);
  logger().info("scan: {} blocks, {} commands in {:.3f} s", run.blocks, scan.commands,
                seconds_since(t));
  if (options.progress) options.progress(0.1);
  const estimate_detail::SetupIndex setup_index(scan.setup_firsts());

  // The first pass's commands again, to `sink` in order: replayed from the tape where it holds
  // them all (`last`: the tape is freed as it goes), else interpreted again as the first pass
  // read them, the interpreter on a thread of its own.
  InterpreterOptions again = interpreter;
  again.same_choice_as_before = first_choice;
  again.keep_diagnostics = false; // the first pass gave them
  auto commands_again = [&](bool last, const std::function<void(const CanonCommand&)>& sink) {
    if (tape.complete()) return tape.replay(sink, last);
    estimate_detail::run_overlapped<CanonCommand>(
        options.overlap_stages,
        [&](estimate_detail::StageQueue<CanonCommand>& commands) {
          interpret(source, again, [&](const CanonCommand& c) { commands.push(CanonCommand(c)); });
        },
        sink);
  };

  // 2. Tools and stock.
  std::vector<Diagnostic> found;
  scan.tool_comments.dialect = e.dialect;
  e.inch = scan.tool_comments.inch;
  std::map<int, Tool> described = described_tools(source, scan.tool_comments, options, found);
  if (!radii_final) {
    bool more = false;
    for (int number : run.comp_radius_unknown)
      if (auto it = described.find(number); it != described.end() && it->second.diameter_mm > 0)
        more = true;
    if (more) {
      std::map<int, double> radii = comp_radii;
      for (const auto& [number, tool] : described)
        if (tool.diameter_mm > 0) radii.emplace(number, tool.radius());
      return estimate_with(source, machine, options, radii, true);
    }
  }
  for (int number : run.comp_radius_unknown)
    found.push_back({Severity::Warning, source.path, 0, 0,
                     "G41/G42 offset by the radius of tool " + std::to_string(number) +
                         ", which nothing describes (tool table, CAM comments, job file, "
                         "--tool): its moves are timed as programmed, on the part's contour "
                         "rather than the tool centre"});
  add_diagnostics(e, std::move(found), source.path);
  std::vector<std::unique_ptr<RemovalSimulator>> removals; // one per setup
  if (options.simulate_removal) {
    ToolAssignment assignment = assign_tools(
        scan.tools, described, options.default_tool ? options.default_tool : machine.default_tool,
        source.path);
    e.tools = std::move(assignment.tools);
    e.unsimulated_tools = std::move(assignment.unsimulated);
    e.tools_guessed = assignment.fallback || !e.unsimulated_tools.empty();
    add_diagnostics(e, std::move(assignment.diagnostics), source.path);
    std::map<int, Tool> used;
    for (const auto& [number, _] : scan.tools.first_move)
      if (auto it = e.tools.find(number); it != e.tools.end()) used.insert(*it);
    RemovalOptions removal_options = options.removal;
    removal_options.source_path = source.path;
    // The stock model gets what the program's own memory leaves of the budget.
    removal_options.memory_budget_bytes =
        std::max(budget - estimated_program_memory(source.text.size(), source.lines.size()),
                 std::size_t(16) << 20);
    removal_options.mirror_z = reads_z_mirrored(machine, scan.z_direction, e);
    removal_options.program_inch = e.inch;
    t = Clock::now();
    // The default stocks are sized from the moves as removal sees them.
    std::vector<StockExtent> mirrored(scan.extents.size());
    if (removal_options.mirror_z) {
      estimate_detail::MachineMoves view(setup, offsets_given, home_z, source.path);
      std::size_t index = 0;
      commands_again(false, [&](const CanonCommand& c) {
        mirrored[setup_index.of(index++)].add(mirrored_z(view.view(c)));
      });
    }
    // Each setup's stock model shares the budget.
    removal_options.memory_budget_bytes =
        std::max(removal_options.memory_budget_bytes / scan.extents.size(), std::size_t(16) << 20);
    try {
      std::vector<Diagnostic> header_problems; // a header stock that cannot be used
      const std::optional<StockSpec> from_comments =
          options.stock
              ? std::nullopt
              : estimate_detail::stock_from_cam_comments(source, e.dialect, 1000, &header_problems);
      add_diagnostics(e, std::move(header_problems), source.path);
      for (std::size_t k = 0; k < scan.extents.size(); ++k) {
        // A later setup cuts what the first left: its guessed stock is no larger.
        if (k > 0 && removals.front()->ready())
          removal_options.first_setup_stock = removals.front()->summary().stock_box;
        removals.push_back(std::make_unique<RemovalSimulator>(
            setup_stock(options, k, e.inch, from_comments),
            removal_options.mirror_z ? mirrored[k] : scan.extents[k], used, removal_options));
        e.positioning_moves += scan.extents[k].positioning_moves();
      }
    } catch (const std::exception& ex) {
      e.diagnostics.push_back({Severity::Error, source.path, 0, 0,
                               std::string("material removal failed: ") + ex.what()});
      e.failed = e.removal_failed = true;
      return e;
    }
    logger().info("stock: {} setup(s) in {:.3f} s", removals.size(), seconds_since(t));
  } else {
    e.tools = std::move(described);
  }

  // 3. The stream.
  PlanOptions plan_options;
  for (const auto& removal : removals)
    if (removal->ready())
      plan_options.max_sample_step_mm =
          plan_options.max_sample_step_mm > 0
              ? std::min(plan_options.max_sample_step_mm, removal->sample_step_mm())
              : removal->sample_step_mm();
  plan_options.max_samples_per_move = options.max_samples_per_move;
  plan_options.look_ahead_batch = options.look_ahead_batch;
  EstimateOptions folding = options;
  for (const auto& [number, tool] : e.tools) {
    folding.energy.flutes[number] = tool.flutes > 0 ? tool.flutes : typical_flutes(tool);
    folding.energy.tool_diameters_mm[number] = tool.diameter_mm;
  }
  std::vector<RemovalSimulator*> setup_removals;
  for (const auto& removal : removals)
    setup_removals.push_back(removal.get());
  estimate_detail::ResultFolder folder(source, e.dialect, e.power, folding, setup_removals,
                                       setup_index, scan.setups.starts(), scan.commands, e);
  t = Clock::now();
  // Replay the first pass's commands (or interpret again where the tape could not hold them),
  // plan, remove and fold as one stream: each command goes through as soon as the planner has
  // timed it, so memory holds the look-ahead window, not the program's results. They run at
  // once, handing commands on in order (stage_queue.hpp): the replay and the planner on a thread
  // of its own (an interpreter on another where it reads the text again), removal on another, a
  // batch at a time, and the folding (energy, the results) here.
  std::size_t streamed = 0;
  estimate_detail::WorkBudget work_budget(options.max_path_samples,
                                          options.simulate_removal ? options.max_removal_work : 0,
                                          setup_removals, e.tools, source.path);
  struct Timed {
    CanonCommand command;
    TimedCommand timed;
  };
  try {
    double total_s = 0;
    std::vector<Diagnostic> planner_diagnostics;
    // Three stages after the replay: the planner, removal (a batch at a time), the folding. The
    // folding hands the memory of what it is done with back to the first two (spare_bin.hpp).
    using estimate_detail::RemovedBatch;
    estimate_detail::SpareBin<RemovedBatch> spare_batches(4);
    estimate_detail::SpareBin<std::vector<MotionSample>> spare_samples(Planner::kMaxSpareSamples);
    estimate_detail::BatchRemoval removal(setup_removals, setup_index, &spare_batches);
    std::vector<std::vector<MotionSample>> spent_samples; // the folding's, given back
    estimate_detail::run_overlapped<RemovedBatch>(
        options.overlap_stages,
        [&](estimate_detail::StageQueue<RemovedBatch>& removed) {
          estimate_detail::run_overlapped<Timed>(
              options.overlap_stages,
              [&](estimate_detail::StageQueue<Timed>& timed) {
                Planner planner(machine, plan_options, [&](const CanonCommand& c, TimedCommand& t) {
                  timed.push({c, std::move(t)});
                });
                estimate_detail::MachineMoves view(setup, offsets_given, home_z, source.path);
                std::vector<std::vector<MotionSample>> reused;
                std::size_t added = 0;
                commands_again(true, [&](const CanonCommand& c) {
                  if (++added % 256 == 0) { // the samples the folding gave back, a bin at a time
                    spare_samples.take_all(reused);
                    for (std::vector<MotionSample>& samples : reused)
                      planner.reuse_samples(std::move(samples));
                    reused.clear();
                  }
                  planner.add(view.view(c));
                });
                total_s = planner.finish();
                planner_diagnostics = planner.take_diagnostics();
              },
              [&](Timed& t) {
                work_budget.count(t.command, t.timed); // before removal cuts it
                if (options.keep_commands) options.keep_commands->push_back(t.command);
                if (auto batch = removal.take(t.command, std::move(t.timed)))
                  removed.push(std::move(*batch));
                ++streamed;
              });
          if (auto batch = removal.finish()) removed.push(std::move(*batch));
        },
        [&](RemovedBatch& batch) {
          folder.take(batch);
          // A long move's samples are left to be freed, the rest go back to the planner: at most
          // 64 samples (4.6 kB) each, a few MiB in all whatever the program.
          constexpr std::size_t kKeptSamples = 64;
          for (TimedCommand& timed : batch.timed)
            if (timed.samples.capacity() > 0 && timed.samples.capacity() <= kKeptSamples)
              spent_samples.push_back(std::move(timed.samples));
          spare_samples.give_all(spent_samples);
          spare_batches.give(std::move(batch));
        },
        1, 4);
    add_diagnostics(e, std::move(planner_diagnostics), source.path);
    folder.finish(total_s);
  } catch (const BudgetExceeded& stopped) {
    add_diagnostics(e, {stopped.diagnostic}, source.path);
    e.failed = e.budget_exceeded = true;
    return e;
  } catch (const std::exception& ex) {
    e.diagnostics.push_back(
        {Severity::Error, source.path, 0, 0, std::string("material removal failed: ") + ex.what()});
    e.failed = e.removal_failed = true;
    return e;
  }
  for (const auto& removal : removals)
    add_diagnostics(e, removal->summary().diagnostics, source.path);
  // A result out of the range of numbers (a profile or program value at its limits) is not an
  // estimate: said, and the run fails, rather than shown as "0 s" or "inf".
  if (!std::isfinite(e.time_s) || !std::isfinite(e.energy.energy_j) ||
      !std::isfinite(e.energy.removed_mm3)) {
    e.diagnostics.push_back({Severity::Error, source.path, 0, 0,
                             "the estimate is not a finite number: a value of the program, the "
                             "profile or the stock is out of range"});
    e.failed = true;
  }
  logger().info("stream: {} commands, {} path samples, {:.3g} removal column visits in {:.3f} s",
                streamed, work_budget.path_samples(), work_budget.removal_work(), seconds_since(t));
  if (options.progress) options.progress(1);
  return e;
}

} // namespace ncjoule
