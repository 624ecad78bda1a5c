// ncjoule timing calibration from a machine's own logs: the programs a controller log recorded,
// predicted on a machine profile and set beside what the machine did, run by run, operation by
// operation and block by block; the profile's timing keys fitted to it with Ceres (rates,
// accelerations, block-end behaviour, tool change, waits), with their uncertainties and the keys
// the logs cannot tell apart; the spindle's run-up from its logged speed; the power model from a
// logged power (through calibrate.hpp); and the calibrated profile written.
//
// Units as everywhere in ncjoule: s, mm/s, mm/s^2, rpm, W.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "ncjoule/calibrate.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/logs.hpp"
#include "ncjoule/machine.hpp"
#include "ncjoule/report.hpp"

namespace ncjoule {

// ---------------------------------------------------------------------------------------------
// Programs, their predicted line times, and the runs the logs hold of them
// ---------------------------------------------------------------------------------------------

struct LoggedProgram {
  SourceFile source;
  ProgramOutline outline;
  EstimateOptions options; // removal off: times do not depend on it
  Estimate estimate;       // on the machine the runs are compared with
};

// Each line's predicted time as a function of the overrides: a + b / rapid for lines that are
// not feed moves, a / feed + b / rapid for feed moves (the rapid part b of a line comes from a
// second plan at another rapid override). Lines are 1-based (index 0 unused).
struct LineTimes {
  std::vector<double> a, b;
  std::vector<char> feed;
  bool rapid_known = false; // b was planned (else 0: every run at 100% rapid)
  double total() const;
  // Predicted time of lines first <= line < next at these overrides (fractions, 1 = 100%).
  double between(int first, int next, double rapid = 1, double feed_override = 1) const;
};

// Plans the program on the machine (removal off) once, and again at half the rapid rates when
// `rapid_override` is asked for. Lines of a subprogram called from elsewhere keep their time at
// their own line.
LineTimes plan_line_times(const LoggedProgram& program, const MachineProfile& machine,
                          bool rapid_override);

// A run of one of the programs, aligned, with what its stretches measured.
struct LoggedRun {
  std::size_t run = 0;     // index into LogEvidence::runs
  std::size_t program = 0; // index into LogEvidence::programs
  std::vector<LineGroup> groups;
  double measured_s = 0;        // cycle start to program end
  double feed_ratio = 0;        // logged path speed / programmed F on steady feed lines (0: none)
  double rapid_ratio = 0;       // measured / predicted time of its rapid stretches (0: none)
  bool usable = false;          // for totals, operations and the fit
  std::vector<std::string> why; // why not (alignment's and the checks')
  std::vector<std::string> notes;
};

// Everything read from the logs about the programs.
struct LogEvidence {
  ControllerLog log;
  std::vector<LogRun> runs;
  std::vector<RunAlignment> alignments; // one per run
  std::vector<LoggedProgram> programs;
  std::vector<LoggedRun> program_runs; // the runs aligned with a program, in time order
  // The rapid override and feed override a stretch ran at (fractions).
  double rapid_at(const LoggedRun& r, double t_s) const;
  double feed_at(const LoggedRun& r, double t_s) const;
};

struct EvidenceOptions {
  AlignOptions align;
  double feed_ratio_tolerance = 0.03;  // logged speed on feed lines vs F x override
  double rapid_ratio_tolerance = 0.25; // a run's rapids vs the other runs', relative to prediction
};

// Aligns the log's runs with the programs (evidence.runs and evidence.programs must be filled)
// and measures each aligned run's stretches; nothing is judged beyond what alignment says.
void gather_runs(LogEvidence& evidence, const EvidenceOptions& options = {});
// Whether a run of the program ran at a logged rapid override other than 100% (its prediction
// then needs the rapid part of each line).
bool needs_rapid_override(const LogEvidence& evidence, std::size_t program);
// Judges each run against the prediction (`times`: one per program, planned on the machine the
// runs are compared with): a run whose logged path speed on steady feed lines is not the
// programmed feed at the override in force, or whose rapids took far longer or shorter than the
// other runs' relative to the prediction (a rapid override not logged), is not usable.
void judge_runs(LogEvidence& evidence, const std::vector<LineTimes>& times,
                const EvidenceOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Measured against predicted
// ---------------------------------------------------------------------------------------------

struct MeasuredRange {
  double median = 0, min = 0, max = 0;
  std::size_t runs = 0;
};

struct OperationCheck {
  std::string name;
  int tool = 0;
  int line = 0; // 1-based line where it starts
  MeasuredRange measured;
  double predicted_s = 0; // at the median run's overrides
};

struct BlockCheck {
  int first = 0, next = 0; // lines first <= line < next (the log shows the first)
  std::string text;        // the text of its line that takes the most time, shortened
  MeasuredRange measured;
  double predicted_s = 0;
};

struct ProgramCheck {
  std::size_t program = 0;
  std::size_t runs = 0, usable_runs = 0;
  MeasuredRange measured; // totals of the usable runs
  double predicted_s = 0;
  std::vector<OperationCheck> operations;
  std::vector<BlockCheck>
      worst_blocks; // largest |predicted - measured|, stretches of 0.5 s or more
};

// The usable runs of each program against the prediction (`times`: one per program, planned on
// the machine checked). Programs without usable runs have usable_runs = 0 and no rows.
std::vector<ProgramCheck> check_programs(const LogEvidence& evidence,
                                         const std::vector<LineTimes>& times,
                                         std::size_t worst_blocks = 10);

// A program's runs and check as the HTML report draws them over its prediction (`times`: the
// program's, as check_programs took them): the check's figures, the runs, and the line each
// usable run had reached over time beside the line the prediction reaches at the overrides of
// the run of median time.
MeasuredOverlay measured_overlay(const LogEvidence& evidence, const ProgramCheck& check,
                                 const LineTimes& times);

// ---------------------------------------------------------------------------------------------
// The fit
// ---------------------------------------------------------------------------------------------

// A timing key of a machine profile that logs can tell.
enum class TimingKey {
  AccelX,
  AccelY,
  AccelZ,
  RapidX,
  RapidY,
  RapidZ,
  TransitionRatio,
  Settle,
  SettleRapid,
  ToolChange,
  ToolChangeFirstExtra,
  ToolChangeSameTool,
  ToolChangeSpindleStop,
  OptionalStop,
  ProgramEnd,
  CoolantOn,
  SpindleRamp,
  ArcAccel,
};
inline constexpr std::size_t kTimingKeyCount = 18;

struct TimingKeyInfo {
  TimingKey key;
  std::string_view table; // "kinematics", "kinematics.x", "kinematics.waits"
  std::string_view stem;  // "accel", "settle", "optional_stop"
  std::string_view unit;  // the suffix it is written with: "m_s2", "mm_s", "s"
  double to_unit;         // internal value times this is the written one
  bool linear;            // adds its value to the lines it concerns (no plan needed to fit it)
};
const TimingKeyInfo& timing_key_info(TimingKey key);
std::string timing_key_name(TimingKey key); // "kinematics.x.accel_m_s2"

double timing_key_value(const MachineProfile& machine, TimingKey key);
void set_timing_key(MachineProfile& machine, TimingKey key, double value);

struct FittedTimingKey {
  TimingKey key;
  double base = 0;  // the base profile's value (internal units)
  double value = 0; // fitted, or the base's when held
  double std_error = 0;
  bool fitted = false;
  std::string why; // held: why (not in the logs, cannot be told from another key); fitted: the data
  std::size_t evidence = 0; // lines of the usable runs that the key's time falls on
};

struct TimingFitOptions {
  std::vector<TimingKey> keys; // empty: every key the base profile's rules use
  int max_iterations = 20;
  double min_stretch_s = 2.0;   // consecutive stretches are joined until they last this long
  double huber_sigma = 10.0;    // robust loss scale, in standard deviations of a stretch
  double stretch_sigma_s = 0.1; // a stretch's time is known to a sample period
  double stretch_sigma_rel = 0.0;
  bool tie_axes =
      true; // fit one acceleration (and one rapid rate) for axes the logs cannot tell apart
  double prior_sigma = 0.5; // the plan's factors are held to 1 +- this (a weak prior at the base)
};

struct TimingFit {
  std::vector<FittedTimingKey> keys;
  MachineProfile machine; // the base with the fitted values
  // Set when the fit finds that the path waits for the spindle (the base said it does not).
  std::optional<bool> spindle_waits;
  std::size_t stretches = 0, runs = 0;
  double rms_before_s = 0, rms_after_s = 0; // of the stretches
  bool converged = false;
  std::string message; // solver trouble; empty when all went well
  std::vector<std::string> notes;
};

// Fits the keys to the usable runs' stretches. Each evaluation plans every program on the
// machine being fitted (the keys that only add time are counted once per line instead).
TimingFit fit_timing(const LogEvidence& evidence, const MachineProfile& base,
                     const TimingFitOptions& options = {});

// The spindle's run-up from rest as the logged spindle speed shows it, (rpm, s) points at each
// 1000 rpm up to the highest speed seen (medians over the run-ups of the usable runs), and how
// many run-ups there were. Empty when fewer than three.
struct SpindleRunUp {
  std::vector<std::pair<double, double>> points;
  std::size_t run_ups = 0;
  double rpm_per_s = 0; // the mean rate from rest to the top
};
SpindleRunUp measure_spindle_run_up(const LogEvidence& evidence);

// ---------------------------------------------------------------------------------------------
// The calibrated profile
// ---------------------------------------------------------------------------------------------

struct CalibratedProfileInfo {
  std::string name;              // the new profile's name
  std::string machine;           // the machine (the log's device name)
  std::string date;              // of the calibration, YYYY-MM-DD
  std::vector<std::string> data; // the logs and programs, with the runs used
};

// The base profile's text with the fitted keys (and the run-up) written in place of its own,
// each with its uncertainty and data in a comment, the others left as they were, and a header
// that names the machine, the date and the data. nullopt (with the reason) when the result would
// not load.
std::optional<std::string> calibrated_profile_text(std::string_view base_toml,
                                                   const std::string& base_path,
                                                   const TimingFit& fit, const SpindleRunUp& run_up,
                                                   const CalibratedProfileInfo& info,
                                                   std::vector<Diagnostic>& diagnostics);

// The logged power of a usable run (its Power samples, or its spindle load times the spindle's
// rating when `spindle_rated_w` > 0) as a power log timed from the run's start.
std::optional<PowerLog> run_power_log(const LogEvidence& evidence, const LoggedRun& run,
                                      double spindle_rated_w = 0);

} // namespace ncjoule
