// ncjoule controller logs: what a machine's control recorded while it ran programs. MTConnect in
// the two forms shops keep it: an adapter's SHDR lines (timestamp|item|value|...) and an agent's
// Streams documents (/sample and /current XML, MTConnect 1.2 to 2.x). Data items are known by
// their MTConnect type (LINE, EXECUTION, PATH_FEEDRATE_OVERRIDE with subType RAPID, ...), not by
// one machine's names: the agent's device file gives the types of SHDR item names, a small
// mapping file (TOML) those of a control that names them otherwise. The log is cut into runs
// (cycle start to program end) and each run is aligned with the program it ran, block by block.
//
// Units as everywhere in ncjoule: s, mm/s, rpm, W; overrides in percent. Times are seconds since
// 1970-01-01 UTC. What is wrong with a log (gaps, a clock that jumps, UNAVAILABLE values, a run
// held or overridden) is found and said, never silently used.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/diagnostic.hpp"
#include "ncjoule/gcode.hpp"

namespace ncjoule {

// ---------------------------------------------------------------------------------------------
// What a logged value means
// ---------------------------------------------------------------------------------------------

enum class LogSignal : std::uint8_t {
  Line,            // LINE, LINE_NUMBER (ABSOLUTE), LINE_LABEL: the block running
  Block,           // BLOCK: the text of the block running
  Program,         // PROGRAM: the name of the program running
  Execution,       // EXECUTION: READY, ACTIVE, FEED_HOLD, PROGRAM_COMPLETED, ...
  Mode,            // CONTROLLER_MODE: AUTOMATIC, MANUAL, ...
  PathFeedrate,    // PATH_FEEDRATE (ACTUAL): the path's speed, mm/s
  FeedOverride,    // PATH_FEEDRATE_OVERRIDE (PROGRAMMED): %
  RapidOverride,   // PATH_FEEDRATE_OVERRIDE (RAPID): %
  SpindleSpeed,    // ROTARY_VELOCITY (ACTUAL) of the spindle, SPINDLE_SPEED: rpm
  SpindleOverride, // ROTARY_VELOCITY_OVERRIDE: %
  SpindleLoad,     // LOAD of the spindle: % of its rating
  Tool,            // TOOL_NUMBER, TOOL_ID
  Power,           // WATTAGE: the machine's electrical power, W
  Current,         // AMPERAGE: A
  Availability,    // AVAILABILITY: AVAILABLE or UNAVAILABLE
  EmergencyStop,   // EMERGENCY_STOP: ARMED or TRIGGERED
};
inline constexpr std::size_t kLogSignalCount = 16;

// "line", "execution", "rapid_override", ...: the keys of a mapping file's [items] table.
std::string_view log_signal_name(LogSignal signal);
std::optional<LogSignal> log_signal_from_name(std::string_view name);

// What a LINE value counts: the line of the program file (1 for its first line, as Hurco and
// many MTConnect adapters report it; or 0 for the first), or the block's N number (Fanuc's
// sequence number). Auto: decided for each run from the program it ran.
enum class LineNumbering : std::uint8_t { Auto, FileLine, FileLineFromZero, NWord };
std::string_view line_numbering_name(LineNumbering numbering); // "auto", "file-line", ...
std::optional<LineNumbering> line_numbering_from_name(std::string_view name);

// ---------------------------------------------------------------------------------------------
// The agent's device file (Devices.xml) and a mapping file
// ---------------------------------------------------------------------------------------------

// A data item as the device file describes it.
struct DataItemInfo {
  std::string id, name;
  std::string type, sub_type; // "PATH_FEEDRATE_OVERRIDE", "RAPID"
  std::string category;       // SAMPLE, EVENT, CONDITION
  std::string units;          // MILLIMETER/SECOND, PERCENT, ...
  std::string representation; // VALUE (or empty), TIME_SERIES, DATA_SET, TABLE
  std::string component;      // the element it belongs to: Rotary, Spindle, Path, Linear, ...
  std::string component_name; // its name: "C", "S", "X", "Path"
  std::string device;         // the device's name
};

struct DeviceFile {
  std::string path;
  std::vector<DataItemInfo> items;
  // The item with this id, else with this name (on `device` when given); nullptr when none.
  const DataItemInfo* find(std::string_view name_or_id, std::string_view device = {}) const;
};

std::optional<DeviceFile> parse_device_file(std::string_view xml, const std::string& path,
                                            std::vector<Diagnostic>& diagnostics);
std::optional<DeviceFile> read_device_file(const std::string& path,
                                           std::vector<Diagnostic>& diagnostics);

// For a control whose log does not name its data by MTConnect type (docs/controller-logs.md):
//   [items]      line = "Block_Number", execution = "Program_Status", ...  (a name or an id)
//   [scale]      path_feedrate = 0.0166667      (the log's value times this is mm/s, W, rpm, %)
//   [execution]  RUNNING = "ACTIVE", HOLD = "FEED_HOLD"   (the control's words as MTConnect's)
//   line_numbering = "file-line" | "file-line-from-zero" | "n-word" | "auto"
struct LogMapping {
  std::string path;
  std::map<LogSignal, std::string> items;
  std::map<LogSignal, double> scale;
  std::map<std::string, std::string> execution;
  LineNumbering line_numbering = LineNumbering::Auto;
};

std::optional<LogMapping> parse_log_mapping(std::string_view toml, const std::string& path,
                                            std::vector<Diagnostic>& diagnostics);
std::optional<LogMapping> read_log_mapping(const std::string& path,
                                           std::vector<Diagnostic>& diagnostics);

// How a data item is read: its signal (none: not used), from its MTConnect type and subType
// and the component it belongs to. A LOAD is the spindle's only on a spindle's component.
std::optional<LogSignal> signal_of(std::string_view type, std::string_view sub_type,
                                   std::string_view component, std::string_view component_name);

// ---------------------------------------------------------------------------------------------
// The log
// ---------------------------------------------------------------------------------------------

struct LogObservation {
  double t_s = 0;           // seconds since 1970-01-01 UTC
  double value = 0;         // numbers (scaled to ncjoule's units); NaN for texts
  std::uint32_t text = 0;   // texts: index into ControllerLog::texts (0: none)
  std::uint32_t line = 0;   // where in its file (SHDR line, XML element line)
  std::uint16_t file = 0;   // index into ControllerLog::files
  std::uint16_t device = 0; // index into ControllerLog::devices
  LogSignal signal = LogSignal::Line;
  bool unavailable = false; // the agent had no value (adapter disconnected, control off)
};

struct ControllerLog {
  struct File {
    std::string path;
    std::string format; // "SHDR", "MTConnectStreams 1.3", ...
    double first_s = 0, last_s = 0;
    std::size_t observations = 0; // of mapped items
  };
  std::vector<File> files;
  std::vector<std::string> devices; // by name ("" when the log names none)
  std::vector<std::string> texts{""};
  std::vector<LogObservation> observations; // in time order once finish_controller_log ran
  // Per device and signal: the item it was read from, as "Block_Number (LINE)".
  std::vector<std::array<std::string, kLogSignalCount>> items;
  // Items the log holds that map to no signal (with their type where known), and items that
  // map to a signal another item already gives.
  std::vector<std::string> unused_items;
  // The spans the files cover, merged: a value logged in one span says nothing of the next.
  std::vector<std::pair<double, double>> coverage;
  // Where the clock jumped back along a file (the time it jumped to).
  std::vector<double> clock_jumps;

  const std::string& text(const LogObservation& o) const { return texts[o.text]; }
  std::uint32_t intern(std::string_view text);
  std::uint16_t device_index(std::string_view name);
  // The covered span that holds `t`, or -1.
  int span_of(double t_s) const;
};

struct LogReadOptions {
  const DeviceFile* devices = nullptr;
  const LogMapping* mapping = nullptr;
  std::string device; // read only this device ("" = every device)
};

// Reads one log file (an SHDR file or a Streams document, told apart by its content) into `log`.
// Unreadable lines and elements are warnings with their line and are skipped; a file that is
// neither form, or a device file given as a log, is an error (false). Call
// finish_controller_log once every file is in.
bool parse_controller_log(std::string_view text, const std::string& path, ControllerLog& log,
                          const LogReadOptions& options, std::vector<Diagnostic>& diagnostics);
bool read_controller_log(const std::string& path, ControllerLog& log, const LogReadOptions& options,
                         std::vector<Diagnostic>& diagnostics);
// Puts the observations in time order, drops the ones two files both hold (pieces of one day's
// log cut from it), merges the files' spans into `coverage`, and says which signals no item
// gave (a note for each that matters: no line, no execution state).
void finish_controller_log(ControllerLog& log, std::vector<Diagnostic>& diagnostics);

// Seconds since 1970-01-01 UTC of an ISO 8601 time stamp (2017-02-07T19:38:27.6093750Z; a
// missing Z or an offset +hh:mm are read too); nullopt when it is not one.
std::optional<double> parse_log_time(std::string_view stamp);
// The same time as text, to the second (2017-02-07 19:38:27 UTC).
std::string format_log_time(double t_s);

// ---------------------------------------------------------------------------------------------
// Runs: cycle start to program end
// ---------------------------------------------------------------------------------------------

struct TimedValue {
  double t_s = 0;
  double value = 0;
};

struct LogRun {
  std::size_t device = 0;
  double start_s = 0; // EXECUTION went ACTIVE
  double end_s = 0;
  // What ended it: "PROGRAM_COMPLETED", "READY", "STOPPED", "INTERRUPTED", "UNAVAILABLE" (the
  // agent lost the control), "end of log".
  std::string ended;
  std::string program; // PROGRAM in force at the start, else the first during it
  // Every change of LINE; the first may be the value in force at the start, at the time it was
  // logged (so may the tool's).
  std::vector<TimedValue> lines;
  std::vector<std::pair<double, std::string>> states; // EXECUTION after the start
  std::vector<std::pair<double, std::string>> blocks; // BLOCK texts, when logged
  std::vector<TimedValue> feed, spindle, spindle_load, power, current, tool;
  // Overrides: the value in force at the start (at start_s) and every change during the run.
  // Empty when neither was logged in the span of the log that holds the run.
  std::vector<TimedValue> feed_override, rapid_override, spindle_override;
  // What makes the run's data doubtful: a value UNAVAILABLE during it, the log's spans ending
  // inside it, a clock that jumps back inside it.
  std::vector<std::string> data_problems;
};

// Cuts each device's observations into runs. A run starts where EXECUTION becomes ACTIVE after
// anything else but a hold (FEED_HOLD, INTERRUPTED, OPTIONAL_STOP, PROGRAM_STOPPED and WAIT stay
// in the run and are listed in its states) and ends at PROGRAM_COMPLETED, READY, STOPPED, an
// UNAVAILABLE execution or availability, or the end of the log.
std::vector<LogRun> find_runs(const ControllerLog& log);

// ---------------------------------------------------------------------------------------------
// Aligning runs with programs
// ---------------------------------------------------------------------------------------------

// What the alignment needs of a program: its names, the N word and tool change of each line and
// where it ends. Lines are 1-based file lines (index 0 unused).
struct ProgramOutline {
  std::string path;
  std::string name;         // the file's name without its folder
  std::string title;        // the O number and title comment a control may show ("O0000 (COVER)")
  int lines = 0;            // in the file
  int end_line = 0;         // the M2/M30 line (0: none)
  std::vector<long> n_word; // per line: its N number, -1 when it has none
  std::vector<int> tool_at; // per line: the tool an M6 on it loads (0: none, -1: an M6 with no T)
  std::vector<char> code;   // per line: holds code (not only a comment or a blank)
};

// Reads a program's outline from its text.
ProgramOutline outline_program(const SourceFile& source);

struct RunAlignment {
  std::size_t run = 0;         // index into the runs
  std::ptrdiff_t program = -1; // index into the programs; -1: none fits
  bool name_matches = false;   // the logged program name is this program's
  std::size_t candidates = 0;  // programs whose lines the run fits
  // When the lines fit several programs alike and the log's name did not decide: all of them
  // (indices into the programs, the one taken among them), in the order given. Programs that
  // differ only in their feeds (a test of feeds and speeds) fit alike: what the machine ran is
  // then told by its logged speeds (calibrate_timing's judge_runs).
  std::vector<std::size_t> alike;
  LineNumbering numbering = LineNumbering::Auto;
  // (time, 1-based file line) each time the running line changed, nondecreasing in line; the
  // first is the run's start at line 1 (the lines before the first logged one ran there).
  std::vector<TimedValue> marks;
  bool complete = false;        // from the top of the program to its end line, ended by the control
  bool usable = false;          // complete and undisturbed (see why)
  std::vector<std::string> why; // why not usable; empty when usable
  std::vector<std::string> notes; // said but not disqualifying (an override logged and used)
  // Overrides in force over the run, as fractions (1 = 100%): min and max; NaN when not known.
  double feed_override_min = 1, feed_override_max = 1;
  double rapid_override_min = 1, rapid_override_max = 1;
  bool feed_override_known = false, rapid_override_known = false;
};

struct AlignOptions {
  LineNumbering numbering = LineNumbering::Auto;
  double max_line_s = 600; // a line standing longer than this: the run was held
  // Overrides below this fraction (the knob at 0 while the operator watches) hold the machine.
  double min_override = 0.05;
};

// Aligns every run with the program it ran, by the logged program name and the order of its
// lines: a run fits a program when its lines, read by the numbering, run forward within the
// program's lines and its tool changes load the program's tools; among several, the one the log
// names wins. Runs that fit no program come back with program -1 and the reason.
std::vector<RunAlignment> align_runs(const std::vector<LogRun>& runs,
                                     const std::vector<ProgramOutline>& programs,
                                     const AlignOptions& options = {});

// The override in force at time t (fraction, 1 = 100%) in a run: the value logged last before t.
// `fallback` when none was logged.
double override_at(const std::vector<TimedValue>& values, double t_s, double fallback = 1);

// ---------------------------------------------------------------------------------------------
// Measured times
// ---------------------------------------------------------------------------------------------

// A stretch of a run between two changes of the running line: the lines first <= line < next
// took duration_s (a line shorter than the log's sample period may never show: its time falls to
// the line before it). The last runs to the run's end.
struct LineGroup {
  int first = 0, next = 0; // 1-based file lines
  double start_s = 0, duration_s = 0;
  bool disturbed = false; // a hold, a stop or an override near zero fell in it
};
std::vector<LineGroup> line_groups(const LogRun& run, const RunAlignment& alignment,
                                   const AlignOptions& options = {});

// When a run reached each line of `starts` (1-based; the first operation starts at the run's
// start), and how long each stretch to the next took (the last to the run's end). NaN where the
// line never showed.
std::vector<double> stretch_times(const RunAlignment& alignment, double end_s,
                                  const std::vector<int>& starts);

} // namespace ncjoule
