// Internal: the interpreter's state machine. interpreter.cpp runs blocks and control flow,
// motion.cpp makes moves, canned_cycles.cpp expands drilling cycles.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "block.hpp"
#include "parameters.hpp"

namespace ncjoule::detail {

// The values of one block's words after evaluation. Axis values are in program units.
// Slot of a word letter in BlockValues: 'a'..'z', then '@' and '^' (polar radius, angle).
constexpr int slot(char c) {
  return c == '@' ? 26 : c == '^' ? 27 : c - 'a';
}

struct BlockValues {
  std::array<std::optional<double>, 28> letter; // by slot()
  std::vector<int> g;                           // G codes x10 (G61.1 -> 611)
  std::vector<int> m;                           // M codes
  std::array<int, 28> column{};                 // source column of each letter
  int g_column(int code) const;
  std::optional<double> operator[](char c) const { return letter[slot(c)]; }
  bool has(char c) const { return letter[slot(c)].has_value(); }
  bool has_axis() const {
    return has('x') || has('y') || has('z') || has('a') || has('b') || has('c') || has('@') ||
           has('^');
  }
  std::vector<std::pair<int, int>> g_columns; // (code, column)
};

enum class Motion : int {
  None = 800,
  Rapid = 0,
  Linear = 10,
  ArcCW = 20,
  ArcCCW = 30,
  SpindleSynced = 330,
  RigidTap = 331,
  Probe = 382,
  Probe3 = 383,
  Probe4 = 384,
  Probe5 = 385,
  Threading = 760,
  G73 = 730,
  G74 = 740,
  G81 = 810,
  G84 = 840,
  G82 = 820,
  G83 = 830,
  G85 = 850,
  G86 = 860,
  G89 = 890
};

class Interpreter {
public:
  Interpreter(const SourceFile& source, const InterpreterOptions& options, const CanonSink& sink);
  InterpretResult run();

private:
  // --- set up -------------------------------------------------------------------------------
  void scan_labels();
  void emit_preamble();

  // --- control flow (interpreter.cpp) -------------------------------------------------------
  struct Frame {
    std::size_t return_pc = 0;
    std::size_t start_pc = 0;                    // first line of the body (for Fanuc repeats)
    int repeats_left = 0;                        // Fanuc M98 L / P repeats still to run
    bool fanuc = false;                          // M98/M97/G65 frame (returns with M99)
    std::map<std::size_t, long> repeat_counters; // o-word repeat loops, by line
    int call_line = 0;                           // line of the outermost call
  };
  void handle_o_word(const Block& b);
  std::optional<std::size_t> find_next(const std::string& label, std::size_t after,
                                       std::initializer_list<const char*> keywords) const;
  std::optional<std::size_t> find_prev(const std::string& label, std::size_t before,
                                       std::initializer_list<const char*> keywords) const;
  bool eval_condition(std::string_view args, int column, double& value);
  void call_subroutine(std::size_t target_line, std::vector<double> args, bool fanuc, int repeats);
  void macro_call(const BlockValues& v); // G65
  void return_from_subroutine(std::optional<double> value);

  // --- one block ----------------------------------------------------------------------------
  bool evaluate_words(const Block& b, BlockValues& v);
  void execute(const Block& b, BlockValues& v);
  bool check_modal_groups(const BlockValues& v);

  // --- motion (motion.cpp) -------------------------------------------------------------------
  Pose target_from_words(const BlockValues& v, bool machine_coordinates);
  void straight(CanonKind kind, const Pose& end, std::string text = {});
  void probe(const Pose& end);
  void spline(const BlockValues& v, bool quadratic);
  void spindle_synced(const BlockValues& v);
  void inverse_time_feed(double length_mm, const BlockValues& v);
  void arc(const BlockValues& v, bool clockwise);
  void go_home(const BlockValues& v, int base_param);
  void set_axis_offsets(const BlockValues& v);
  void set_coordinate_data(const BlockValues& v);
  void set_tool_data(const BlockValues& v);

  // --- canned cycles (canned_cycles.cpp) -----------------------------------------------------
  void canned_cycle(Motion cycle, const BlockValues& v);

  // --- words of several letters (keywords.cpp) and Sinumerik cycles (sinumerik_cycles.cpp) ----
  struct SinumerikCycle {
    std::string name;                        // "cycle81"
    std::vector<std::optional<double>> args; // by position; empty arguments are nullopt
    int line = 0;                            // where it was defined (MCALL) or called
    int column = 0;
  };
  // Honours the block's multi-letter words (MCALL, CYCLE8x, TRANS/ATRANS, ROT/AROT, planner
  // hints) and warns about the rest. Clears v's axis words when they were a frame's values,
  // not a move. `call_now` receives a cycle to run after the block's motion.
  void keywords(const Block& b, BlockValues& v, std::optional<SinumerikCycle>& call_now);
  std::optional<SinumerikCycle> parse_cycle(const Keyword& k);
  void sinumerik_cycle(const SinumerikCycle& c);
  bool frame_active() const {
    return frame_rotation_deg_ != 0 || frame_shift_.x != 0 || frame_shift_.y != 0 ||
           frame_shift_.z != 0;
  }
  void rotate_arc_offsets(BlockValues& v) const;

  // --- output and diagnostics ----------------------------------------------------------------
  CanonCommand make(CanonKind kind) const;
  void emit(CanonCommand c);
  void emit_simple(CanonKind kind, double value = 0, std::string text = {});
  void error(int column, std::string message);
  void warning(int column, std::string message);
  void note(int column, std::string message);
  void stop() { finished_ = true; }

  double unit() const { return state_.inch ? 25.4 : 1.0; }
  Pose offset_total() const; // work offset + G92 (mm)
  bool system_parameter(std::string_view name, double& value) const;

  const SourceFile& source_;
  const InterpreterOptions& options_;
  const CanonSink& sink_;
  Dialect dialect_;
  InterpretResult result_;
  Parameters params_;
  ToolTable tools_; // a copy: G10 L1/L10 edit it as the program runs

  // Program counter and control flow.
  std::size_t pc_ = 0;
  std::size_t next_pc_ = 0;
  bool finished_ = false;
  bool seen_percent_ = false;
  std::vector<Frame> frames_;
  std::unordered_map<std::string, std::vector<std::pair<std::size_t, std::string>>> labels_;
  std::unordered_map<long, std::size_t> program_numbers_;          // Fanuc O-number -> line
  std::optional<std::unordered_map<long, std::size_t>> n_numbers_; // Haas M97 targets
  std::size_t loop_iterations_ = 0;                                // backward jumps of loops
  std::size_t blocks_run_ = 0;
  std::set<std::tuple<int, int, std::string>> reported_; // diagnostics already given
  void report(Severity severity, int column, std::string message);
  std::map<std::size_t, long> top_repeat_counters_; // o-word repeat loops outside calls

  // Modal state.
  ModalState state_;
  Pose pos_;                   // current position, program coordinates, mm
  std::array<Pose, 10> g5x_{}; // work offsets 1..9 (mm)
  int g5x_index_ = 1;
  Pose g92_;                 // G92 offsets (mm)
  double tool_offset_z_ = 0; // active tool length offset (mm)
  Motion motion_ = Motion::Rapid;
  bool incremental_ = false;      // G91
  bool arc_incremental_ = true;   // G91.1
  bool retract_to_r_ = true;      // G99
  double naivecam_tolerance_ = 0; // G64 Q (else P): restored after canned cycles
  int cutter_comp_ = 40;
  int selected_tool_ = 0;
  // Sticky canned-cycle values (program units).
  double cycle_r_ = 0, cycle_z_ = 0, cycle_q_ = 0, cycle_p_ = 0;
  bool have_cycle_r_ = false, have_cycle_z_ = false;
  // Height of the drilling axis when the current series of cycles began (rs274ngc's "initial
  // level", kept across the blocks of one series): G98 retracts to it, every hole of the series
  // is approached at it, and under G91 R is measured from it.
  double cycle_initial_height_ = 0;
  bool have_cycle_initial_height_ = false;
  // Sinumerik: the cycle MCALL made modal, and the programmable frame (TRANS/ATRANS shift,
  // ROT/AROT rotation about Z), applied to programmed positions as rotate, then shift.
  std::optional<SinumerikCycle> modal_cycle_;
  Pose frame_shift_;
  double frame_rotation_deg_ = 0;
  bool rigid_tapping_ = false; // M29 given (Fanuc, Haas): G84/G74 are synchronised
  int current_line_ = 0;
  int current_call_line_ = 0;
  std::size_t command_count_ = 0;
  Block block_; // reused
};

} // namespace ncjoule::detail
