// `ncjoule calibrate --log` end to end: a power log is synthesized through the library from a
// sample program and known constants (shifted in time, with noise from a fixed seed), written as
// CSV, and fitted back by the ncjoule program. The new profile must load, and every fitted
// constant must lie within a few of its reported standard errors of the truth.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>

#include "ncjoule/calibrate.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"

#ifdef NCJOULE_CLI

using namespace ncjoule;
namespace fs = std::filesystem;

namespace {

const std::string kSource = NCJOULE_SOURCE_DIR;
const std::string kProgram = kSource + "/samples/programs/bracket-linuxcnc.ngc";
const std::string kMachine = kSource + "/samples/machines/generic-3axis.toml";
const std::string kStock = "box:0,0,-20,100,60,0";

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The machine the log "was measured on": the generic profile's constants, each changed, so
// that the fit has to move away from its starting point to find them.
PowerConstants truth_from(PowerConstants k) {
  auto& p = k.pavanaskar;
  p.tare_w = 410;
  p.coolant_w = 140;
  p.spindle_ka_w = 130;
  p.spindle_kb_w_per_rpm = 0.26;
  p.move_ka_w = {190, 300, 220};
  p.move_kb_w_per_mm_s = {0.8, 0.35, 1.1};
  k.zhou.c3 = 1.0e-6; // c4 stays 1.13: the log fit holds the exponent by default
  k.tool_change_w = 450;
  return k;
}

struct PrintedConstant {
  double value = 0, std_error = 0;
  bool held = false;
};

// Reads calibrate's report: "  <key>  <value> +- <se> <unit>" or "  <key>  <value> <unit>
// (held)", and "time offset: the program starts <s> s into the log".
std::map<std::string, PrintedConstant> printed_constants(const std::string& out, double& offset_s) {
  std::map<std::string, PrintedConstant> constants;
  std::istringstream lines(out);
  std::string line;
  offset_s = std::nan("");
  while (std::getline(lines, line)) {
    if (line.rfind("time offset:", 0) == 0) {
      std::sscanf(line.c_str(), "time offset: the program starts %lf", &offset_s);
      continue;
    }
    std::istringstream words(line);
    std::string key, plus_minus;
    PrintedConstant c;
    if (line.rfind("  ", 0) != 0 || !(words >> key >> c.value)) continue;
    if (words >> plus_minus && plus_minus == "+-") {
      words >> c.std_error;
    } else {
      c.held = line.find("(held)") != std::string::npos;
      if (!c.held) continue;
    }
    constants[key] = c;
  }
  return constants;
}

} // namespace

TEST_CASE("calibrate --log fits a shifted, noisy log of the bracket program back to the truth") {
  MachineProfile machine = load_profile(kMachine);
  REQUIRE(machine.power.model == PowerModel::Combined);
  const PowerConstants initial = machine.power;
  const PowerConstants truth = truth_from(machine.power);
  machine.power = truth;

  // The program on the model, with the stock calibrate is told about.
  EstimateOptions options;
  options.stock = parse_stock_spec(kStock);
  REQUIRE(options.stock);
  options.keep_trace = true;
  std::ifstream in(kProgram, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const Estimate e = estimate_program(make_source(kProgram, text), machine, options);
  REQUIRE_FALSE(e.failed);
  REQUIRE(e.removal);
  const std::vector<OperatingSegment>& trace = e.trace;
  REQUIRE(!trace.empty());

  // A 10 Hz meter started 8.37 s before the program and stopped 15 s after it; Gaussian noise
  // of 12 W, and a spike where the spindle starts (an outlier for the robust loss).
  const double offset = 8.37, noise_w = 12;
  std::mt19937 rng(20250611);
  std::normal_distribution<double> noise(0.0, noise_w);
  const fs::path dir = fs::path(NCJOULE_BINARY_DIR) / "tests/energy/calibrate_log_cli";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path log_path = dir / "bracket-log.csv";
  {
    std::ofstream log(log_path);
    log << "# synthesized: bracket-linuxcnc.ngc on generic-3axis with changed constants\n";
    log << "time_s,power_w\n";
    const int samples = static_cast<int>((e.time_s + offset + 15) * 10);
    for (int i = 0; i <= samples; ++i) {
      const double t = i * 0.1;
      double p = component_sum(component_power_w(truth, operating_point_at(trace, t - offset)));
      if (i == static_cast<int>((offset + 0.05) * 10)) p += 2500;
      log << t << ',' << p + noise(rng) << '\n';
    }
  }
  const fs::path profile_path = dir / "fitted.toml";
  const fs::path out_path = dir / "calibrate.out";
  const std::string command = std::string("\"") + NCJOULE_CLI + "\" calibrate --log \"" +
                              log_path.string() + "\" --program \"" + kProgram + "\" --machine \"" +
                              kMachine + "\" --stock " + kStock + " -o \"" + profile_path.string() +
                              "\" > \"" + out_path.string() + "\" 2>&1";
  const int status = std::system(command.c_str());
  const std::string out = read_file(out_path);
  MESSAGE(out);
  REQUIRE(status == 0);

  // The profile loads and holds what calibrate printed.
  const MachineProfile fitted = load_profile(profile_path.string());
  CHECK(fitted.power.model == PowerModel::Combined);
  CHECK(fitted.kinematics.tool_change_s == doctest::Approx(machine.kinematics.tool_change_s));
  double found_offset = 0;
  const auto printed = printed_constants(out, found_offset);
  CHECK(found_offset == doctest::Approx(offset).epsilon(0.02 / offset));

  int fitted_count = 0;
  for (PowerParameter p : model_parameters(PowerModel::Combined)) {
    const std::string key(parameter_info(p).key);
    CAPTURE(key);
    const auto it = printed.find(key);
    REQUIRE(it != printed.end());
    const PrintedConstant& c = it->second;
    const double in_profile = get_parameter(fitted.power, p);
    CHECK(in_profile == doctest::Approx(c.value).epsilon(1e-5));
    if (c.held) {
      CHECK(in_profile == doctest::Approx(get_parameter(initial, p)));
      continue;
    }
    ++fitted_count;
    const double t = get_parameter(truth, p);
    MESSAGE(key << " = " << c.value << " +- " << c.std_error << " (true " << t << ", "
                << (c.value - t) / c.std_error << " SE)");
    CHECK(c.std_error > 0);
    CHECK(std::abs(c.value - t) <= 4 * c.std_error);
  }
  // Tare, coolant, spindle KA/KB, six move terms, c3 and the tool change: all but the exponent
  // and the n^2 term of the profile's straight spindle line.
  CHECK(fitted_count == static_cast<int>(model_parameters(PowerModel::Combined).size()) - 2);
  // The profile says where the fitted values came from.
  CHECK(read_file(profile_path).find("fitted from " + log_path.string()) != std::string::npos);
}

TEST_CASE("calibrate --log without --program is refused and writes nothing") {
  const fs::path dir = fs::path(NCJOULE_BINARY_DIR) / "tests/energy/calibrate_log_cli";
  fs::create_directories(dir);
  const fs::path log_path = dir / "short.csv";
  {
    std::ofstream log(log_path);
    log << "time_s,power_w\n0,100\n0.1,100\n0.2,100\n";
  }
  const fs::path profile_path = dir / "never.toml";
  fs::remove(profile_path);
  const std::string command = std::string("\"") + NCJOULE_CLI + "\" calibrate --log \"" +
                              log_path.string() + "\" --machine \"" + kMachine + "\" -o \"" +
                              profile_path.string() + "\" > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  CHECK(status != 0);
  CHECK_FALSE(fs::exists(profile_path));
}

#endif
