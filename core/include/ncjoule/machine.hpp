// ncjoule machine profiles: what a machine can do (kinematics) and what it draws (power).
//
// A profile is a TOML file a person can read and edit (samples/machines/*.toml); this header is
// its in-memory form. All values are in internal units: mm, s, mm/s, mm/s^2, rpm, W.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ncjoule/gcode.hpp"
#include "ncjoule/material.hpp"
#include "ncjoule/tool.hpp"

namespace ncjoule {

enum class Axis : int { X = 0, Y = 1, Z = 2 };

struct AxisLimits {
  double rapid_mm_s = 0;     // rapid traverse rate
  double max_feed_mm_s = 0;  // highest programmable feed
  double accel_mm_s2 = 1000; // 1 m/s^2 unless the profile says otherwise
  double jerk_mm_s3 = 0;     // 0: no jerk limit (trapezoid even with the S-curve option)
};

enum class RapidMode { Linear, DogLeg };      // all axes on one line, or each at its own rate
enum class FeedProfile { Trapezoid, SCurve }; // velocity profile per block
// How fast a continuous-path (G64) junction between two moves may be taken.
//  Tolerance: from the angle between the moves and the path tolerance (the blend arc that stays
//             within the tolerance of the corner, taken at the acceleration limit).
//  NextFeed:  Pavanaskar's analyzer: each block slows only to the next block's feed, whatever
//             the angle.
//  LinuxCnc29: LinuxCNC 2.9's trajectory planner: blend arcs that shorten the path, its G64
//             tolerances, its full stops and its servo-cycle limits (docs/machine-profiles.md).
enum class JunctionRule { Tolerance, NextFeed, LinuxCnc29 };

// Which way +Z moves the tool. Up: away from the work (ISO 841, every standard mill). Down:
// into it (a machine whose post scales Z by -1, as Estlcam's "Scale z=-1" does). Auto: up,
// unless a program's rapids across XY all run below its cuts (the estimate then says so).
enum class ZDirection { Auto, Up, Down };

struct Kinematics {
  std::array<AxisLimits, 3> axes; // X, Y, Z
  double rotary_rapid_deg_s = 0;  // A/B/C, 0 when the machine has none
  double rotary_accel_deg_s2 = 0;
  RapidMode rapid_mode = RapidMode::Linear;
  FeedProfile feed_profile = FeedProfile::Trapezoid;
  JunctionRule junction_rule = JunctionRule::Tolerance;
  double path_tolerance_mm = 0.01;     // junction deviation used under G64 without P
  bool exact_stop_every_block = false; // every block starts and ends at rest, whatever G64 says
  // The rates are stand-ins, not the machine's (a profile built from a power fit whose source
  // gives no kinematics): a program that asks for more feed than they allow is told so.
  bool placeholder_rates = false;
  double tool_change_s = 0; // time of one M6
  // The sequence around it, where a control's differs: the first change of a program takes
  // longer (the magazine and arm start from their parked places), and an M6 for the tool
  // already in the spindle runs a shorter sequence (or none). Not given: every M6 takes
  // tool_change_s.
  double tool_change_first_extra_s = 0;
  std::optional<double> tool_change_same_tool_s;
  // Added to an M6 that finds the spindle turning: the control stops it and orients it for the
  // arm before the change (an M6 after M5 only orients, which tool_change_s holds), and leaves
  // it at rest (the next M3 runs it up from rest). 0: none.
  double tool_change_spindle_stop_s = 0;
  // The in-position check of a control that settles after every stop (Hurco, Haas and Fanuc
  // without their look-ahead modes): added to every move that ends at rest. 0 (LinuxCNC's
  // planner, which does not wait) by default.
  double settle_s = 0;
  // The same for rapids, where a control's differs (its rapids settle to a tighter window);
  // not given: settle_s.
  std::optional<double> settle_rapid_s;
  // The highest speed at the transition from one feed block to the next, as a fraction of the
  // lower of their two speeds, whatever the angle between them: a control that slows at every
  // block end even on a straight or tangent path (a Hurco or a Fanuc without its high-speed
  // look-ahead mode). 1: the corner rule alone (LinuxCNC). Rules Tolerance and NextFeed only.
  double transition_speed_ratio = 1;
  // How many blocks the control reads ahead of the one it runs: at the end of a block it must
  // be able to stop within the next lookahead_blocks, the last it has read. Matters on chains of
  // short blocks at high feed. 0: the whole path (ncjoule's planner sees all of it). Rules
  // Tolerance and NextFeed only.
  std::size_t lookahead_blocks = 0;
  // The centripetal acceleration a control allows on arcs (mm/s^2): it holds an arc of radius r
  // to sqrt(arc_accel * r), below what the axes' acceleration allows, as Fanuc's "allowable
  // acceleration in circular interpolation" does. Small-radius arcs (helical bores) then run
  // slower than F. Not given: the slower in-plane axis's acceleration.
  std::optional<double> arc_accel_mm_s2;
  // What a control spends on codes that move nothing, beyond what ncjoule times for them
  // ([kinematics.waits], measured from a machine's logs): an M1 with the optional stop off
  // still stops and checks, M30 rewinds and resets, coolant on may wait for pressure. 0: none.
  struct Waits {
    double optional_stop_s = 0; // M1, whether or not it stops for the operator
    double program_stop_s = 0;  // M0, the control's part (the operator's wait is not predicted)
    double program_end_s = 0;   // M2/M30 until the control reports the program complete
    double coolant_on_s = 0;    // M7/M8: the path waits for the coolant
  } waits;
  double spindle_s_per_1000rpm = 0; // spindle ramp: seconds per 1000 rpm of speed change
  // Whether the path waits for the spindle's ramp (LinuxCNC, Haas: "at speed"); a control that
  // moves on while the spindle runs up (Hurco's M3 line ends with its rapid) does not.
  bool spindle_waits = true;
  // A spindle's run-up as measured: seconds from rest to each speed (rpm, s), rising in both;
  // between the points and from rest to the first, linear; past the last, at the last
  // segment's rate. A change between speeds takes the difference of their times; a stop or a
  // reversal runs down on `spindle_run_down` (the run-up's times when empty). When given, it
  // replaces spindle_s_per_1000rpm: a real spindle's run-up is not linear in speed (its motor
  // has a constant-torque range, then a constant-power one where each rpm takes longer).
  std::vector<std::pair<double, double>> spindle_run_up, spindle_run_down;
  ZDirection z_positive = ZDirection::Auto; // removal only: times do not depend on it
  // The feed `ncjoule optimize` gives feed moves that run in air (air_feed_mm_min); 0: the
  // machine's highest feed. Capped by each axis's max_feed along the move.
  double air_feed_mm_s = 0;
};

// Pavanaskar Eq. 3.12 constants (per machine, per axis). Units: W, W/(mm/s), W/rpm, W/(mm^3/s).
struct PavanaskarConstants {
  double tare_w = 0;
  double coolant_w = 0;
  double spindle_ka_w = 0;
  double spindle_kb_w_per_rpm = 0;
  // Losses that grow with the square of speed (viscous bearing friction, windage, iron losses):
  // the no-load line bends up over a spindle's whole range. 0: a straight line.
  double spindle_kc_w_per_rpm2 = 0;
  std::array<double, 3> move_ka_w{}; // X, Y, Z
  std::array<double, 3> move_kb_w_per_mm_s{};
  std::array<double, 3> cut_ka_w{};
  std::array<double, 3> cut_kb_w_per_mm3_s{};
  // The spindle speeds the spindle line was measured (or estimated) over (0: not declared):
  // outside them its power is extrapolated, and a warning says how far.
  double spindle_fitted_rpm_min = 0, spindle_fitted_rpm_max = 0;
};

// Zhou et al. as fitted by Anziani: P = c1 + c2*n + c3*n^c4*MRR. Stored in the thesis's units
// (kW, rpm, mm^3/s) because that is how the constants are published.
struct ZhouConstants {
  double c1_kw = 0, c2_kw_per_rpm = 0, c3 = 0, c4 = 0;
  // SEC = d1*n^d2 + d3*n/MRR + d4/MRR (J/mm^3); optional second model.
  double d1 = 0, d2 = 0, d3 = 0, d4 = 0;
  // The spindle speeds and removal rates the constants were fitted on (0: not declared).
  // Outside them the model is extrapolated, and a warning says so.
  double fitted_rpm_min = 0, fitted_rpm_max = 0;
  double fitted_mrr_min_mm3_s = 0, fitted_mrr_max_mm3_s = 0;
};

// Where the cutting term of the combined (and Zhou) model comes from.
enum class CuttingTerm {
  Fitted,   // Zhou's c3 and c4 as the profile gives them (a machine's fit)
  Material, // the workpiece material: c3 = k_c / (1000 * efficiency), c4 = 0
};

enum class PowerModel { Combined, Pavanaskar, Zhou };

struct PowerConstants {
  PowerModel model = PowerModel::Combined;
  PavanaskarConstants pavanaskar;
  ZhouConstants zhou;
  double tool_change_w = 0; // power drawn during a tool change (above tare)
  CuttingTerm cutting_term = CuttingTerm::Fitted;
  std::string material; // default workpiece material (material term)
  std::optional<Material>
      profile_material; // a material the profile defines ([power.profile_material])
  std::optional<Material> cutting_material; // the material the cutting term is from (with_material)
  double cutting_efficiency = 0.8;          // power at the cutting edge / power drawn for it
  // What the cutting term's constants are, for headers ("fitted: Zhou et al. ... Anziani (2025)",
  // "material aluminium-alloy: k_c 0.53 J/mm^3, Kalpakjian & Schmid ..."); set on load and by
  // with_material().
  std::string cutting_source;
  // The spindle's rated power (W, at the spindle), and its curve against speed where known
  // (rpm, W pairs, in increasing rpm); 0 / empty: not given.
  double spindle_rated_w = 0;
  std::vector<std::pair<double, double>> spindle_power_curve;
  // The speed of a spindle the program does not command (a router's trim router or a VFD
  // spindle switched by hand): moves that remove material with no M3/M4 or S in force are
  // counted at it. 0: not known (their spindle and cutting energy are then not counted, and
  // a warning says so).
  double hand_spindle_rpm = 0;
  // The spindle's highest speed (0: not given): a program asking for more is warned about and
  // counted at it, as the control clamps the speed.
  double spindle_max_rpm = 0;
  // The rating and maximum speed stand in for a spindle the profile's source does not describe
  // (a seed machine fitted from published data): the warnings they raise say so.
  bool placeholder_spindle = false;
  double co2_kg_per_kwh = 0;
  double price_per_kwh = 0;
  // What an hour of the machine costs the shop besides its electricity (depreciation, floor
  // space, the operator: the machine-hour rate a quote is made with), in `currency`; 0: not
  // counted.
  double machine_rate_per_hour = 0;
  std::string currency = "EUR";
};

// The rated spindle power at a speed: the curve interpolated (its ends held), else the single
// rating; 0 when the profile gives none.
double rated_spindle_power_w(const PowerConstants& power, double rpm);

// What the load and top-speed warnings add when `placeholder_spindle` is set: why the figure is
// no prediction, and what to do instead.
inline constexpr const char* kPlaceholderSpindleAdvice =
    "(its source does not describe the spindle): use a profile of the machine the program was "
    "made for";

// The constants with the cutting term taken from `material` (c3 = k_c / (1000 * efficiency),
// c4 = 0, cutting_source saying so). Models whose cutting term is fitted are returned as they
// are, and `used` (when given) is set to false.
PowerConstants with_material(const PowerConstants& power, const Material& material,
                             bool* used = nullptr);

// Where the work sits in the machine ([setup] of a profile, work offsets of a job file): what a
// program that moves in machine coordinates (G53, G28/G30) needs to be placed.
struct WorkSetup {
  // Machine coordinates (mm) of each work offset's origin: 1..9 = G54..G59.3. Empty: not
  // described (the estimate then takes machine Z home to be above the work).
  std::map<int, Pose> work_offsets;
  // Machine travel (mm, machine coordinates) of X, Y, Z as (min, max); not given: unchecked.
  std::optional<std::array<std::pair<double, double>, 3>> travel;
  // Without work offsets: how far above the highest point a program reaches (and above its Z0)
  // machine Z home is taken to be.
  double z_home_above_work_mm = 100;
  // The units of a program that sets neither G20 nor G21, as the control is set at power-on
  // (Haas setting 9, Fanuc parameter 0000 INI); not given: mm, with a warning either way.
  std::optional<bool> power_on_inch;
  // How this shop's posts write G41/G42 when a program does not say (cutter_compensation =
  // "control" or "wear"): in control, the path is the part contour; in wear, the tool centre.
  std::optional<CutterCompMode> cutter_compensation;
  // Folders holding the programs the control has in its memory (O9xxx macros, probing cycles,
  // LinuxCNC subroutine files), searched when a program calls one it does not hold; relative
  // ones are taken from the profile's folder.
  std::vector<std::string> macro_dirs;
  // Without work offsets: where machine X/Y home (machine X0 Y0) lies in the program's work
  // coordinates, so that a G53 X/Y move or a G28 X/Y return goes there; not given: at work X0 Y0.
  std::optional<std::pair<double, double>> xy_home_in_work_mm;
  // Peck drilling's small moves as this machine's control is set (mm): how far above the last
  // peck G83 rapids back down, how far G73 backs off; not given: the dialect's.
  std::optional<double> peck_clearance_mm, chip_break_retract_mm;
};

// "G54" .. "G59", "G59.1" .. "G59.3" (any case) -> 1 .. 9; "G54.1 P1" .. "G54.1 P300" (Haas
// "G154 P1", G110 .. G129 = G154 P1 .. P20) -> 10 .. 309; 0 when the name is none of them.
int work_offset_index(std::string_view name);
// 1 .. 9 -> "G54" .. "G59.3", 10 .. 309 -> "G54.1 P1" ..; "G54" for anything else.
std::string work_offset_name(int index);

// One value of a profile as written: the file that gives it (the profile, or a base profile it
// starts from), its text and its line.
struct ProfileValue {
  std::string file;
  std::string text;
  int line = 0;
};

struct MachineProfile {
  std::string name;
  std::string source_path; // file it came from
  // The profiles it starts from (`base = "..."`), nearest first; empty for a whole profile.
  std::vector<std::string> base_paths;
  // Every value read, by dotted key ("power.material", "kinematics.x.rapid_mm_min"): which
  // file gives it, for the settings' sources and for errors.
  std::map<std::string, ProfileValue> values;
  bool by_default = false; // nothing named it: the generic profile stood in (said in headers)
  // One line on what the profile is and what its numbers rest on (`ncjoule profiles`).
  std::string summary;
  // What of the profile is an estimate for its class of machine, not a measurement of one
  // ("power", "timing", "rates"; `estimated = [...]`): the summaries say so.
  std::vector<std::string> estimated;
  std::string dialect; // controller dialect name (see gcode.hpp), or "auto": detected
  // With dialect "auto": the machine's own control, used when nothing in a program names one.
  std::string fallback_dialect;
  // The tool moves cut with where the program selects none and describes none ([default_tool]).
  std::optional<Tool> default_tool;
  Kinematics kinematics;
  WorkSetup setup;
  PowerConstants power;
  std::vector<std::string> sources; // where the constants come from, as written in the file
};

} // namespace ncjoule
