#include "calibrate_timing_cli.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <set>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "ncjoule/profile.hpp"
#include "ncjoule/text_file.hpp"
#include "output_file.hpp"

namespace ncjoule::cli {
namespace {

std::string today() {
  const std::time_t now = std::time(nullptr);
  return format_log_time(double(now)).substr(0, 10);
}

void print_fit(const TimingFit& fit) {
  std::printf("timing fit: %zu stretches of %zu usable runs; rms %.3f s per stretch with the "
              "base profile, %.3f s fitted%s%s\n",
              fit.stretches, fit.runs, fit.rms_before_s, fit.rms_after_s,
              fit.converged ? "" : " (did not converge)",
              fit.message.empty() ? "" : (" -- " + printable(fit.message)).c_str());
  // Notes and names quote the logs and the programs (a program's name, a block's text): escaped.
  for (const std::string& n : fit.notes)
    std::printf("  note: %s\n", printable(n).c_str());
  for (const FittedTimingKey& f : fit.keys) {
    const TimingKeyInfo& info = timing_key_info(f.key);
    const std::string name = timing_key_name(f.key);
    if (f.fitted)
      std::printf("  %-42s %12.5g +- %-9.2g (base %.5g)\n", name.c_str(), f.value * info.to_unit,
                  f.std_error * info.to_unit, f.base * info.to_unit);
    else
      std::printf("  %-42s %12.5g  left as in the base: %s\n", name.c_str(), f.base * info.to_unit,
                  printable(f.why).c_str());
  }
}

void print_totals(const LogEvidence& e, const std::vector<ProgramCheck>& before,
                  const std::vector<ProgramCheck>& after) {
  std::printf("programs (median of the usable runs)\n");
  std::printf("  %-40s %5s %12s %14s %8s %14s %8s\n", "program", "runs", "measured s",
              "base profile s", "error", "calibrated s", "error");
  auto err = [](double p, double m) {
    char text[32];
    std::snprintf(text, sizeof text, "%+.1f%%", m > 0 ? 100 * (p - m) / m : 0.0);
    return std::string(text);
  };
  for (std::size_t i = 0; i < before.size(); ++i) {
    const ProgramCheck& b = before[i];
    if (b.usable_runs == 0) continue;
    std::string name = printable(e.programs[b.program].outline.name);
    if (name.size() > 40) name = name.substr(0, 37) + "...";
    std::printf("  %-40s %5zu %12.1f %14.1f %8s %14.1f %8s\n", name.c_str(), b.usable_runs,
                b.measured.median, b.predicted_s, err(b.predicted_s, b.measured.median).c_str(),
                after[i].predicted_s, err(after[i].predicted_s, b.measured.median).c_str());
  }
}

// The power model, where a usable run logged the machine's power (or its spindle load with the
// spindle's rating in the profile): fitted through the power-log fit of calibrate.hpp.
std::optional<PowerConstants> fit_logged_power(const LogEvidence& e, const MachineProfile& machine,
                                               std::string& source) {
  for (const LoggedRun& r : e.program_runs) {
    if (!r.usable) continue;
    const auto log = run_power_log(e, r, machine.power.spindle_rated_w);
    if (!log) continue;
    const LoggedProgram& p = e.programs[r.program];
    EstimateOptions options = p.options;
    options.simulate_removal = true;
    options.keep_trace = true;
    const Estimate traced = estimate_program(p.source, machine, options);
    if (traced.failed) continue;
    LogFitOptions fit_options;
    fit_options.max_offset_s = 5; // the log is the run itself: its start is the program's
    const bool spindle_only = e.runs[r.run].power.empty();
    PowerConstants initial = machine.power;
    if (spindle_only) {
      // A spindle load is the spindle's power alone: the machine's other terms are not in it.
      initial.pavanaskar.tare_w = 0;
      initial.pavanaskar.coolant_w = 0;
      initial.pavanaskar.move_ka_w = {};
      initial.pavanaskar.move_kb_w_per_mm_s = {};
      fit_options.hold = {PowerParameter::Tare, PowerParameter::Coolant};
    }
    const LogFitResult fit = fit_power_log(*log, traced.trace, initial, fit_options);
    if (fit.report.points == 0) continue;
    std::printf("power fit on run of %s at %s (%s):\n", printable(p.outline.name).c_str(),
                format_log_time(e.runs[r.run].start_s).c_str(),
                spindle_only ? "spindle load x the spindle's rating" : "logged electrical power");
    std::printf("  %zu samples, RMSE %.1f W, R^2 %.4f\n", fit.report.points, fit.report.rmse,
                fit.report.r_squared);
    for (const std::string& n : fit.notes)
      std::printf("  note: %s\n", printable(n).c_str());
    PowerConstants out = machine.power;
    if (spindle_only) {
      apply_fit(out, fit.report); // only the spindle and cutting terms it fitted
    } else {
      out = fit.constants;
    }
    source = "fitted from the logged " + std::string(spindle_only ? "spindle load" : "power") +
             " of a run of " + p.outline.name + " (" + format_log_time(e.runs[r.run].start_s) + ")";
    return out;
  }
  return std::nullopt;
}

} // namespace

void add_timing_options(CLI::App& cmd, TimingCalibrationOptions& o) {
  cmd.add_flag("--timing", o.on,
               "Fit the timing keys of the base profile (-m) to the controller's MTConnect logs "
               "(--log: SHDR or Streams XML) of the programs it ran (--program, repeatable)");
  add_log_options(cmd, o.logs);
}

int run_timing_calibration(const TimingCalibrationOptions& o) {
  if (o.machine.empty() || o.programs.empty() || o.logs.logs.empty()) {
    std::fprintf(stderr, "ncjoule: --timing needs the base profile (-m PROFILE.toml), the "
                         "programs (--program) and the logs (--log)\n");
    return kUsage;
  }
  std::vector<Diagnostic> problems;
  const auto base_text = read_text_file(o.machine, "a machine profile (.toml)", problems);
  if (!base_text) {
    print_diagnostics(problems);
    return kInputError;
  }
  MachineProfile base;
  try {
    base = parse_profile(*base_text, o.machine);
  } catch (const ProfileError& e) {
    print_diagnostics({e.diagnostic()});
    return kInputError;
  }
  EstimateOptions options;
  if (!o.dialect.empty()) {
    options.dialect = dialect_from_option(o.dialect);
    if (!options.dialect) return kUsage;
  }
  LogEvidence evidence;
  std::vector<LineTimes> times;
  if (const int status = read_evidence(o.logs, o.programs, options, base, evidence, times);
      status != kOk)
    return status;
  print_log_summary(evidence);
  print_run_table(evidence);
  const std::size_t usable =
      std::size_t(std::count_if(evidence.program_runs.begin(), evidence.program_runs.end(),
                                [](const LoggedRun& r) { return r.usable; }));
  if (usable == 0) {
    std::fprintf(stderr, "ncjoule: no usable run of the programs given in the logs (see the "
                         "table above): nothing to fit, nothing written\n");
    return kInputError;
  }
  const auto before = check_programs(evidence, times);
  const TimingFit fit = fit_timing(evidence, base);
  print_fit(fit);
  const SpindleRunUp run_up = measure_spindle_run_up(evidence);
  if (!run_up.points.empty())
    std::printf("spindle run-up: %zu run-ups from rest, %.0f rpm/s to the top; to %g rpm in "
                "%.2f s\n",
                run_up.run_ups, run_up.rpm_per_s, run_up.points.back().first,
                run_up.points.back().second);
  std::vector<LineTimes> fitted_times = times;
  for (std::size_t p = 0; p < evidence.programs.size(); ++p)
    fitted_times[p] =
        plan_line_times(evidence.programs[p], fit.machine, needs_rapid_override(evidence, p));
  print_totals(evidence, before, check_programs(evidence, fitted_times));

  // The calibrated profile: what it is, of which machine, when, from what.
  CalibratedProfileInfo info;
  std::set<std::string> devices;
  std::map<std::string, std::pair<std::size_t, std::size_t>> per_program; // usable, all
  for (const LoggedRun& r : evidence.program_runs) {
    const std::string& d = evidence.log.devices[evidence.runs[r.run].device];
    if (r.usable && !d.empty()) devices.insert(d);
    auto& count = per_program[evidence.programs[r.program].outline.name];
    count.first += r.usable;
    ++count.second;
  }
  for (const std::string& d : devices)
    info.machine += (info.machine.empty() ? "" : ", ") + d;
  info.date = today();
  info.name = !o.name.empty()
                  ? o.name
                  : base.name + (info.machine.empty() ? "" : " (" + info.machine + ")") +
                        ", calibrated " + info.date;
  for (const ControllerLog::File& f : evidence.log.files)
    info.data.push_back("log " + f.path + " (" + f.format + ", " + format_log_time(f.first_s) +
                        " to " + format_log_time(f.last_s) + ")");
  for (const auto& [name, count] : per_program)
    info.data.push_back("program " + name + ": " + std::to_string(count.first) + " usable run" +
                        (count.first == 1 ? "" : "s") + " of " + std::to_string(count.second));
  auto text = calibrated_profile_text(*base_text, o.machine, fit, run_up, info, problems);
  if (!text) {
    print_diagnostics(problems);
    return kInputError;
  }
  std::string power_source;
  if (const auto power = fit_logged_power(evidence, fit.machine, power_source)) {
    std::vector<Diagnostic> power_problems;
    auto with_power =
        profile_with_power(*text, o.machine, "", *power, {}, power_source, power_problems);
    if (with_power) {
      text = with_power;
    } else {
      // The timing stands on its own: a power fit the profile cannot take is said and left out.
      for (Diagnostic& d : power_problems)
        d.severity = Severity::Warning;
      print_diagnostics(power_problems);
      std::fprintf(stderr, "ncjoule: the power fit is left out of %s; its timing is written\n",
                   o.output.c_str());
    }
  }
  const std::string error = write_output_file(
      o.output, "# Machine profile written by ncjoule calibrate --timing.\n" + *text);
  if (!error.empty()) {
    std::fprintf(stderr, "ncjoule: %s; nothing was written\n", error.c_str());
    return kOutputError;
  }
  std::printf("wrote %s (%s)\n", printable(o.output).c_str(), printable(info.name).c_str());
  return kOk;
}

} // namespace ncjoule::cli
