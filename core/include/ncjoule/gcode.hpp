// ncjoule stage 1: G-code source, dialects and the interpreter.
//
// The interpreter reads NC text and emits *canonical commands*, in the manner of LinuxCNC's
// split between its rs274ngc interpreter and the "canonical machining functions" it calls:
// rapid, linear feed, arc or helix, dwell, tool change, spindle, coolant, program end.
// Canned cycles, subprograms and control flow are expanded here, so later stages see only
// motion and machine state.
//
// Units: positions are stored in millimetres and degrees, in the program's work coordinate
// system (G5x, G92 and tool length offsets are reported as separate commands, as rs274 does).
// Every command carries the index of the source line it came from.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/diagnostic.hpp"

namespace ncjoule {

// ---------------------------------------------------------------------------------------------
// Source text
// ---------------------------------------------------------------------------------------------

// One physical line of the source: [begin, begin + length) holds the text, the following
// eol_length bytes its line ending ("\n", "\r\n", "\r" or none on the last line).
struct LineSpan {
  std::size_t begin = 0;
  std::size_t length = 0;
  std::uint8_t eol_length = 0;
};

// An NC file held in memory, byte for byte, with the position of every line.
struct SourceFile {
  std::string path; // as given by the user; used in diagnostics
  std::string text; // exact bytes
  std::vector<LineSpan> lines;

  std::string_view line_text(std::size_t index) const {
    const LineSpan& l = lines[index];
    return std::string_view(text).substr(l.begin, l.length);
  }
};

// The Fanuc family's additional work offsets (G54.1 P1..P300; Haas G154 P1..P99): work offset
// index 9 + P, after G54..G59.3 (1..9).
inline constexpr int kAdditionalWorkOffsets = 300;

// Splits text into lines; never fails.
SourceFile make_source(std::string path, std::string text);
// How many lines make_source() makes of `text` (LF, CRLF or a lone CR ends one), plus one: what
// a program's memory is judged by before it is split.
std::size_t count_lines(std::string_view text);

// Reads the control's programs from folders, first folder first: for an O-number the file
// named O9810, O9810.NC, 9810.nc (any case, any extension), for a LinuxCNC o<name> the file
// name.ngc. Unreadable files are skipped with a warning in `diagnostics` (taken by reference:
// it must outlive the returned function).
std::function<std::optional<SourceFile>(const std::string& name)>
control_programs_in(std::vector<std::string> folders, std::vector<Diagnostic>& diagnostics);

// The comments of one source line as a dialect reads them ("( )" and ";" as Dialect says), each
// trimmed, with the 1-based column of its opening character, and whether the line holds
// anything else than comments, blanks and a '%' tape mark. Every stage that reads comments
// (tool descriptions, operation names, annotation) reads them through this.
struct LineComment {
  std::string_view text;
  int column = 0;
};
struct LineComments {
  std::vector<LineComment> comments;
  bool has_code = false;
};
struct Dialect;
LineComments line_comments(std::string_view line, const Dialect& dialect);

// ---------------------------------------------------------------------------------------------
// Dialects: how a controller family writes G-code, as data.
// ---------------------------------------------------------------------------------------------

struct Dialect {
  std::string name; // "linuxcnc", "fanuc", "haas", "grbl", "mach3", "siemens", "heidenhain",
                    // "reprap"
  bool paren_comments = true;     // ( ... )
  bool semicolon_comments = true; // ; to end of line
  bool nested_paren_comments = false;
  bool dwell_p_in_ms = false;         // G4 P in milliseconds (Fanuc/Haas with integer P)
  bool dwell_p_integer_is_ms = false; // P without a decimal point is ms, with one is s
  bool dwell_x_word = false;          // G4 X<seconds> accepted
  bool decimal_point_optional_ms =
      false;                       // bare integers mean 1/1000 mm (Fanuc without G-code setting)
  bool o_word_subroutines = false; // LinuxCNC o<name> sub/call/if/while
  bool fanuc_subprograms = false;  // M98 P.. L.. / M99 within one file
  bool haas_local_subprograms = false;  // M97 P<N-number>
  bool g65_macro_calls = false;         // G65 P<program> with arguments
  bool dollar_lines = false;            // grbl's $ settings lines are ignored
  bool upper_case_comments = false;     // annotate in upper case (Fanuc family)
  bool retract_to_r_by_default = false; // initial G98/G99 state
  std::size_t max_line_length = 0;      // 0: no limit
  bool dwell_s_word = false;            // G4 S<seconds> accepted (Marlin, RepRapFirmware)
  bool paren_argument_lists = false;    // NAME(args) is a call (Sinumerik CYCLE81(...)), not
                                        // a comment
  bool sinumerik_words = false;         // MCALL, CYCLE81..89, TRANS/ATRANS, ROT/AROT, ...
  bool star_block_end = false;          // '*' ends a block (Heidenhain ISO)
  bool arc_centre_absolute = false;     // I/J/K are the absolute arc centre (Heidenhain ISO)
  bool g70_g71_units = false;           // G70 inch, G71 mm (Heidenhain ISO)
  // Canned cycles are a modal group of their own (Fanuc's group 09, as on Haas, Mach3 and
  // Sinumerik in ISO mode): G80 cancels the cycle and the G0/G1/G2/G3 in force before it moves
  // the axis words that follow. In LinuxCNC G80 is motion mode "none".
  bool canned_cycle_group = false;
  // Two G codes of one modal group in a block: the last one counts (Fanuc), where LinuxCNC
  // refuses the block.
  bool last_code_of_group_wins = false;
  // A full circle of zero radius (start, end and centre at one point, as Eagle's stepcraft.ulp
  // writes for holes smaller than its bit) is no motion (Mach3, UCCNC), where LinuxCNC refuses it.
  bool zero_radius_circle_is_no_motion = false;
  // A '%' line holds '%' alone (LinuxCNC: "Bad character '%' used" for "%name", "% text" or
  // "%(comment)"); elsewhere a name or a comment may follow it.
  bool percent_alone = false;
  // M codes the family's controls run that move nothing ncjoule times and draw nothing it
  // models (chip conveyor, air blast, axis brakes, messages): read without a warning. Each
  // family's manual names its own; a code outside the list stays an "unknown code" warning.
  std::vector<int> machine_m_codes;
  // G16/G15 polar coordinates (Fanuc, Haas, Mach3, Sinumerik in ISO mode): in the plane's
  // first axis word the radius, in its second the angle (degrees, counterclockwise from the first
  // axis). Fanuc measures the radius from the work zero under G90 and from the current point
  // under G91; Mach3 from the point where G16 was read (polar_pole_at_g16).
  bool polar_g16 = false;
  bool polar_pole_at_g16 = false;
  // A program streamed line by line with no end code (Marlin has no M2/M30 of its own): ending
  // at the end of the file is a note, not a warning.
  bool end_code_optional = false;
  // Marlin's parser: a letter alone is a flag ("G28 X Y"), what follows a number up to the next
  // letter is skipped ("X0..2" is X0) and a letter it has no use for is a parameter nothing
  // reads. Elsewhere such a word is a typo the control refuses (LinuxCNC: "Bad character 'o'
  // used", "bad number format"; Fanuc and Haas alarm; grbl: error 2): an error.
  bool lenient_words = false;
  // Peck drilling's small moves, a control parameter each family documents its own default for:
  // how far above the last peck G83 rapids back down after its retract to R, and how far G73
  // (high-speed peck) backs off to break the chip. rs274ngc: 0.010 in for both.
  double peck_clearance_mm = 0.254;
  double chip_break_retract_mm = 0.254;
  std::string comment_open = "("; // what the annotator writes
  std::string comment_close = ")";
};

// The built-in dialects; unknown names give std::nullopt.
std::optional<Dialect> find_dialect(std::string_view name);
std::vector<std::string> dialect_names();
// Guesses the dialect from the text (O-number headers, M98, grbl $ lines, o-words, ...).
// Returns "linuxcnc" when nothing is clear.
Dialect detect_dialect(const SourceFile& source);

// How the dialect of a run was chosen.
enum class DialectOrigin : std::uint8_t {
  Given,    // by the user or a profile
  Detected, // from the program's text (what told is in DialectChoice::reason)
  Default,  // nothing told: linuxcnc, with the controller-specific refusals relaxed to warnings
};
struct DialectChoice {
  Dialect dialect;
  DialectOrigin origin = DialectOrigin::Default;
  std::string reason; // e.g. "O-number program header at line 2", "given"
};
DialectChoice choose_dialect(const SourceFile& source);
// "linuxcnc (given)", "fanuc (detected: O-number program header at line 2)", ...
std::string describe_dialect_choice(const DialectChoice& choice);

// ---------------------------------------------------------------------------------------------
// Canonical commands
// ---------------------------------------------------------------------------------------------

struct Pose {
  double x = 0, y = 0, z = 0; // mm
  double a = 0, b = 0, c = 0; // degrees
};

enum class Plane : std::uint8_t { XY, YZ, XZ }; // G17, G19, G18
enum class FeedMode : std::uint8_t { UnitsPerMinute, InverseTime, UnitsPerRevolution }; // G94/93/95
enum class SpindleDir : std::uint8_t { Off, Clockwise, CounterClockwise };
enum class PathMode : std::uint8_t { ExactStop, ExactPath, Continuous }; // G61.1, G61, G64

// Machine state that holds while a command runs: enough for timing and power without
// replaying the stream.
struct ModalState {
  FeedMode feed_mode = FeedMode::UnitsPerMinute;
  double feed = 0; // F as programmed, converted to mm where it is a length:
                   // mm/min (G94), 1/min (G93), mm/rev (G95)
  double spindle_rpm = 0;
  SpindleDir spindle = SpindleDir::Off;
  bool mist = false;
  bool flood = false;
  int tool = 0;      // tool in the spindle
  bool inch = false; // program units at the time (for printing in program units)
  PathMode path_mode = PathMode::Continuous;
  double path_tolerance = 0; // mm, G64 P; 0 = as fast as possible
  Plane plane = Plane::XY;
};

enum class CanonKind : std::uint8_t {
  Traverse,     // G0, and the rapid parts of canned cycles, G28/G30, G53 G0
  Feed,         // G1 and the feed parts of canned cycles
  Arc,          // G2/G3, helices included
  Probe,        // G38.x: timed as a feed
  Dwell,        // value = seconds
  SelectTool,   // value = tool number (T word)
  ChangeTool,   // value = tool number (M6)
  SetFeedRate,  // value = F (program units/min, as rs274 prints)
  SetFeedMode,  // state.feed_mode
  SpindleSpeed, // value = rpm
  SpindleClockwise,
  SpindleCounterClockwise,
  SpindleStop,
  MistOn,
  FloodOn,
  MistOff,
  FloodOff,
  LengthUnits,      // state.inch
  PlaneSelect,      // state.plane
  PathControl,      // state.path_mode, state.path_tolerance; value = G64 Q (else P, else 0);
                    // text = "canned cycle" around the moves of a canned cycle
  ToolLengthOffset, // end.z = offset (mm)
  WorkOffset,       // value = index (1 = G54 ... 9 = G59.3), end = offset (mm)
  AxisOffset,       // G92: end = offset (mm)
  ProgramStop,      // M0
  OptionalStop,     // M1
  ProgramEnd,       // M2, M30
  Message,          // text = (MSG,...)
  Comment,          // text
  // A code that changes only how the controller blends, smooths or looks ahead, never the
  // programmed path: text = the code and its words as written ("G187 P3 E0.01", "G103 P5",
  // "G5.1 Q1", "G642", "CYCLE832(0.01,3)", "SOFT"), value = the code's number (187, 103, 5.1;
  // 0 for Sinumerik words). The planner may use it to choose its corner tolerance and look-ahead
  // (Haas G187: P1 rough, P2 medium, P3 finish, E the corner tolerance; G103 P: blocks of
  // look-ahead, P0 = the full buffer; Fanuc G5.1 Q1/Q0: AI contour control on/off; Sinumerik
  // G64x/CYCLE832/SOFT: blending and jerk limitation); it may also ignore it, as the default
  // planner does, since the programmed path and feed rate stay the same.
  PlannerHint,
};

struct CanonCommand {
  CanonKind kind = CanonKind::Comment;
  int line = 0;      // 0-based source line of the block that produced it
  int call_line = 0; // 0-based line in the main program whose block led here (a call site, or
                     // `line` itself outside subprograms)
  Pose start;        // moves: where the move starts (mm, program coordinates)
  Pose end;          // moves: where it ends
  // False for a move that starts before the program has set X, Y and Z (the start is the
  // assumed 0,0,0, not where the spindle is): "G0 X Y" before the first Z of most posts.
  bool start_known = true;
  // Axes this move sends to a machine position rather than a work position (G53, the return of
  // G28/G30 to home): bit 0 X, 1 Y, 2 Z. Their end is where the work offsets in the interpreter's
  // parameters put that machine position; where nothing describes the offsets, later stages
  // know it is not a place in the work (a Z home is above the part, not at its Z0).
  std::uint8_t machine_axes = 0;
  // Arcs: centre in the plane's two axes (X/Y for G17, Y/Z for G19, Z/X for G18), and the
  // rotation as rs274 prints it: +k = counter-clockwise with k-1 extra full turns, -k clockwise.
  double centre_first = 0, centre_second = 0;
  int rotation = 0;
  Plane plane = Plane::XY;
  double value = 0;
  std::string text;
  ModalState state; // state while this command runs
};

bool is_move(CanonKind kind);      // Traverse, Feed, Arc, Probe
bool is_feed_move(CanonKind kind); // Feed, Arc, Probe: the moves that cut

// Where the interpreter hands its commands: one call per command, in order.
using CanonSink = std::function<void(const CanonCommand&)>;

// Arc geometry helpers shared by the printer, the planner and removal.
struct ArcGeometry {
  double radius = 0; // mm, in the plane
  double sweep = 0;  // radians, signed (+ counter-clockwise in the plane's frame)
  double axial = 0;  // mm, helix rise along the plane's normal
  double length = 0; // mm, helix length sqrt((r*theta)^2 + h^2)
};
ArcGeometry arc_geometry(const CanonCommand& arc);
// Point on a move (line or arc) at fraction u in [0, 1] of its parameter.
Pose point_on_move(const CanonCommand& move, double u);
// A box (X, Y and Z of `low` and `high`) that holds every point point_on_move gives on an arc:
// its circle's square in the plane and its rise along the normal, a hair larger. Where a box
// already holds it, no point of the arc can widen it: the points need not be worked out.
void arc_bounds(const CanonCommand& arc, Pose& low, Pose& high);
// Length of a move's path in mm (linear axes only).
double move_length(const CanonCommand& move);
// How far each linear axis (X, Y, Z) travels over a move in mm, out and back both counted: a
// line's displacement, an arc's in-plane axes summed over each quarter turn (a full circle of
// radius r moves X and Y 4r each), its helix axis the rise.
std::array<double, 3> axis_travel(const CanonCommand& move);
// Whether a move travels across X and Y: every arc, and a line whose X or Y changes by more than
// a micrometre. What tells a level cut or a crossing from a plunge or a retract in Z alone.
bool travels_in_xy(const CanonCommand& move);

// ---------------------------------------------------------------------------------------------
// Tool table
// ---------------------------------------------------------------------------------------------

struct ToolEntry {
  int number = 0;
  double z_offset = 0; // mm, tool length
  double diameter = 0; // mm
  std::string comment; // the text after ';' (often the tool's name: "6mm ball end mill")
};
using ToolTable = std::map<int, ToolEntry>;
// Reads a LinuxCNC .tbl file ("T1 P1 Z1.5 D0.25 ;comment"); values in the given units.
// Errors go to diagnostics; the entries that parsed are kept.
ToolTable parse_tool_table(const SourceFile& file, bool inch, std::vector<Diagnostic>& diagnostics);

// ---------------------------------------------------------------------------------------------
// The interpreter
// ---------------------------------------------------------------------------------------------

// Bounds on what one program may make the interpreter do, each an error when passed (0: no
// limit). The defaults stop runaway programs; services and fuzzers that run programs from
// strangers set them lower.
struct InterpreterLimits {
  std::size_t max_commands = 0;                // canonical commands (guards runaway loops)
  std::size_t max_loop_iterations = 1'000'000; // backward jumps of loops
  std::size_t max_cycle_repeats = 100'000;     // L of one canned cycle block
  std::size_t max_arc_turns = 1'000'000;       // P of one arc (full turns of a helix)
};

// How a program's G41/G42 were posted. Control: the path is the part's contour and the control
// offsets it by the radius of the tool the D word names (CAM "in control"). Wear: the path is
// already the tool centre and the D register holds only a wear value (Fusion's "wear" and
// "inverse wear", Mastercam's "wear" and "reverse wear"); that value is not known here and is
// taken as 0, so the path runs as programmed.
enum class CutterCompMode : std::uint8_t { Control, Wear };

struct InterpreterOptions : InterpreterLimits {
  std::optional<Dialect> dialect; // empty: detect from the text
  // Detection found nothing: this dialect (the machine's control) rather than linuxcnc.
  std::optional<Dialect> fallback_dialect;
  // A later pass over a program (or a rewrite of it): the choice its first pass made, over
  // `dialect`. Its origin counts as well as its dialect: a program nothing named is read as
  // leniently again ("G28 Z", "M0 Turn ON spindle" warned of, not refused), where a dialect
  // merely given would refuse the blocks the first pass ran.
  std::optional<DialectChoice> same_choice_as_before;
  ToolTable tools;
  bool block_delete = false; // honour '/' (skip those blocks)
  bool optional_stop = true; // M1 stops (only recorded; time counts zero)
  // false: no diagnostics are collected (a second pass over a program whose first pass gave
  // them); the commands are the same.
  bool keep_diagnostics = true;
  // Work offsets known before the program runs (mm, machine coordinates of each origin;
  // 1..9 = G54..G59.3), as a controller holds them in its parameters; empty: all zero.
  std::map<int, Pose> work_offsets;
  // The program starts in inches (a control set to inch at power-on) until G20/G21 says.
  bool start_inch = false;
  // Cutter radius compensation (G41/G42): radii (mm) by tool number of tools described outside
  // the tool table (CAM header comments, a job file, --tool), as the estimate resolves them. A
  // D word's radius is the one a G10 L1 R of the program gave, else this, else the tool table's.
  std::map<int, double> comp_radius_mm;
  // How G41/G42 were posted: given, it holds whatever the program tells; empty, the program's own
  // word decides (G41.2/G42.2, a CAM tool line saying "WEAR COMP"), else
  // `default_cutter_compensation` (a machine's setting), else Control.
  std::optional<CutterCompMode> cutter_compensation;
  std::optional<CutterCompMode> default_cutter_compensation;
  // The machine's own peck distances (its control's parameters), over the dialect's defaults.
  std::optional<double> peck_clearance_mm, chip_break_retract_mm;
  // Programs the control holds outside this file (Fanuc/Haas O9xxx and probing macros, a
  // LinuxCNC subroutine file): asked for by name when a call finds no target in the file, as
  // the digits of the O-number ("9810") or the o<name> ("probe"); they return the program's
  // source, or nothing. Those found run like programs of the file; the caller does the reading
  // (control_programs_in reads folders).
  std::function<std::optional<SourceFile>(const std::string& name)> control_programs;
};

struct InterpretResult {
  Dialect dialect;
  DialectOrigin dialect_origin = DialectOrigin::Given;
  std::string dialect_reason; // what told the dialect (see DialectChoice)
  std::vector<Diagnostic> diagnostics;
  bool completed = false; // reached program end or end of file without a fatal error
  std::size_t blocks = 0; // blocks executed
  // Blocks with at least one word a controller reads (G1, X10, M3, an O-word, #1=2): a text that
  // has none holds no G-code, whatever else it holds (words of several letters, stray bytes).
  std::size_t word_blocks = 0;
  bool program_end = false; // ended at M2/M30 or a closing '%', not at the end of the file
  bool units_given = false; // a G20/G21 (G70/G71, a Heidenhain header) set the units
  // Tool numbers G41/G42 named (by D, or the tool in the spindle) whose radius nothing gave:
  // those moves were made as programmed.
  std::set<int> comp_radius_unknown;
  std::size_t commands = 0;
};

// Runs the program and hands every canonical command to sink. Never throws for bad input:
// problems become diagnostics, and the run stops only where going on would be unsafe.
InterpretResult interpret(const SourceFile& source, const InterpreterOptions& options,
                          const CanonSink& sink);

// Convenience: collects the commands.
struct Toolpath {
  std::vector<CanonCommand> commands;
  InterpretResult result;
};
Toolpath interpret(const SourceFile& source, const InterpreterOptions& options = {});

// Prints one command the way `rs274 -g` does (without its leading sequence number and N
// column), in program units with 4 decimals; empty for commands rs274 has no line for.
std::string format_canon(const CanonCommand& command);
// The same, appended to `out` (nothing for commands rs274 has no line for).
void append_canon(std::string& out, const CanonCommand& command);

} // namespace ncjoule
