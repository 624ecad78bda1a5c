// ncjoule stage 4: energy. Power models, their constants, and the integration of power over the
// planner's samples into energy per command and per program (see docs/models.md).
//
// Units: W, J, s, mm, mm/s, mm^3, mm^3/s, rpm. The Zhou constants stay in the published units
// (kW, rpm, mm^3/s) inside PowerConstants and are converted to W where they are evaluated.
//
// How the three models read the machine's state (all documented in docs/models.md):
// - Axis motion (Pavanaskar, Combined): a move's feed is split among the axes by the components
//   of its velocity vector, F_i = |v_i| = speed * |d_i| / |d| for the step's displacement d.
//   KA_move_i applies only while axis i moves; KB_move_i * F_i follows the axis's own speed. A
//   rapid is a move like any other.
// - Cutting in Pavanaskar's model: while material is removed (MRR > 0), each axis contributes
//   its cut terms weighted by its share of the path, w_i = |d_i| / (|d_x| + |d_y| + |d_z|); the
//   shares add up to 1, so a diagonal cut costs the share-weighted mean of the X and Y cut lines,
//   and KA_cut_i is drawn only while cutting. With no material removed no cut term applies.
// - Combined: Pavanaskar's tare, coolant, spindle and axis-motion terms, and Zhou's MRR term
//   c3 * n^c4 * MRR (kW -> W) for cutting. Pavanaskar's KA_cut/KB_cut are not used.
// - Zhou: c1 is the machine's base power (reported as tare), c2 * n the spindle, c3 * n^c4 * MRR
//   cutting; there are no axis or coolant terms (the fit absorbed them).
// - Spindle off: no spindle power (and no Zhou cutting term). Coolant off: no coolant power.
// - Tool change (M6 with a duration): tare + coolant if on + tool_change_w; the spindle is
//   stopped while the tool is swapped.
// - Spindle ramp (a spindle command with a duration): spindle power goes linearly from its value
//   at the old speed (0 when off) to its value at the new speed; the energy is the trapezoid.
// - Every model adds tool_change_w during tool changes.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/gcode.hpp"
#include "ncjoule/kinematics.hpp"
#include "ncjoule/machine.hpp"
#include "ncjoule/removal.hpp"

namespace ncjoule {

// ---------------------------------------------------------------------------------------------
// Components: every prediction is split into these, and they add up to the total.
// ---------------------------------------------------------------------------------------------

enum class PowerComponent : std::uint8_t {
  Tare,
  Coolant,
  Spindle,
  AxisX,
  AxisY,
  AxisZ,
  Cutting,
  ToolChange
};
inline constexpr std::size_t kPowerComponentCount = 8;
using ComponentValues = std::array<double, kPowerComponentCount>;

// "tare", "coolant", "spindle", "axis_x", "axis_y", "axis_z", "cutting", "tool_change"
std::string_view component_name(PowerComponent component);
inline double component_sum(const ComponentValues& values) {
  double sum = 0;
  for (double v : values)
    sum += v;
  return sum;
}

// ---------------------------------------------------------------------------------------------
// Operating point: what the machine does at one instant; the input of every power model.
// Fields that are switches hold 0 or 1, and may take values in between inside a segment that
// ramps from one state to another (see OperatingSegment).
// ---------------------------------------------------------------------------------------------

struct OperatingPoint {
  double spindle_on = 0;                   // 1 while the spindle turns
  double spindle_rpm = 0;                  // 0 when off
  double coolant_on = 0;                   // mist or flood
  std::array<double, 3> axis_moving{};     // 1 while the axis moves (X, Y, Z)
  std::array<double, 3> axis_speed_mm_s{}; // |v_i|, the axis's part of the feed
  std::array<double, 3> cut_share{};       // |d_i| / sum |d_j| while cutting, else 0
  double mrr_mm3_s = 0;
  // While cutting: the radial engagement a_e (mm), the step's volume over its depth of cut and
  // its length across XY; 0 where removal does not say (the cut is then taken as a slot).
  double radial_width_mm = 0;
  double tool_change = 0; // 1 while a tool change runs
  // The cutting term's factor for the chip thickness (Kienzle's k_c(h) / k_c), 1 where no
  // correction applies.
  double cutting_factor = 1;
};

// ---------------------------------------------------------------------------------------------
// Power constants as a flat list of named parameters, so that calibration can fit any subset
// and the profile writer can name each one.
// ---------------------------------------------------------------------------------------------

enum class PowerParameter : std::uint8_t {
  Tare,
  Coolant,
  SpindleKA,
  SpindleKB,
  SpindleKC,
  MoveKAX,
  MoveKAY,
  MoveKAZ,
  MoveKBX,
  MoveKBY,
  MoveKBZ,
  CutKAX,
  CutKAY,
  CutKAZ,
  CutKBX,
  CutKBY,
  CutKBZ,
  ZhouC1,
  ZhouC2,
  ZhouC3,
  ZhouC4,
  ZhouD1,
  ZhouD2,
  ZhouD3,
  ZhouD4,
  ToolChange
};
inline constexpr std::size_t kPowerParameterCount = 26;

struct PowerParameterInfo {
  // Dotted key under [power] in a machine profile, as core/machine reads it, e.g.
  // "pavanaskar.x.move_kb_w_per_mm_s", "zhou.c3", "tool_change_w".
  std::string_view key;
  std::string_view unit; // e.g. "W/(mm/s)"
  PowerComponent component;
};

const PowerParameterInfo& parameter_info(PowerParameter parameter);
double get_parameter(const PowerConstants& constants, PowerParameter parameter);
void set_parameter(PowerConstants& constants, PowerParameter parameter, double value);
// The parameters a model's power formula uses (the SEC model's d1..d4 are in none of them).
std::vector<PowerParameter> model_parameters(PowerModel model);
std::string_view model_name(PowerModel model); // "combined", "pavanaskar", "zhou"
std::optional<PowerModel> model_from_name(std::string_view name);

// The linear part of a model's power at a point: P = sum_j linear[j] * value_j + the Zhou MRR
// term zhou_mrr_weight_w * c3 * n^c4 (zero for Pavanaskar). Shared by the estimator and the
// fits, so that what is fitted is exactly what is predicted.
struct PowerFeatures {
  std::array<double, kPowerParameterCount> linear{};
  double zhou_mrr_weight_w = 0; // 1000 * spindle_on * MRR (kW -> W)
  double zhou_rpm = 0;
};
PowerFeatures power_features(PowerModel model, const OperatingPoint& point);

// Power of each component at one point, W.
ComponentValues component_power_w(const PowerConstants& constants, const OperatingPoint& point);

// component_power_w for one set of constants evaluated at many points: the parameters the model
// uses, their values and components are looked up once (looking them up on every call was a
// tenth of an estimate's work). The same operations in the same order: the same bits.
class PowerEvaluator {
public:
  explicit PowerEvaluator(const PowerConstants& constants);
  ComponentValues operator()(const OperatingPoint& point) const;

private:
  struct Term {
    PowerParameter parameter;
    PowerComponent component;
    double value;
  };
  PowerModel model_;
  double zhou_c3_, zhou_c4_;
  std::array<Term, kPowerParameterCount> terms_{};
  std::size_t term_count_ = 0;
};

// Zhou et al.: P = c1 + c2*n + c3*n^c4*MRR, in kW. SEC model d1*n^d2 + d3*n/MRR + d4/MRR,
// in J/mm^3 (MRR must be > 0).
double zhou_power_kw(const ZhouConstants& zhou, double rpm, double mrr_mm3_s);
double zhou_sec_model_j_mm3(const ZhouConstants& zhou, double rpm, double mrr_mm3_s);

// A one-line account of the model and its constants, for result headers.
std::string describe_power_constants(const PowerConstants& constants);

// ---------------------------------------------------------------------------------------------
// Operating trace: the program as a sequence of time segments, over each of which the operating
// point goes linearly from `start` to `end` (the MRR of a sample step is constant over it).
// ---------------------------------------------------------------------------------------------

struct OperatingSegment {
  std::size_t command = 0; // index into Timeline::commands
  double t0_s = 0, t1_s = 0;
  OperatingPoint start, end;
};

// Builds the trace from the planner's samples and the removal stage's step volumes. `removal`
// may be null (no cutting). Problems (sizes that do not match) go to diagnostics.
std::vector<OperatingSegment> operating_trace(const std::vector<CanonCommand>& commands,
                                              const Timeline& timeline,
                                              const RemovalResult* removal,
                                              std::vector<Diagnostic>* diagnostics = nullptr);

// The segments of one timed command, appended to `out` (what operating_trace does for each).
// `previous_rpm` is the spindle speed before the command (for spindle ramps); it is updated.
void append_operating_segments(std::size_t index, const CanonCommand& command,
                               const TimedCommand& timed, const CommandRemoval* removal,
                               double& previous_rpm, std::vector<OperatingSegment>& out,
                               std::vector<Diagnostic>* diagnostics = nullptr);

// The operating point at time t (linear inside a segment). Before the first segment and after
// the last the machine is idle: tare only. Segments must be sorted by time.
OperatingPoint operating_point_at(const std::vector<OperatingSegment>& trace, double t_s);

// ---------------------------------------------------------------------------------------------
// Estimation
// ---------------------------------------------------------------------------------------------

struct EnergyOptions {
  std::optional<double> co2_kg_per_kwh; // overrides the profile's value
  std::optional<double> price_per_kwh;
  std::optional<double> machine_rate_per_hour; // overrides the profile's
  std::optional<std::string> currency;
  // Where the price and the machine rate above come from, for the reports ("command line",
  // "user config config.toml [machines.\"haas-vf2\"]"); empty: the profile's own.
  std::string price_from, rate_from;
  // Flutes of each tool (by the number moves carry), where known: with a material that has
  // Kienzle's constants, the chip thickness (feed per tooth) corrects the cutting term.
  std::map<int, int> flutes;
  // Diameters of the tools (mm): with the radial engagement removal measured, the chip of a
  // side cut is thinner than a slot's.
  std::map<int, double> tool_diameters_mm;
};

// Mean chip thickness (mm) of a cut at `per_tooth_mm` feed per tooth with radial engagement
// `radial_width_mm` of a `diameter_mm` cutter: (2 / pi) f_z for a slot, thinner for a side cut;
// a slot's where the engagement or the diameter is not known.
double mean_chip_thickness_mm(double per_tooth_mm, double radial_width_mm, double diameter_mm);

struct CommandEnergy {
  std::size_t command = 0; // index into Timeline::commands
  int line = 0;            // 0-based source line
  double duration_s = 0;
  double energy_j = 0;
  double mean_power_w = 0; // energy / duration; the instantaneous power when duration is 0
  double peak_power_w = 0;
  double peak_power_without_cutting_w = 0; // the same with the cutting component left out
  double removed_mm3 = 0;
  double sec_j_mm3 = 0; // energy / removed volume, 0 when nothing was removed
  ComponentValues components_j{};
  // The highest cutting power at the spindle (cutting component times the cutting efficiency)
  // over the spindle's rated power at that speed; 0 when the profile gives no rating.
  double spindle_load = 0;
};

struct EnergyResult {
  std::vector<CommandEnergy> commands; // parallel to Timeline::commands
  double duration_s = 0;
  double energy_j = 0;
  double removed_mm3 = 0;
  double sec_j_mm3 = 0;    // total energy / total removed volume (0 when nothing was removed)
  double mean_power_w = 0; // energy / duration
  double peak_power_w = 0;
  double co2_kg = 0;
  // What the run costs: its electricity plus its time at the machine-hour rate (0 when no
  // rate is given), in `currency`.
  double cost = 0;
  double electricity_cost = 0;
  double machine_cost = 0;
  double machine_rate_per_hour = 0;
  std::string currency;
  // Where the price per kWh and the machine rate came from ("profile", "command line", a user
  // config's file and section).
  std::string price_from = "profile", rate_from = "profile";
  ComponentValues components_j{};
  std::string model_description;
  std::vector<Diagnostic> diagnostics;
};

// The total power at the two ends of an operating segment, W (component_sum of the model's
// components there).
struct SegmentPower {
  double start_w = 0, end_w = 0;
};

// Energy one command at a time, in program order: estimate_energy for a pipeline that keeps no
// program-sized lists. The totals add up the commands given so far.
class EnergyIntegrator {
public:
  explicit EnergyIntegrator(const PowerConstants& constants, const EnergyOptions& options = {});
  // The spindle speed before the first command (0: stopped).
  void set_rpm_before(double rpm);
  // One command: its operating segments (appended to `segments`) and its energy. With `powers`,
  // the total power at the ends of each new segment is appended to it, parallel to `segments`
  // (for a power series that would otherwise evaluate the model again).
  CommandEnergy add(std::size_t index, const CanonCommand& command, const TimedCommand& timed,
                    const CommandRemoval* removal, std::vector<OperatingSegment>& segments,
                    std::vector<Diagnostic>* diagnostics = nullptr,
                    std::vector<SegmentPower>* powers = nullptr);
  // One command whose segments are already made (integrate_energy's form).
  CommandEnergy integrate(std::size_t index, const CanonCommand& command, const TimedCommand& timed,
                          const std::vector<OperatingSegment>& segments, double removed_mm3);
  CommandEnergy integrate(std::size_t index, const CanonCommand& command, const TimedCommand& timed,
                          const OperatingSegment* first, const OperatingSegment* last,
                          double removed_mm3, std::vector<SegmentPower>* powers = nullptr);
  // The totals (no per-command list); `program_duration_s` > 0 replaces the sum of durations.
  // Its diagnostics say where the cutting term was used outside the speeds and removal rates
  // its constants were fitted on (once per program).
  EnergyResult totals(double program_duration_s = 0) const;

private:
  void correct_for_chip_thickness(const CanonCommand& command, OperatingSegment* first,
                                  OperatingSegment* last) const;
  void note_cutting(const OperatingPoint& point);
  // The model's power at `point`: the last point's again when `point` has the same bits (a
  // segment's end is the next one's start).
  const ComponentValues& power_at(const OperatingPoint& point);
  void spin_for_stopped_cut(const CanonCommand& command, OperatingSegment* first,
                            OperatingSegment* last);

  const PowerConstants& constants_;
  const PowerEvaluator evaluate_power_; // of constants_
  OperatingPoint last_point_;           // the point last evaluated, and its power
  ComponentValues last_power_{};
  bool has_last_point_ = false;
  EnergyOptions options_;
  double previous_rpm_ = 0;
  EnergyResult totals_;
  // Where the cutting term was used: speeds and removal rates while cutting.
  double cut_rpm_min_ = 0, cut_rpm_max_ = 0, cut_mrr_min_ = 0, cut_mrr_max_ = 0;
  bool cut_seen_ = false;
  // Material removed with the spindle stopped: the first such line (-1: none), how many such
  // commands, and the speed they were counted at (0: none known).
  // Spindle speeds asked for: the highest (and where), the lowest running one, and the
  // first line asking for more than the spindle's maximum.
  double spindle_rpm_min_ = 0, spindle_rpm_max_ = 0;
  int spindle_rpm_max_line_ = -1, over_max_line_ = -1;
  double over_max_rpm_ = 0;
  void note_spindle(const CanonCommand& command, OperatingSegment* first, OperatingSegment* last);
  int stopped_cut_line_ = -1;
  std::size_t stopped_cuts_ = 0;
  double stopped_cut_rpm_ = 0;
  bool stopped_cut_at_s0_ = false; // the first such cut had M3/M4 in force, at S0
};

// Integrates power over every step of every command (trapezoid rule, MRR per step = step
// volume / step time), so MRR that varies inside a block is integrated, not averaged first.
// A command with a duration and no samples (dwell, tool change, spindle ramp, ...) draws the
// power of its state over its duration.
EnergyResult estimate_energy(const std::vector<CanonCommand>& commands, const Timeline& timeline,
                             const RemovalResult* removal, const PowerConstants& constants,
                             const EnergyOptions& options = {});

// The same from a ready trace (calibration and tests use it).
EnergyResult integrate_energy(const std::vector<OperatingSegment>& trace, const Timeline& timeline,
                              const RemovalResult* removal, const PowerConstants& constants,
                              const EnergyOptions& options = {});

} // namespace ncjoule
