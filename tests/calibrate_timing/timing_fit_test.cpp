// The timing fit recovers the keys of the machine that made the logs, holds those the logs
// cannot tell, and writes a profile that loads.
#include "synthetic_log.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

// The machine the logs come from: the Hurco profile with other waits, settling, tool change and
// acceleration.
MachineProfile true_machine() {
  MachineProfile m = shipped_profile("hurco-vmx24");
  m.kinematics.tool_change_s = 4.0;
  m.kinematics.tool_change_first_extra_s = 1.0;
  m.kinematics.settle_s = 0.10;
  m.kinematics.waits.coolant_on_s = 3.0;
  m.kinematics.waits.optional_stop_s = 1.5;
  m.kinematics.waits.program_end_s = 2.0;
  for (AxisLimits& a : m.kinematics.axes)
    a.accel_mm_s2 = 4000;
  return m;
}

} // namespace

TEST_CASE("timing fit: the keys of the machine that made the logs come back") {
  const MachineProfile base = shipped_profile("hurco-vmx24");
  const MachineProfile truth = true_machine();
  LogEvidence evidence = synthetic_evidence(truth, base, 3, 0.03);
  judge_runs(evidence, plan_all(evidence, base));
  REQUIRE(evidence.program_runs.size() == 3);
  for (const LoggedRun& r : evidence.program_runs)
    CHECK(r.usable);
  TimingFitOptions options;
  options.min_stretch_s = 0; // every stretch on its own: the synthetic log has no noise to join
  const TimingFit fit = fit_timing(evidence, base, options);
  CHECK(fit.runs == 3);
  CHECK(fit.rms_after_s < 0.5 * fit.rms_before_s);
  CHECK(key_of(fit, TimingKey::ToolChange).fitted);
  CHECK(key_of(fit, TimingKey::ToolChange).value == doctest::Approx(4.0).epsilon(0.05));
  CHECK(key_of(fit, TimingKey::ToolChangeFirstExtra).value == doctest::Approx(1.0).epsilon(0.15));
  CHECK(key_of(fit, TimingKey::CoolantOn).value == doctest::Approx(3.0).epsilon(0.05));
  CHECK(key_of(fit, TimingKey::OptionalStop).value == doctest::Approx(1.5).epsilon(0.1));
  CHECK(key_of(fit, TimingKey::ProgramEnd).value == doctest::Approx(2.0).epsilon(0.1));
  CHECK(key_of(fit, TimingKey::Settle).value == doctest::Approx(0.10).epsilon(0.15));
  // The accelerations move from the base's 2.5 m/s^2 towards the 4 the logs were made with (a
  // weak prior holds them near the base where the moves tell little).
  CHECK(key_of(fit, TimingKey::AccelX).value > 2700);
  // No rapid of this program is long enough to reach the rapid rate: not in the logs.
  CHECK_FALSE(key_of(fit, TimingKey::RapidX).fitted);
  CHECK(key_of(fit, TimingKey::RapidX).why.find("no move reaches it") != std::string::npos);
  // The control does not wait for the spindle: the fitted wait is nothing, the base kept.
  CHECK_FALSE(key_of(fit, TimingKey::SpindleRamp).fitted);
  CHECK_FALSE(fit.spindle_waits);
  // Every fitted key has an uncertainty.
  for (const FittedTimingKey& f : fit.keys)
    if (f.fitted) CHECK(std::isfinite(f.std_error));
  // No M6 of the tool already in the spindle, no M6 with the spindle turning: not in the logs,
  // left as in the base.
  const FittedTimingKey& same = key_of(fit, TimingKey::ToolChangeSameTool);
  CHECK_FALSE(same.fitted);
  CHECK(same.value == same.base);
  CHECK(same.why.find("not in the logs") != std::string::npos);
  CHECK_FALSE(key_of(fit, TimingKey::ToolChangeSpindleStop).fitted);
  // The fitted machine times the runs as they were logged.
  const auto checks = check_programs(evidence, plan_all(evidence, fit.machine));
  REQUIRE(checks.size() == 1);
  CHECK(checks[0].predicted_s == doctest::Approx(checks[0].measured.median).epsilon(0.01));
}

// Helical bores as NIST's plate programs mill them (radius 0.0674 in at F110 in/min: 1.3 m/s^2
// centripetal, under the axes' 2.5), between lines at the same feed.
const char* kBoreProgram = R"(%
O0002(BORES)
N10 G20
N20 G0 G17 G40 G49 G80 G90
N30 T4 M6
N40 G0 G90 G54 X.6795 Y-1.7205 S12000 M3
N50 Z.25 M8
N60 Z.1
N70 G1 Z.01 F110.
N80 G3 X.5498 Z.0025 I-.0674 J0.
N90 X.6845 Z-.005 I.0673 J0.
N100 X.5498 Z-.0125 I-.0674 J0.
N110 X.6845 Z-.02 I.0673 J0.
N120 X.5498 Z-.0275 I-.0674 J0.
N130 X.6845 Z-.035 I.0673 J0.
N140 X.5498 Z-.0425 I-.0674 J0.
N150 X.6845 Z-.05 I.0673 J0.
N160 G1 X1.6845
N170 Y-1.2
N180 X.6845
N190 Y-1.7205
N200 G3 X.5498 Z-.0575 I-.0674 J0.
N210 X.6845 Z-.065 I.0673 J0.
N220 X.5498 Z-.0725 I-.0674 J0.
N230 X.6845 Z-.08 I.0673 J0.
N240 X.5498 Z-.0875 I-.0674 J0.
N250 X.6845 Z-.095 I.0673 J0.
N260 G0 Z.25
N270 X2. Y-1.
N280 G1 Z-.05 F110.
N290 X3.
N300 Y0.
N310 X2.
N320 Y-1.
N330 G0 Z.25
N340 M5
N350 G91 G28 Z0. M9
N360 M30
%
)";

TEST_CASE("timing fit: a control that holds small arcs slower than its axes' acceleration") {
  const MachineProfile base = shipped_profile("hurco-vmx24");
  MachineProfile truth = base;
  truth.kinematics.arc_accel_mm_s2 = 700; // 0.7 m/s^2: the bores run at 34.3 mm/s, not 46.6
  LogEvidence evidence = synthetic_evidence(truth, base, 3, 0.01, -1, kBoreProgram);
  judge_runs(evidence, plan_all(evidence, base));
  TimingFitOptions options;
  options.min_stretch_s = 0;
  const TimingFit fit = fit_timing(evidence, base, options);
  const FittedTimingKey& arc = key_of(fit, TimingKey::ArcAccel);
  CHECK(arc.base == doctest::Approx(2500)); // not given: the XY axes' acceleration
  INFO(arc.why);
  REQUIRE(arc.fitted);
  CHECK(arc.value == doctest::Approx(700).epsilon(0.1));
  // The lines at the same feed keep the axes' acceleration: the arcs' slowness is not spread
  // over every move.
  CHECK(key_of(fit, TimingKey::AccelX).value > 2000);
  const auto checks = check_programs(evidence, plan_all(evidence, fit.machine));
  REQUIRE(checks.size() == 1);
  CHECK(checks[0].predicted_s == doctest::Approx(checks[0].measured.median).epsilon(0.01));
}

TEST_CASE("timing fit: arcs run as the axes allow leave the arc acceleration unset") {
  const MachineProfile base = shipped_profile("hurco-vmx24");
  LogEvidence evidence = synthetic_evidence(base, base, 3, 0.01, -1, kBoreProgram);
  judge_runs(evidence, plan_all(evidence, base));
  TimingFitOptions options;
  options.min_stretch_s = 0;
  const TimingFit fit = fit_timing(evidence, base, options);
  const FittedTimingKey& arc = key_of(fit, TimingKey::ArcAccel);
  CHECK_FALSE(arc.fitted);
  CHECK(arc.why.find("no arc in these logs ran slower") != std::string::npos);
  CHECK_FALSE(fit.machine.kinematics.arc_accel_mm_s2.has_value());
}

TEST_CASE("timing fit: with no usable run nothing is fitted, and it says so") {
  const MachineProfile base = shipped_profile("hurco-vmx24");
  LogEvidence evidence = synthetic_evidence(base, base, 1, 0);
  for (LoggedRun& r : evidence.program_runs)
    r.usable = false;
  const TimingFit fit = fit_timing(evidence, base);
  CHECK(fit.stretches == 0);
  CHECK(fit.message.find("no usable run") != std::string::npos);
  for (const FittedTimingKey& f : fit.keys)
    CHECK_FALSE(f.fitted);
}

TEST_CASE("calibrated profile: fitted keys in place of the base's, the rest as it was") {
  const std::string base_path =
      std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/hurco-vmx24.toml";
  std::vector<Diagnostic> d;
  const auto base_text = read_text_file(base_path, "a profile", d);
  REQUIRE(base_text);
  const MachineProfile base = parse_profile(*base_text, base_path);
  LogEvidence evidence = synthetic_evidence(true_machine(), base, 2, 0.02);
  judge_runs(evidence, plan_all(evidence, base));
  TimingFitOptions options;
  options.min_stretch_s = 0;
  const TimingFit fit = fit_timing(evidence, base, options);
  CalibratedProfileInfo info;
  info.name = "Our VMX24 (synthetic)";
  info.machine = "mill-7";
  info.date = "2020-03-02";
  info.data = {"log synthetic.shdr"};
  SpindleRunUp run_up;
  run_up.points = {{1000, 0.2}, {2000, 0.4}};
  run_up.run_ups = 4;
  const auto text = calibrated_profile_text(*base_text, base_path, fit, run_up, info, d);
  REQUIRE(text);
  CHECK(text->find("calibrated by ncjoule calibrate --timing on 2020-03-02 for mill-7") !=
        std::string::npos);
  CHECK(text->find("#   log synthetic.shdr") != std::string::npos);
  CHECK(text->find("tool_change_same_tool_s: not in the logs") != std::string::npos);
  CHECK(text->find("\ntool_change_s = 6.0") == std::string::npos); // the base's value is gone
  CHECK(text->find("base: tool_change_s = 6.0") != std::string::npos);
  // Comments of the base the fit does not concern stay.
  CHECK(text->find("# data sheet: 24 hp peak") != std::string::npos);
  const MachineProfile out = parse_profile(*text, "out.toml");
  CHECK(out.name == "Our VMX24 (synthetic)");
  CHECK(out.kinematics.tool_change_s ==
        doctest::Approx(key_of(fit, TimingKey::ToolChange).value).epsilon(1e-3));
  CHECK(out.kinematics.waits.coolant_on_s ==
        doctest::Approx(key_of(fit, TimingKey::CoolantOn).value).epsilon(1e-3));
  // The path does not wait for the spindle: the measured run-up is written.
  REQUIRE(out.kinematics.spindle_run_up.size() == 2);
  CHECK(out.kinematics.spindle_run_up[1].first == 2000);
}

TEST_CASE("timing fit: runs of two kinds (a wait set otherwise between them) are said, not "
          "silently averaged") {
  // Two runs that stop 1.5 s at M1, two that stop 6 s (the control's setting changed between
  // them): one value fits neither kind, and the note names the runs of each.
  const MachineProfile base = shipped_profile("hurco-vmx24");
  MachineProfile short_wait = true_machine(), long_wait = true_machine();
  long_wait.kinematics.waits.optional_stop_s = 6.0;
  LogEvidence evidence =
      synthetic_evidence_of({short_wait, long_wait, short_wait, long_wait}, base, 0.03);
  judge_runs(evidence, plan_all(evidence, base));
  TimingFitOptions options;
  options.min_stretch_s = 0;
  const TimingFit fit = fit_timing(evidence, base, options);
  REQUIRE(fit.runs == 4);
  std::string said;
  for (const std::string& n : fit.notes)
    if (n.find("the runs disagree") != std::string::npos) said += n + "\n";
  CAPTURE(said);
  CHECK(said.find("kinematics.waits.optional_stop_s") != std::string::npos);
  CHECK(said.find("runs 1, 3 and") != std::string::npos); // the short-wait runs first
  CHECK(said.find("runs 2, 4;") != std::string::npos);
  CHECK(said.find("coolant_on") == std::string::npos); // the keys they agree on: nothing

  // Runs of one kind: no note.
  LogEvidence same = synthetic_evidence(short_wait, base, 4, 0.03);
  judge_runs(same, plan_all(same, base));
  const TimingFit agreed = fit_timing(same, base, options);
  for (const std::string& n : agreed.notes)
    CHECK(n.find("the runs disagree") == std::string::npos);
}
