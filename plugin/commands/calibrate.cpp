// `ncjoule calibrate`: fits a machine's power constants from steady-state tables (and, once
// the planner and removal stages can run a program here, from a power log), prints each
// constant with its standard error and each fit's RMSE and R^2, and writes a new profile.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "ncjoule/calibrate.hpp"
#include "ncjoule/profile.hpp"

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
  std::string spindle;
  std::string axis[3];
  std::string cut[3];
  std::string zhou;
  std::string log;
  std::string program;
};

std::optional<std::string> read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void print_report(const FitReport& fit) {
  std::printf("%s: %zu points, RMSE %.6g, R^2 %.5f%s%s\n", fit.what.c_str(), fit.points, fit.rmse,
              fit.r_squared, fit.converged ? "" : " (did not converge)",
              fit.message.empty() ? "" : (" -- " + fit.message).c_str());
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
                file.c_str(), c.std_error, fit.points, fit.r_squared);
  return text;
}

int run_calibrate(const CalibrateCliOptions& o) {
  PowerConstants constants;
  std::string base_text;
  if (!o.machine.empty()) {
    auto text = read_text(o.machine);
    if (!text) {
      std::fprintf(stderr, "%s: cannot read the machine profile\n", o.machine.c_str());
      return kInputError;
    }
    base_text = *text;
    try {
      constants = parse_profile(base_text, o.machine).power;
    } catch (const ProfileError& e) {
      std::fprintf(stderr, "%s: %s%s%s\n", e.file().c_str(), e.key().c_str(),
                   e.key().empty() ? "" : ": ", e.reason().c_str());
      return kInputError;
    }
  }
  if (!o.model.empty()) {
    auto model = model_from_name(o.model);
    if (!model) {
      std::fprintf(stderr, "--model must be combined, pavanaskar or zhou\n");
      return kUsage;
    }
    constants.model = *model;
  }
  std::map<PowerParameter, std::string> notes;
  std::vector<std::string> fitted_files;
  auto given = [&](PowerParameter p, double value, const char* option) {
    set_parameter(constants, p, value);
    notes[p] = std::string("given on the command line (") + option + ")";
  };
  if (o.tare_w >= 0) given(PowerParameter::Tare, o.tare_w, "--tare-w");
  if (o.coolant_w >= 0) given(PowerParameter::Coolant, o.coolant_w, "--coolant-w");
  if (o.tool_change_w >= 0) given(PowerParameter::ToolChange, o.tool_change_w, "--tool-change-w");

  bool fitted_any = false;
  auto use = [&](const FitReport& fit, const std::string& file) {
    print_report(fit);
    apply_fit(constants, fit);
    for (const FittedConstant& c : fit.constants)
      if (!c.held) notes[c.parameter] = note_for(fit, c, file);
    fitted_files.push_back(fit.what + " from " + file);
    fitted_any = true;
  };
  if (!o.spindle.empty()) {
    auto t = read_table(o.spindle, kFieldRpm);
    if (!t) return kInputError;
    use(fit_spindle(*t, constants.pavanaskar.tare_w), o.spindle);
  }
  for (int i = 0; i < 3; ++i) {
    if (o.axis[i].empty()) continue;
    auto t = read_table(o.axis[i], kFieldFeed);
    if (!t) return kInputError;
    use(fit_axis_move(*t, static_cast<Axis>(i), constants), o.axis[i]);
  }
  for (int i = 0; i < 3; ++i) {
    if (o.cut[i].empty()) continue;
    auto t = read_table(o.cut[i], kFieldRpm | kFieldFeed | kFieldMrr);
    if (!t) return kInputError;
    use(fit_axis_cut(*t, static_cast<Axis>(i), constants), o.cut[i]);
  }
  if (!o.zhou.empty()) {
    auto t = read_table(o.zhou, kFieldRpm | kFieldMrr);
    if (!t) return kInputError;
    use(fit_zhou_power(*t), o.zhou);
    use(fit_zhou_sec(*t), o.zhou);
  }
  if (!o.log.empty()) {
    // The log fit (fit_power_log) needs the program's operating trace, which comes from the
    // machine loader, the planner and the removal engine; this command gains it when they can
    // run here.
    std::fprintf(stderr,
                 "%s: fitting a power log needs the planner and the removal engine, which this "
                 "build does not have yet\n",
                 o.log.c_str());
    return kInputError;
  }
  if (!fitted_any) {
    std::fprintf(stderr, "nothing to fit: give at least one of --spindle, --axis-x/y/z, "
                         "--cut-x/y/z, --zhou (see --help)\n");
    return kUsage;
  }
  std::string error;
  const std::string name =
      !o.name.empty() ? o.name : std::filesystem::path(o.output).stem().string();
  std::string source = "ncjoule calibrate:";
  for (std::size_t i = 0; i < fitted_files.size(); ++i)
    source += (i ? "; " : " ") + fitted_files[i];
  if (!o.machine.empty()) source += "; other constants from " + o.machine;
  auto text = profile_with_power(base_text, name, constants, notes, source, error);
  if (!text) {
    std::fprintf(stderr, "%s: %s\n", o.machine.c_str(), error.c_str());
    return kInputError;
  }
  // Write beside the target and rename, so a failure leaves no half-written profile.
  const std::string temporary = o.output + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary);
    out << "# Machine profile written by ncjoule calibrate.\n" << *text;
    if (!out) {
      std::fprintf(stderr, "%s: cannot write\n", temporary.c_str());
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      return kOutputError;
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, o.output, ec);
  if (ec) {
    std::fprintf(stderr, "%s: cannot write: %s\n", o.output.c_str(), ec.message().c_str());
    std::filesystem::remove(temporary, ec);
    return kOutputError;
  }
  std::printf("wrote %s (model %s)\n", o.output.c_str(),
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
                  "Power with the machine on and idle, spindle off (W); subtracted from the "
                  "spindle and axis tables")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--coolant-w", o->coolant_w, "Coolant pump power (W)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--tool-change-w", o->tool_change_w, "Power above tare during a tool change (W)")
      ->check(CLI::NonNegativeNumber);
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
  auto* log = cmd->add_option("--log", o->log,
                              "Power log (time_s, power_w) of a run of --program on --machine")
                  ->check(CLI::ExistingFile);
  cmd->add_option("--program", o->program, "NC program the log recorded")
      ->check(CLI::ExistingFile)
      ->needs(log);
  cmd->add_option("-o,--output", o->output, "New profile (TOML) to write")->required();
  cmd->callback([o, &exit_code] { exit_code = run_calibrate(*o); });
});

} // namespace
} // namespace ncjoule::cli
