// Internal: the interpreter's state machine. interpreter.cpp runs the main loop,
// control_flow.cpp the O-words and subprogram calls, block_words.cpp reads a block's words,
// convert*.cpp execute a block step by step in rs274ngc's order, motion.cpp makes moves,
// canned_cycles.cpp expands drilling cycles.
#pragma once

#include <array>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "block.hpp"
#include "cutter_comp.hpp"
#include "cutter_comp_mode.hpp"
#include "label_index.hpp"
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
  void scan_labels(std::size_t from = 0);

  // --- the text run: the file given, then the control's programs loaded when called --------
  std::string_view line_text(std::size_t line) const;
  std::size_t line_count() const { return line_count_; }
  // The file a line of the joined text is in, and the line's 0-based number there.
  std::pair<const SourceFile*, std::size_t> locate(std::size_t line) const;
  // Loads the control's program `name` (O-number digits or an o<name>) through
  // options_.control_programs and indexes its labels; false when there is none.
  bool load_control_program(const std::string& name);
  std::string not_in_folders() const;
  void emit_preamble();

  // --- control flow (control_flow.cpp) -----------------------------------------------------
  struct Frame {
    std::size_t return_pc = 0;
    std::size_t start_pc = 0;                    // first line of the body (for Fanuc repeats)
    int repeats_left = 0;                        // Fanuc M98 L / P repeats still to run
    bool fanuc = false;                          // M98/M97/G65 frame (returns with M99)
    std::map<std::size_t, long> repeat_counters; // o-word repeat loops, by line
    int call_line = 0;                           // line of the outermost call
  };
  void handle_o_word(const Block& b);
  void o_sub(const Block& b);
  void o_return(const Block& b);
  void o_call(const Block& b);
  void o_if(const Block& b);    // if, elseif, else, endif
  void o_while(const Block& b); // do, while, endwhile
  void o_repeat(const Block& b);
  void o_break_or_continue(const Block& b);
  std::optional<std::size_t> find_next(const std::string& label, std::size_t after,
                                       std::initializer_list<const char*> keywords) const;
  std::optional<std::size_t> find_prev(const std::string& label, std::size_t before,
                                       std::initializer_list<const char*> keywords) const;
  bool eval_condition(std::string_view args, int column, double& value);
  void call_subroutine(std::size_t target_line, std::vector<double> args, bool fanuc, int repeats);
  void macro_call(const BlockValues& v);        // G65
  void fanuc_call(const BlockValues& v, int m); // M98, M97
  void fanuc_return(const BlockValues& v);      // M99
  // The line of block N<n_number> (Haas M97 target, Fanuc GOTO), in the program (O-number
  // section) being run if it has one there.
  std::optional<std::size_t> n_number_line(long n_number);
  // Fanuc macro B control flow (macro_flow.cpp). Returns true when the block's own words run
  // (IF [...] THEN whose condition holds).
  bool macro_statement(const Block& b);
  void macro_goto(const MacroStatement& m);
  std::optional<std::size_t> macro_loop_match(std::size_t line, const MacroStatement& m);
  void return_from_subroutine(std::optional<double> value);

  // --- one block: its words (block_words.cpp) and its execution (convert*.cpp) ----------------
  bool evaluate_words(const Block& b, BlockValues& v);
  bool check_modal_groups(BlockValues& v);
  void execute(const Block& b, BlockValues& v);
  void convert_comments(const Block& b);
  void convert_other_codes(const BlockValues& v);
  void convert_feed(const BlockValues& v);
  void convert_spindle_speed(const BlockValues& v);
  void convert_tool(const BlockValues& v);
  void convert_spindle_and_coolant(const BlockValues& v);
  void check_e_word(const BlockValues& v);
  void check_m_codes(const BlockValues& v);
  void convert_dwell(const Block& b, const BlockValues& v);
  void convert_plane_and_units(const BlockValues& v);
  void convert_cutter_compensation(const BlockValues& v);
  void convert_tool_length_offset(BlockValues& v);
  void convert_coordinate_system(const BlockValues& v);
  bool convert_additional_work_offset(int code, const BlockValues& v); // G54.1 P, G154 P, G110
  void select_work_offset(int index);
  void convert_path_control(const BlockValues& v);
  void convert_distance_modes(const BlockValues& v);
  bool convert_group0(const BlockValues& v);
  void set_motion_mode(const BlockValues& v);
  void convert_motion(BlockValues& v, bool axes_used);
  void convert_stops_and_calls(const BlockValues& v);

  // --- motion (motion.cpp) -------------------------------------------------------------------
  Pose target_from_words(const BlockValues& v, bool machine_coordinates);
  // Under G16: the plane's radius and angle words turned into the Cartesian words every move and
  // cycle reads, in the block's distance mode.
  void polar_words(BlockValues& v);
  // G16 (on) and G15 (off), or a warning where the dialect has no polar coordinates.
  void polar_mode(bool on, int column);
  // A straight move to `end`; `machine_axes` marks the axes sent to a machine position
  // (CanonCommand::machine_axes).
  void straight(CanonKind kind, const Pose& end, std::string text = {},
                std::uint8_t machine_axes = 0);
  // The linear axes a block names (X, Y, Z as bits 0, 1, 2).
  static std::uint8_t named_axes(const BlockValues& v);
  void probe(const Pose& end);
  void spline(const BlockValues& v, bool quadratic);
  void spindle_synced(const BlockValues& v);
  void inverse_time_feed(double length_mm, const BlockValues& v);
  void arc(const BlockValues& v, bool clockwise);
  // Centre of an I/J/K arc from the offsets (mm, in the plane's two axes).
  void arc_centre_from_offsets(const BlockValues& v, double sf, double ss, double ef, double es,
                               double of, double os, double& cf, double& cs);
  void spiral_warning(int column, double sf, double ss, double ef, double es, double cf, double cs);
  void go_home(const BlockValues& v, int base_param);
  void set_axis_offsets(const BlockValues& v);
  void set_coordinate_data(const BlockValues& v);
  void set_tool_data(const BlockValues& v);

  // --- cutter radius compensation (cutter_comp_moves.cpp) -------------------------------------
  void comp_on(const BlockValues& v, int code);
  void comp_off(int column);
  // The radius (mm) of tool `number` for G41/G42, if anything gives it.
  std::optional<double> comp_radius_of(int number) const;
  // LinuxCNC refuses what compensation cannot make: in its dialect, so does this interpreter.
  bool comp_strict() const { return strict_ && dialect_.name == "linuxcnc"; }
  // What compensation cannot make: an error where LinuxCNC is the control, else a warning; the
  // moves run as programmed from the tool's place until G40.
  void comp_problem(int column, const std::string& what);
  // Issues every held move and command as it is (a stop, the end of the program).
  void comp_release();
  // Moves the held moves' ends to `p` and issues them; a problem with that goes to comp_problem.
  bool comp_move_end(PlanePoint p, int column);
  // A G0/G1 (`kind`) or G2/G3 (`arc`, programmed) under compensation: true when made here.
  bool comp_straight(CanonKind kind, const Pose& end, int column);
  bool comp_arc(const CanonCommand& arc, int column);
  // A move compensation does not make (G28, G53, a cycle, a probe) with compensation on.
  void comp_bypass(int column, const std::string& what);
  // Holds `c` until the next move shows its corner (`direction`: where a straight's end may move;
  // `sweep`: an arc's programmed sweep).
  void comp_hold(CanonCommand c, PlanePoint direction, double sweep);
  // Holds a straight from `start` to the programmed `end` with the tool at `tool_at` in the
  // plane, and moves the tool and the program's position there.
  void comp_hold_straight(CanonKind kind, const Pose& start, const Pose& end, PlanePoint tool_at,
                          PlanePoint direction);

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
  // A tool change written as a comment ("( M6 T2 )": FreeCAD's grbl post, grbl has no changer).
  void commented_tool_change(const Comment& comment);
  void stop() { finished_ = true; }

  double unit() const { return state_.inch ? 25.4 : 1.0; }
  Pose offset_total() const; // work offset + G92 (mm)
  bool system_parameter(std::string_view name, double& value) const;

  const SourceFile& source_;
  std::deque<SourceFile> control_sources_;    // loaded programs (addresses stay put)
  std::vector<std::size_t> control_starts_;   // first joined line of each
  std::set<std::string> control_names_tried_; // loaded or looked for in vain
  std::size_t line_count_ = 0;
  const InterpreterOptions& options_;
  const CanonSink& sink_;
  Dialect dialect_;
  bool strict_ = true; // the dialect was given or recognised: refuse what its control refuses
  InterpretResult result_;
  Parameters params_;
  ToolTable tools_; // a copy: G10 L1/L10 edit it as the program runs

  // Program counter and control flow.
  std::size_t pc_ = 0;
  std::size_t next_pc_ = 0;
  bool finished_ = false;
  bool seen_percent_ = false;
  std::vector<Frame> frames_;
  LabelIndex labels_;                                     // where each O-word label is, by keyword
  std::unordered_map<long, std::size_t> program_numbers_; // Fanuc O-number -> line
  std::optional<std::unordered_map<long, std::vector<std::size_t>>> n_numbers_; // M97, GOTO
  std::vector<std::size_t> program_starts_; // O-number header lines, in order
  std::unordered_map<std::size_t, std::size_t> macro_loop_matches_; // WHILE/DO <-> END m lines
  std::size_t loop_iterations_ = 0;                                 // backward jumps of loops
  std::size_t blocks_run_ = 0;
  // Diagnostics already given, by line, column and message; looked up by a view of the message,
  // so that a repeat, as a loop gives them, costs no copy.
  using ReportedView = std::tuple<int, int, std::string_view>;
  struct ReportedOrder {
    using is_transparent = void;
    static ReportedView view(const ReportedView& v) { return v; }
    static ReportedView view(const std::tuple<int, int, std::string>& k) {
      return {std::get<0>(k), std::get<1>(k), std::get<2>(k)};
    }
    template <class A, class B> bool operator()(const A& a, const B& b) const {
      return view(a) < view(b);
    }
  };
  std::set<std::tuple<int, int, std::string>, ReportedOrder> reported_;
  void report(Severity severity, int column, std::string message);
  std::map<std::size_t, long> top_repeat_counters_; // o-word repeat loops outside calls

  // Modal state.
  ModalState state_;
  Pose pos_; // current position, program coordinates, mm
  // X, Y, Z (bits 0..2) the program has set (an absolute or machine-coordinate word, or a
  // return home), and those the move being made sets; a move starts where it is known only
  // once all three are.
  unsigned known_axes_ = 0, axes_being_set_ = 0;
  // Work offsets (mm): 1..9 G54..G59.3, 10.. the Fanuc family's G54.1 P1.. (9 + P).
  std::array<Pose, 10 + kAdditionalWorkOffsets> g5x_{};
  int g5x_index_ = 1;
  bool units_given_ = false; // G20/G21 or its dialect's equivalent seen
  Pose g92_;                 // G92 offsets (mm)
  double tool_offset_z_ = 0; // active tool length offset (mm)
  Motion motion_ = Motion::Rapid;
  // The G0/G1/G2/G3 mode in force when the current canned cycle (or G80) began: what moves axis
  // words after G80 where canned cycles are a modal group of their own (Dialect).
  Motion motion_before_cycle_ = Motion::Rapid;
  bool incremental_ = false; // G91
  // G16 polar coordinates: on, the pole (Mach3: where G16 was read) and the last angle given.
  bool polar_ = false;
  Pose polar_pole_;
  double polar_angle_deg_ = 0;
  bool arc_incremental_ = true;   // G91.1
  bool retract_to_r_ = true;      // G99
  double naivecam_tolerance_ = 0; // G64 Q (else P): restored after canned cycles
  bool error_past_cap_ = false;   // an error was kept past the diagnostics cap
  bool error_reported_ = false;   // an error, kept or not (options_.keep_diagnostics)
  int cutter_comp_ = 40;
  CutterCompState comp_;
  bool comp_motion_ = false;       // the move being made is a G0/G1/G2/G3 compensation may offset
  int comp_column_ = 0;            // its column
  std::set<int> g10_radius_tools_; // tools whose radius a G10 L1/L10/L11 R of the program gave
  std::optional<CompModeHints> comp_hints_;    // read at the first G41/G42
  std::optional<CompQueue::Held> comp_next_;   // the next command emitted is held with this
  bool arc_offsets_reversed_ = false;          // I/J/K read from the centre to the start
  std::size_t arcs_fitting_only_standard_ = 0; // I/J/K arcs that fit only the standard way
  int selected_tool_ = 0;
  bool tool_changed_ = false; // an M6 of the program's own has run
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
  double tap_peck_ = 0;        // Q of the current series of G84/G74 (program units), 0: none
  int current_line_ = 0;
  int current_call_line_ = 0;
  std::size_t command_count_ = 0;
  Block block_; // reused
};

} // namespace ncjoule::detail
