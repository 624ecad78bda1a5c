// ncjoule: the whole pipeline behind one call. Interprets a program, plans it on a machine,
// simulates material removal and integrates power, and folds the results into one summary per
// source line, per operation and per program: what the command line, the annotator, the reports
// and the C API all show.
//
// The pipeline streams: commands flow through the planner, removal and energy a batch at a time
// and are folded into small per-line results as they come. Memory is bounded by the stock model
// and those results (about 100 bytes a source line), never by the program's commands.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ncjoule/budget.hpp"
#include "ncjoule/energy.hpp"
#include "ncjoule/gcode.hpp"
#include "ncjoule/kinematics.hpp"
#include "ncjoule/machine.hpp"
#include "ncjoule/removal.hpp"

namespace ncjoule {

struct EstimateOptions {
  std::optional<Dialect> dialect; // empty: the machine's dialect, else detected from the file
  bool detect_dialect = false;    // detect even when the machine names a dialect (--dialect auto)
  // The choice an estimate of the same program made (optimize's check of its rewrite), over
  // `dialect`: read as it was, leniently where nothing named a dialect.
  std::optional<DialectChoice> dialect_choice;
  std::optional<StockSpec> stock; // empty: the bounding box of the cutting moves
  bool simulate_removal = true;   // false: no tools needed, cutting power is zero
  RemovalOptions removal;
  EnergyOptions energy;
  // A LinuxCNC tool table: lengths for G43, and a tool for every entry with a diameter.
  ToolTable tool_table;
  std::string tool_table_path; // for diagnostics
  // Tools from a job file or the command line; a tool here replaces the program's header
  // comment (and the tool table) for the same number.
  std::map<int, Tool> tools;
  // The stocks of the program's setups after the first (a job file's [[setup]] entries, in
  // order; `stock` is the first setup's); a setup given none gets the box of its own cuts.
  std::vector<std::optional<StockSpec>> setup_stocks;
  // Work offsets (machine coordinates of each origin, mm; 1..9 = G54..G59.3) from a job file,
  // in place of the profile's [setup] work_offsets_mm for the same offset.
  std::map<int, Pose> work_offsets;
  // Folders of the control's programs (--macro-dir), searched before the profile's macro_dirs.
  std::vector<std::string> macro_dirs;
  // How this program's G41/G42 were posted, whatever the program and the profile say (a job
  // file's cutter_compensation); empty: the program's words, else the profile's [setup].
  std::optional<CutterCompMode> cutter_compensation;
  // The tool of moves that select and describe none; empty: the machine profile's.
  std::optional<Tool> default_tool;
  // The workpiece material (material.hpp); empty: the machine profile's. It sets the cutting
  // term of profiles whose cutting term is the material's.
  std::string material;
  // Called now and then with the fraction done (0 to 1) on the calling thread, e.g. for a
  // progress bar; may be empty.
  std::function<void(double fraction)> progress;
  // Keep the operating trace of the whole program in Estimate::trace (calibration needs it;
  // memory grows with the program).
  bool keep_trace = false;
  // When set, every canonical command as removal reads it (program coordinates, mm; machine
  // positions placed), in program order, is appended here: what optimize replays. Memory grows
  // with the program.
  std::vector<CanonCommand>* keep_commands = nullptr;
  // The memory budget of the run is removal.memory_budget_bytes (0: default_memory_budget_bytes):
  // the program's own memory (estimated_program_memory) is taken out of it first, and the stock
  // model gets the rest.
  // Bounds on what the program may make the interpreter do (gcode.hpp); its max_commands is the
  // budget of moves (budget.hpp).
  InterpreterLimits limits{.max_commands = kDefaultMaxMoves};
  // Path samples of one move at most (PlanOptions::max_samples_per_move).
  std::size_t max_samples_per_move = 100'000;
  // The work budgets besides the one of moves (budget.hpp; 0: none): the path samples the
  // planner makes for the whole program, and the removal work, in grid columns under the tool
  // summed over its steps (each step's length plus the tool's diameter, times the diameter, over
  // a cell's area; counted before the step is cut).
  std::size_t max_path_samples = kDefaultMaxPathSamples;
  double max_removal_work = kDefaultMaxColumnVisits;
  // Moves the planner gathers before it looks ahead (PlanOptions::look_ahead_batch).
  std::size_t look_ahead_batch = 64;
  // The interpreter, the planner and the folding of results (removal, energy) run at once, each
  // on a thread of its own, handing commands on in order; false: one after the other on the
  // calling thread. The numbers are the same either way (tests compare the two).
  bool overlap_stages = true;
  // The second pass replays the first pass's commands, held compactly (about 20 bytes a move, at
  // most 64 bytes a line of the program), rather than interpreting the text again; a program
  // whose commands need more (loops, calls) is interpreted again. false: always interpret again.
  // The numbers are the same either way (tests compare the two).
  bool replay_first_pass = true;
};

// A job file (TOML) says what a program is cut from and with:
//   stock = "box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX"   (or an .stl path)   or   stock_stl = "x.stl"
//   units = "mm" | "in"   (of the stock's values written without a unit; default: the program's)
//   material = "aluminium-alloy"                  (the workpiece: material.hpp)
//   machine = "haas-vf2" | "mill.toml"            (a shipped profile's name, or a profile file)
//   [[setup]]  stock = ... or stock_stl = ..., name = "..."   (one per setup of the program, in
//              order, in place of the top-level stock: setups.hpp says where a setup begins)
//   [work_offsets_mm]  G54 = [X, Y, Z], G55 = ...  (machine coordinates of each origin)
//   cutter_compensation = "control" | "wear"      (how the program's G41/G42 were posted)
//   [[tool]]  number = 1, type = "flat" | "ball" | "bullnose" | "drill" | "chamfer",
//             diameter_mm, corner_radius_mm, point_angle_deg, tip_diameter_mm,
//             flute_length_mm, shank_diameter_mm, flutes
// Paths are relative to the job file's folder.
struct JobFile {
  std::string path;
  std::optional<StockSpec> stock; // of the first setup; empty: the job gives none
  // Stocks of the setups after the first ([[setup]] entries 2, 3, ...); empty ones: none given.
  std::vector<std::optional<StockSpec>> setup_stocks;
  std::map<int, Pose> work_offsets; // [work_offsets_mm]: G54 = [X, Y, Z], ... (1..9)
  std::optional<CutterCompMode> cutter_compensation; // "control" | "wear"
  std::string material;                              // empty: the job names none
  // The machine: a shipped profile's name as -m takes it, or a profile file (resolved against
  // the job file's folder); empty: the job names none.
  std::string machine;
  std::map<int, Tool> tools;
};
// Parses the text of a job file that lives at `path`. Errors (file, line, column, key and what
// is wrong) go to `diagnostics` and give std::nullopt; unknown keys are warnings.
std::optional<JobFile> parse_job_file(std::string_view text, const std::string& path,
                                      std::vector<Diagnostic>& diagnostics);
// The same, reading the file.
std::optional<JobFile> read_job_file(const std::string& path, std::vector<Diagnostic>& diagnostics);

// What a source line does, by its most telling command: moves first, then what takes time.
enum class LineKind : std::uint8_t {
  Setting, // feed rate, units, plane, offsets, path control, ... (or nothing that runs)
  Rapid,
  Feed,
  Arc,
  Probe,
  Dwell,
  SelectTool,
  ToolChange,
  Spindle,
  Coolant,
  ProgramStop,
  OptionalStop,
  ProgramEnd,
  Message,
  Comment,
};
// "setting", "rapid", "feed", "arc", "probe", "dwell", "select_tool", "tool_change", "spindle",
// "coolant", "program_stop", "optional_stop", "program_end", "message", "comment"
const char* line_kind_name(LineKind kind);
LineKind line_kind(CanonKind kind);
// "rapid", "feed", ... for a command (line_kind_name of its line kind).
std::string kind_name(CanonKind kind);

// Everything the results say about one source line, over every time it ran. Kept small (about
// 100 bytes): a million-line program holds a million of these and nothing else of its size.
struct LineSummary {
  std::int32_t line = 0; // 0-based
  LineKind kind = LineKind::Setting;
  bool has_move = false;
  std::uint16_t note = 0;      // 1-based index into Estimate::notes (the first note), 0: none
  std::uint16_t operation = 0; // 1-based index into Estimate::operations where it first ran
  std::uint32_t commands = 0;  // canonical commands the line produced, over all its runs
  double start_s = 0;          // when it first ran
  double end_s = 0;            // when its last run ended
  double time_s = 0;           // over all its runs
  double removed_mm3 = 0;
  double energy_j = 0;
  float length_mm = 0;
  float entry_speed_mm_s = 0; // at its first move
  float exit_speed_mm_s = 0;  // at its last move
  float peak_speed_mm_s = 0;
  float mrr_peak_mm3_s = 0;
  float power_peak_w = 0;
  float spindle_load = 0; // highest cutting power at the spindle / its rating (0: no rating)
  std::array<float, kPowerComponentCount> components_j{}; // add up to energy_j (to float)
};

// Where a program's time goes, by what the machine does. Air cutting is feed motion that removes
// nothing (known only when removal is simulated): the first time an energy-minded programmer
// wants to cut.
struct TimeSplit {
  double rapid_s = 0;
  double feed_s = 0;    // all feed moves (G1, G2/G3, probes, canned-cycle feeds)
  double air_cut_s = 0; // the part of feed_s that removes nothing
  double tool_change_s = 0;
  double dwell_s = 0;   // G4 and the dwells of canned cycles
  double spindle_s = 0; // spindle speed-ups and slow-downs
  double other_s = 0;   // anything else that takes time
  int tool_changes = 0;
  double cutting_s() const { return feed_s - air_cut_s; }
  double total_s() const {
    return rapid_s + feed_s + tool_change_s + dwell_s + spindle_s + other_s;
  }
  void add(CanonKind kind, double duration_s, bool removes_material, bool removal_known);
};

// One operation: what runs from the post's operation comment or tool change to the next.
struct OperationSummary {
  // The comment a CAM post writes for the operation (see find_operation_name), else "T" and the
  // tool number. What runs before the first operation is "before first operation"; a program
  // with no operation start is one operation named "program".
  std::string name;
  int tool = 0;       // tool in the spindle at its start (0: none)
  int line = -1;      // 0-based line where it starts (tool change or comment; -1: program start)
  double start_s = 0; // when it first starts
  double time_s = 0;  // over every run of it (a tool change in a subprogram called twice)
  double energy_j = 0;
  double removed_mm3 = 0;
  double co2_kg = 0; // the program's factors applied to this operation's energy
  double cost = 0;
  ComponentValues components_j{};
  TimeSplit time;
};

// Power and removal rate over time, reduced as they come to at most a few thousand points (each
// time bucket keeps its lowest and highest value), so peaks and dips survive.
struct Series {
  std::vector<double> t_s;
  std::vector<double> value;
};
struct ProgramSeries {
  Series power_w;
  Series mrr_mm3_s;
};

// The toolpath reduced to a few thousand points for drawing: a point is kept where the path
// turns or the power changes.
struct PathPoint {
  float x = 0, y = 0, z = 0; // mm, program coordinates
  float power_w = 0;
  float mrr_mm3_s = 0;
  std::int32_t line = 0; // 0-based source line
  bool rapid = false;
};

// One setup of a program (a clamping of the part): where it starts, why, its stock and totals.
struct SetupSummary {
  int first_line = 0; // 0-based source line of its first command
  std::string reason; // "the program's start", "M0 at line 41, then G55"
  std::string stock;  // the stock it cuts, as RemovalResult::stock_description says
  StockSource stock_source = StockSource::None; // given, the program's, guessed from its cuts
  std::string stock_from;        // the kind of its source (RemovalResult::stock_from)
  std::string stock_origin;      // where it is written (RemovalResult::stock_origin)
  std::optional<Box3> stock_box; // program coordinates, mm; empty: no stock simulated
  double time_s = 0, energy_j = 0, removed_mm3 = 0;
};

// The figures that rest on a guessed stock (a setup whose stock nothing states: removal.hpp's
// guess_stock), with the range each can span: from no removal at all in the guessed setups (the
// floor) to the guess. Removed volume, MRR, cutting power and energy, peak power and SEC depend on
// it; times do not. A block that would need more than the spindle's rated power under a guessed
// stock is where the guess is wrong (material the CAM knew was gone: rest machining, a lead-in
// from outside the part): such blocks are listed, and their cutting is left out of the peak.
struct StockGuessRange {
  bool guessed = false;          // some setup's stock is guessed
  double removed_mm3 = 0;        // what the guessed setups remove (the floor is 0)
  double cutting_energy_j = 0;   // their cutting energy (the energy's floor is the total less it)
  double peak_power_floor_w = 0; // the program's peak with no cutting in the guessed setups
  double peak_power_guess_w = 0; // the peak the guess gives, its overloads included
  // Blocks over the spindle's rating under the guessed stock: how many, the first and the worst
  // (0-based lines; -1: none) and the worst one's share of the rating.
  std::size_t overload_blocks = 0;
  int first_overload_line = -1, worst_overload_line = -1;
  double worst_load = 0;
};

// The program's figures that rest on a guessed stock, each as the range it can span: from no
// removal in the guessed setups (low) to the guess (high). SEC has no such floor (nothing
// removed): it is only marked. Empty (guessed == false) when every stock is known.
struct GuessedFigures {
  struct Range {
    double low = 0, high = 0;
  };
  bool guessed = false;
  Range removed_mm3, energy_j, peak_power_w, co2_kg, cost;
  // The peak with the blocks over the spindle's rating under the guess (left out of high).
  double peak_with_overloads_w = 0;
};
struct Estimate;
GuessedFigures guessed_figures(const Estimate& e);

// mm^3 in a cubic inch (25.4^3): an inch program's volumes and removal rates are read in in^3.
inline constexpr double kMm3PerIn3 = 25.4 * 25.4 * 25.4;

struct Estimate {
  std::string file;
  Dialect dialect;
  DialectOrigin dialect_origin = DialectOrigin::Given;
  std::string dialect_reason;
  std::size_t blocks = 0;   // blocks the interpreter executed
  std::size_t commands = 0; // canonical commands they made
  bool program_end = false; // ended at M2/M30 or a closing '%', not at the end of the file
  double time_s = 0;        // the program's time
  // What was guessed rather than given: tools that stood in for ones nothing describes (or
  // tools left unsimulated), and the machine (the generic profile, nothing named one).
  bool tools_guessed = false;
  bool machine_guessed = false;
  bool inch = false; // the program's units: its first G20/G21 (else those it starts in)
  TimeSplit time;
  std::map<int, Tool> tools;            // by the number moves carry; 0: moves with none selected
  std::vector<int> unsimulated_tools;   // tools moves use that nothing describes (no removal)
  std::optional<RemovalResult> removal; // totals, stock and grid; empty when not simulated
  PowerConstants power;                 // the constants used (the profile's, with the material)
  EnergyResult energy;                  // totals and components (no per-command list)
  std::vector<OperationSummary> operations;
  std::vector<SetupSummary> setups; // at least one
  // The range of the figures a guessed stock sets (guessed == false when every stock is known).
  // energy.peak_power_w leaves out the cutting of blocks over the rating under a guessed stock.
  StockGuessRange stock_guess;
  // Feed moves taken for positioning rather than cutting (StockExtent::positioning_moves).
  std::size_t positioning_moves = 0;
  std::vector<LineSummary> lines; // one per source line that holds code, in file order
  std::vector<std::string> notes; // what LineSummary::note refers to
  ProgramSeries series;
  std::vector<PathPoint> path;
  std::vector<OperatingSegment> trace; // with EstimateOptions::keep_trace only
  std::vector<Diagnostic> diagnostics; // interpreter, planner, removal and energy, in order
  std::size_t diagnostics_dropped = 0; // beyond the cap on diagnostics
  bool failed = false;                 // an error made the numbers meaningless (see diagnostics)
  bool removal_failed = false;         // ... and it was the material removal stage's
  // ... and it was a work budget's (budget.hpp): the run was stopped, the program may be fine.
  bool budget_exceeded = false;
};

// The memory (bytes) the pipeline holds for a program of `bytes` bytes in `lines` lines besides
// the stock model: the text and its line positions, a result per line, and an annotated copy.
// Checked against the run's memory budget before anything else is allocated.
std::size_t estimated_program_memory(std::size_t bytes, std::size_t lines);
// Why such a program cannot be estimated within `budget` bytes; empty when it can.
std::string program_memory_problem(std::size_t bytes, std::size_t lines, std::size_t budget);
// The memory budget of a run when none is given: a quarter of this machine's physical memory,
// or half of what this process may take (ulimit -v, -d) where that is less.
std::size_t default_memory_budget_bytes();

// Runs the pipeline. Never throws for bad input: problems are diagnostics, and `failed` is set
// only when no estimate could be made (the removal stage failed outright). What cannot be
// modelled (a tool nothing describes, an unknown code) is a warning and a labelled
// approximation.
Estimate estimate_program(const SourceFile& source, const MachineProfile& machine,
                          const EstimateOptions& options = {});

} // namespace ncjoule
