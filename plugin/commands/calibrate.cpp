// `ncjoule calibrate`: fits a machine's power constants from steady-state tables and from a
// time-stamped power log of a known program, prints each constant with its standard error and
// each fit's RMSE and R^2, and writes a new profile with the fitted values and their sources.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "calibrate_timing_cli.hpp"
#include "cli_support.hpp"
#include "command_registry.hpp"
#include "ncjoule/calibrate.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"
#include "ncjoule/text_file.hpp"
#include "output_file.hpp"

namespace ncjoule::cli {
namespace {

struct CalibrateCliOptions {
  std::string machine;
  std::string model;
  std::string name;
  std::string output;
  double tare_w = -1;
  double coolant_w = -1;
  double tool_change_w = -1;
  std::optional<double> baseline_w; // subtracted from the spindle and axis tables instead of tare
  std::string spindle;
  std::string axis[3];
  std::string cut[3];
  std::string zhou;
  std::string log;
  std::string program;
  std::vector<std::string> logs, programs; // as given: one each, or several with --timing
  TimingCalibrationOptions timing;
  std::string stock;   // as estimate's --stock
  std::string dialect; // as estimate's --dialect
  double max_offset_s = 60;
  std::string loss = "huber";
};

void print_report(const FitReport& fit) {
  // `what` names the user's file, and a message may quote it: escaped (printable).
  std::printf("%s: %zu points, RMSE %.6g, R^2 %.5f%s%s\n", printable(fit.what).c_str(), fit.points,
              fit.rmse, fit.r_squared, fit.converged ? "" : " (did not converge)",
              fit.message.empty() ? "" : (" -- " + printable(fit.message)).c_str());
  for (const FittedConstant& c : fit.constants) {
    const auto& info = parameter_info(c.parameter);
    if (c.held)
      std::printf("  %-36s %14.6g %-18s (held)\n", std::string(info.key).c_str(), c.value,
                  std::string(info.unit).c_str());
    else
      std::printf("  %-36s %14.6g +- %-10.3g %s\n", std::string(info.key).c_str(), c.value,
                  c.std_error, std::string(info.unit).c_str());
  }
}

// Reads a steady-state table; nullopt (with the reasons printed) when it is unusable.
std::optional<std::vector<SteadyStateReading>> read_table(const std::string& path,
                                                          unsigned required) {
  std::vector<Diagnostic> diagnostics;
  auto csv = read_numeric_csv(path, diagnostics);
  std::vector<SteadyStateReading> readings;
  if (csv) readings = readings_from_csv(*csv, required, diagnostics);
  print_diagnostics(diagnostics);
  for (const Diagnostic& d : diagnostics)
    if (d.severity == Severity::Error) return std::nullopt;
  return readings;
}

std::string note_for(const FitReport& fit, const FittedConstant& c, const std::string& file) {
  char text[256];
  std::snprintf(text, sizeof text, "fitted from %s: +- %.3g (1 SE), %zu points, R^2 %.4f",
                printable(file).c_str(), c.std_error, fit.points, fit.r_squared);
  return text;
}

// What the fits have produced so far: the constants, the source of each, and the files used.
struct Calibration {
  PowerConstants constants;
  std::map<PowerParameter, std::string> notes;
  std::vector<std::string> fitted_files;
  bool fitted_any = false;

  // False, with the reason said, when the data could not be fitted at all.
  bool use(const FitReport& fit, const std::string& file, const std::string& how = "") {
    if (!fit.refused.empty()) {
      std::fprintf(stderr, "%s: error: %s: nothing fitted: %s\n", file.c_str(), fit.what.c_str(),
                   fit.refused.c_str());
      return false;
    }
    print_report(fit);
    apply_fit(constants, fit);
    for (const FittedConstant& c : fit.constants) {
      if (c.held) continue;
      notes[c.parameter] = note_for(fit, c, file + how);
      // A fitted cutting term is what cuts from now on, not the material's.
      if (c.parameter == PowerParameter::ZhouC3 || c.parameter == PowerParameter::ZhouC4)
        constants.cutting_term = CuttingTerm::Fitted;
    }
    fitted_files.push_back(fit.what + " from " + file);
    fitted_any = true;
    return true;
  }
};

std::optional<RobustLoss> loss_from_name(const std::string& name) {
  if (name == "huber") return RobustLoss::Huber;
  if (name == "cauchy") return RobustLoss::Cauchy;
  if (name == "none") return RobustLoss::None;
  return std::nullopt;
}

// The log fit: runs the program through the whole pipeline on the machine (tools from its
// header comments, the stock as estimate takes it), builds its operating trace, finds the time
// offset between log and program, and fits the model's constants to the whole trace.
int fit_from_log(const CalibrateCliOptions& o, MachineProfile machine, Calibration& calibration) {
  if (o.program.empty() || o.machine.empty()) {
    std::fprintf(stderr, "--log needs --program (the program the log recorded) and --machine "
                         "(the machine it ran on: its kinematics time the program)\n");
    return kUsage;
  }
  const auto loss = loss_from_name(o.loss);
  if (!loss) {
    std::fprintf(stderr, "--loss must be huber, cauchy or none\n");
    return kUsage;
  }
  EstimateOptions options;
  if (!o.dialect.empty()) {
    options.dialect = dialect_from_option(o.dialect);
    if (!options.dialect) return kUsage;
  }
  if (!o.stock.empty()) {
    std::vector<Diagnostic> problems;
    options.stock = parse_stock_spec(o.stock, &problems, TextOrigin{"--stock '" + o.stock + "'"});
    if (!options.stock) {
      print_diagnostics(problems);
      return kUsage;
    }
  }
  std::vector<Diagnostic> diagnostics;
  const auto log = read_power_log(o.log, diagnostics);
  print_diagnostics(diagnostics);
  if (!log) return kInputError;
  for (const Diagnostic& d : diagnostics)
    if (d.severity == Severity::Error) return kInputError;

  const auto source = read_source(o.program);
  if (!source) return kInputError;
  // The trace depends only on the machine's kinematics; the constants fitted so far are the
  // starting point of the fit.
  machine.power = calibration.constants;
  EstimateOptions traced = options;
  traced.keep_trace = true; // the fit compares the log with the whole operating trace
  const Estimate e = estimate_program(*source, machine, traced);
  print_diagnostics(e.diagnostics, e.diagnostics_dropped);
  bool program_errors = e.failed;
  for (const Diagnostic& d : e.diagnostics)
    program_errors = program_errors || d.severity == Severity::Error;
  if (program_errors) {
    std::fprintf(stderr,
                 "%s: cannot be run on the model (see above); define the tools in the "
                 "program's header comments and give the stock with --stock\n",
                 o.program.c_str());
    return e.budget_exceeded ? kBudgetExceeded : kInputError;
  }
  const std::vector<OperatingSegment>& trace = e.trace;

  LogFitOptions fit_options;
  fit_options.max_offset_s = o.max_offset_s;
  fit_options.loss = *loss;
  const LogFitResult fit = fit_power_log(*log, trace, calibration.constants, fit_options);
  if (fit.report.points == 0 || !fit.report.refused.empty() ||
      (!fit.report.converged && !fit.report.message.empty())) {
    std::fprintf(stderr, "%s: the log fit failed: %s\n", o.log.c_str(),
                 (fit.report.refused.empty() ? fit.report.message : fit.report.refused).c_str());
    return kInputError;
  }
  std::printf("%s: %zu samples over %.1f s; %s runs %.1f s on %s\n", printable(o.log).c_str(),
              log->t_s.size(), log->t_s.back() - log->t_s.front(), printable(o.program).c_str(),
              e.time_s, printable(machine.name).c_str());
  std::printf("time offset: the program starts %.3f s into the log\n", fit.offset_s);
  for (const std::string& note : fit.notes)
    std::printf("  note: %s\n", printable(note).c_str());
  char how[160];
  std::snprintf(how, sizeof how, " (program %s, offset %.3f s, %s loss)",
                printable(o.program).c_str(), fit.offset_s, o.loss.c_str());
  calibration.constants = fit.constants; // the fitted values, and the exponent where held
  calibration.use(fit.report, o.log, how);
  return kOk;
}

// The profile goes through the one output writer: a failure leaves no half-written profile.
int write_profile(const std::string& output, const std::string& text) {
  const std::string error =
      write_output_file(output, "# Machine profile written by ncjoule calibrate.\n" + text);
  if (error.empty()) return kOk;
  std::fprintf(stderr, "ncjoule: %s; nothing was written\n", error.c_str());
  return kOutputError;
}

int run_calibrate(const CalibrateCliOptions& o) {
  Calibration calibration;
  PowerConstants& constants = calibration.constants;
  MachineProfile machine;
  std::string base_text;
  if (!o.machine.empty()) {
    std::vector<Diagnostic> problems;
    auto text = read_text_file(o.machine, "a machine profile (.toml)", problems);
    if (!text) {
      print_diagnostics(problems);
      return kInputError;
    }
    base_text = *text;
    try {
      machine = parse_profile(base_text, o.machine);
    } catch (const ProfileError& e) {
      print_diagnostics({e.diagnostic()});
      return kInputError;
    }
    constants = machine.power;
  }
  if (!o.model.empty()) {
    auto model = model_from_name(o.model);
    if (!model) {
      std::fprintf(stderr, "--model must be combined, pavanaskar or zhou\n");
      return kUsage;
    }
    constants.model = *model;
  }
  auto given = [&](PowerParameter p, double value, const char* option) {
    set_parameter(constants, p, value);
    calibration.notes[p] = std::string("given on the command line (") + option + ")";
  };
  if (o.tare_w >= 0) given(PowerParameter::Tare, o.tare_w, "--tare-w");
  if (o.coolant_w >= 0) given(PowerParameter::Coolant, o.coolant_w, "--coolant-w");
  if (o.tool_change_w >= 0) given(PowerParameter::ToolChange, o.tool_change_w, "--tool-change-w");

  // The state the spindle and axis readings are taken above: the tare unless --baseline-w
  // names another (Pavanaskar subtracted a 375 W starting state, not his 325 W constant power).
  const double baseline_w = o.baseline_w.value_or(constants.pavanaskar.tare_w);
  std::string above;
  if (o.baseline_w) {
    char text[96];
    std::snprintf(text, sizeof text, " above a baseline of %g W (--baseline-w)", *o.baseline_w);
    above = text;
  }
  auto with_baseline = [&] {
    PowerConstants known = constants;
    known.pavanaskar.tare_w = baseline_w;
    return known;
  };
  if (!o.spindle.empty()) {
    auto t = read_table(o.spindle, kFieldRpm);
    if (!t) return kInputError;
    if (!calibration.use(fit_spindle(*t, baseline_w), o.spindle, above)) return kInputError;
  }
  for (int i = 0; i < 3; ++i) {
    if (o.axis[i].empty()) continue;
    auto t = read_table(o.axis[i], kFieldFeed);
    if (!t) return kInputError;
    if (!calibration.use(fit_axis_move(*t, static_cast<Axis>(i), with_baseline()), o.axis[i],
                         above))
      return kInputError;
  }
  for (int i = 0; i < 3; ++i) {
    if (o.cut[i].empty()) continue;
    auto t = read_table(o.cut[i], kFieldRpm | kFieldFeed | kFieldMrr);
    if (!t) return kInputError;
    if (!calibration.use(fit_axis_cut(*t, static_cast<Axis>(i), with_baseline()), o.cut[i], above))
      return kInputError;
  }
  if (!o.zhou.empty()) {
    auto t = read_table(o.zhou, kFieldRpm | kFieldMrr);
    if (!t) return kInputError;
    if (!calibration.use(fit_zhou_power(*t), o.zhou) || !calibration.use(fit_zhou_sec(*t), o.zhou))
      return kInputError;
    set_zhou_fitted_ranges(constants.zhou, *t);
  }
  if (!o.log.empty()) {
    if (const int status = fit_from_log(o, machine, calibration); status != kOk) return status;
  }
  if (!calibration.fitted_any) {
    std::fprintf(stderr, "nothing to fit: give at least one of --spindle, --axis-x/y/z, "
                         "--cut-x/y/z, --zhou, --log (see --help)\n");
    return kUsage;
  }
  const std::string name =
      !o.name.empty() ? o.name : std::filesystem::path(o.output).stem().string();
  std::string source = "ncjoule calibrate:";
  for (std::size_t i = 0; i < calibration.fitted_files.size(); ++i)
    source += (i ? "; " : " ") + calibration.fitted_files[i];
  if (!o.machine.empty()) source += "; other constants from " + o.machine;
  std::vector<Diagnostic> problems;
  auto text = profile_with_power(base_text, o.machine, name, constants, calibration.notes, source,
                                 problems);
  if (!text) {
    print_diagnostics(problems);
    return kInputError;
  }
  if (const int status = write_profile(o.output, *text); status != kOk) return status;
  std::printf("wrote %s (model %s)\n", printable(o.output).c_str(),
              std::string(model_name(constants.model)).c_str());
  return kOk;
}

const Registration registration([](CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CalibrateCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate",
      "Fit a machine's power constants from measurements and write a new profile.\n"
      "Tables are CSV files with a header; units are in the column names: rpm, feed_mm_min | "
      "feed_mm_s | feed_ipm, mrr_mm3_s | mrr_mm3_min, power_w | power_kw (whole-machine power "
      "in a steady state).");
  cmd->add_option("-m,--machine", o->machine,
                  "Base profile (TOML): its other sections and power constants are kept, and "
                  "the fitted ones replace theirs")
      ->check(CLI::ExistingFile);
  cmd->add_option("--model", o->model,
                  "Power model of the new profile: combined, pavanaskar, zhou");
  cmd->add_option("--name", o->name, "Machine name in the new profile (default: output file name)");
  cmd->add_option("--tare-w", o->tare_w,
                  "Power with the machine on and idle, spindle off (W), written to the profile; "
                  "subtracted from the spindle and axis tables unless --baseline-w is given")
      ->check(CLI::Range(0.0, 1e6)); // W, up to 1 MW
  cmd->add_option("--baseline-w", o->baseline_w,
                  "Power state the spindle and axis table readings are taken above (W), e.g. "
                  "Pavanaskar's 375 W starting state; default: the tare. Not written to the "
                  "profile")
      ->check(CLI::Range(0.0, 1e6)); // W, up to 1 MW
  cmd->add_option("--coolant-w", o->coolant_w, "Coolant pump power (W)")
      ->check(CLI::Range(0.0, 1e6)); // W, up to 1 MW
  cmd->add_option("--tool-change-w", o->tool_change_w, "Power above tare during a tool change (W)")
      ->check(CLI::Range(0.0, 1e6)); // W, up to 1 MW
  cmd->add_option("--spindle", o->spindle,
                  "Spindle table: rpm, power -> KA_spindle + KB_spindle * n above tare")
      ->check(CLI::ExistingFile);
  const char* axes = "xyz";
  for (int i = 0; i < 3; ++i) {
    cmd->add_option(std::string("--axis-") + axes[i], o->axis[i],
                    std::string("Axis ") + static_cast<char>('X' + i) +
                        " moving alone: feed, power [, rpm] -> KA_move + KB_move * F")
        ->check(CLI::ExistingFile);
    cmd->add_option(std::string("--cut-") + axes[i], o->cut[i],
                    std::string("Cuts along ") + static_cast<char>('X' + i) +
                        ": rpm, feed, mrr, power -> KA_cut + KB_cut * MRR (Pavanaskar)")
        ->check(CLI::ExistingFile);
  }
  cmd->add_option("--zhou", o->zhou,
                  "Cutting table: rpm, mrr, power -> Zhou's c1..c4 (all >= 0) and the SEC "
                  "model's d1..d4")
      ->check(CLI::ExistingFile);
  auto* log = cmd->add_option("--log", o->logs,
                              "Power log (time_s, power_w) of a run of --program on --machine; "
                              "with --timing, the controller's MTConnect logs (repeatable)")
                  ->check(CLI::ExistingFile);
  auto* program = cmd->add_option("--program", o->programs,
                                  "NC program the log recorded (with --timing: repeatable)")
                      ->check(CLI::ExistingFile)
                      ->needs(log);
  log->needs(program);
  cmd->add_option("--stock", o->stock,
                  "Stock of the logged run: box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (mm) or an STL "
                  "file; default: the bounding box of the cutting moves")
      ->needs(log);
  cmd->add_option("--dialect", o->dialect,
                  "Controller dialect of --program; default: the machine profile's")
      ->needs(log);
  cmd->add_option("--max-offset", o->max_offset_s,
                  "Search the time offset between log and program within +- S seconds "
                  "(default 60)")
      ->check(CLI::PositiveNumber)
      ->needs(log);
  cmd->add_option("--loss", o->loss, "Robust loss of the log fit: huber (default), cauchy or none")
      ->check(CLI::IsMember({"huber", "cauchy", "none"}))
      ->needs(log);
  cmd->add_option("-o,--output", o->output, "New profile (TOML) to write")->required();
  add_timing_options(*cmd, o->timing);
  cmd->callback([o, &exit_code] {
    if (o->timing.on) {
      TimingCalibrationOptions t = o->timing;
      t.logs.logs = o->logs;
      t.programs = o->programs;
      t.machine = o->machine;
      t.name = o->name;
      t.output = o->output;
      t.dialect = o->dialect;
      exit_code = run_timing_calibration(t);
      return;
    }
    if (o->logs.size() > 1 || o->programs.size() > 1) {
      std::fprintf(stderr, "one --log and one --program (several only with --timing)\n");
      exit_code = kUsage;
      return;
    }
    o->log = o->logs.empty() ? "" : o->logs.front();
    o->program = o->programs.empty() ? "" : o->programs.front();
    exit_code = run_calibrate(*o);
  });
});

} // namespace
} // namespace ncjoule::cli
