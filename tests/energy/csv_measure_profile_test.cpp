// CSV errors that point at the cell, measured energy of a log, and the [power] section of a
// profile written and read back.
#include <doctest/doctest.h>

#include <cmath>

#include <fstream>
#include <sstream>

#include "ncjoule/calibrate.hpp"
#include "ncjoule/profile.hpp"

using namespace ncjoule;

TEST_CASE("CSV errors say file, line, column and what is wrong") {
  std::vector<Diagnostic> d;
  const auto csv = parse_numeric_csv("spindle.csv",
                                     "# spindle trial\nrpm,power_w\n3000,1100\n4000, 13x0\n"
                                     "5000\n6000,-5\n",
                                     d);
  REQUIRE(csv);
  REQUIRE(d.size() == 2);
  CHECK(d[0].file == "spindle.csv");
  CHECK(d[0].line == 4);
  CHECK(d[0].column == 7);
  CHECK(d[0].message.find("power_w") != std::string::npos);
  CHECK(d[0].message.find("13x0") != std::string::npos);
  CHECK(d[1].line == 5);
  CHECK(d[1].message.find("expected 2 fields") != std::string::npos);
  const auto readings = readings_from_csv(*csv, kFieldRpm, d);
  CHECK(readings.size() == 1);
  REQUIRE(d.size() == 3);
  CHECK(d[2].line == 6);
  CHECK(d[2].column == 6);
  CHECK(d[2].message.find("negative") != std::string::npos);

  std::vector<Diagnostic> missing;
  const auto axis = parse_numeric_csv("x.csv", "speed,power_w\n1,2\n", missing);
  REQUIRE(axis);
  CHECK(readings_from_csv(*axis, kFieldFeed, missing).empty());
  REQUIRE_FALSE(missing.empty());
  CHECK(missing[0].line == 1);
  CHECK(missing[0].message.find("feed_mm_min") != std::string::npos);
}

TEST_CASE("CSV columns convert their units") {
  std::vector<Diagnostic> d;
  const auto csv = parse_numeric_csv("cut.csv", "feed_ipm;mrr_mm3_min;power_kw\n30;600;1.2\n", d);
  REQUIRE(csv);
  const auto r = readings_from_csv(*csv, kFieldFeed | kFieldMrr, d);
  REQUIRE(r.size() == 1);
  CHECK(d.empty());
  CHECK(r[0].feed_mm_s == doctest::Approx(12.7));
  CHECK(r[0].mrr_mm3_s == doctest::Approx(10));
  CHECK(r[0].power_w == doctest::Approx(1200));
}

TEST_CASE("power logs: times must increase") {
  std::vector<Diagnostic> d;
  const auto csv =
      parse_numeric_csv("log.csv", "time_s,power_w\n0,100\n0.1,110\n0.1,120\n0.2,90\n", d);
  REQUIRE(csv);
  const auto log = power_log_from_csv(*csv, d);
  REQUIRE(log);
  CHECK(log->t_s.size() == 3);
  REQUIRE(d.size() == 1);
  CHECK(d[0].line == 4);
  CHECK(d[0].column == 1);
}

TEST_CASE("measured energy: trapezoid rule, idle power subtracted as Mora did") {
  PowerLog log;
  // 10 Hz: 2 s idle at 400 W, then a ramp to 1400 W over 1 s, then 3 s at 1400 W.
  for (int i = 0; i <= 60; ++i) {
    const double t = 0.1 * i;
    log.t_s.push_back(t);
    log.power_w.push_back(t <= 2 ? 400 : t <= 3 ? 400 + 1000 * (t - 2) : 1400);
  }
  const double exact = 2 * 400 + 1 * 900 + 3 * 1400;
  const MeasuredEnergy gross = measure_energy(log);
  CHECK(gross.energy_j == doctest::Approx(exact));
  CHECK(gross.duration_s == doctest::Approx(6));
  CHECK(gross.peak_power_w == doctest::Approx(1400));
  CHECK(gross.net_energy_j == doctest::Approx(exact));
  MeasureOptions first;
  first.idle_from_first_s = 1.5;
  const MeasuredEnergy net = measure_energy(log, first);
  CHECK(net.idle_w == doctest::Approx(400));
  CHECK(net.net_energy_j == doctest::Approx(exact - 400 * 6));
  MeasureOptions fixed;
  fixed.idle_w = 300;
  CHECK(measure_energy(log, fixed).net_energy_j == doctest::Approx(exact - 300 * 6));
}

TEST_CASE("a profile written with fitted constants loads back through the profile loader") {
  const std::string haas_path =
      std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/haas-vf0-pavanaskar2014.toml";
  std::ifstream in(haas_path);
  REQUIRE(in);
  std::stringstream base;
  base << in.rdbuf();
  const MachineProfile original = parse_profile(base.str(), haas_path);
  PowerConstants k;
  k.model = PowerModel::Combined;
  // Values distinct from each other and within every constant's physical range (a spindle's
  // n^2 term of W/rpm^2, Zhou's exponent), which the loader checks.
  for (std::size_t i = 0; i < kPowerParameterCount; ++i)
    set_parameter(k, static_cast<PowerParameter>(i), 0.0015 + 0.00037 * static_cast<double>(i));
  k.zhou.c3 = 8.06e-7;
  k.co2_kg_per_kwh = 0.42;
  k.price_per_kwh = 0.19;
  k.currency = "USD";
  std::vector<Diagnostic> problems;
  const auto text = profile_with_power(base.str(), "base.toml", "fitted", k,
                                       {{PowerParameter::SpindleKA, "fit of spindle.csv"}},
                                       "ncjoule calibrate: spindle.csv", problems);
  REQUIRE(text);
  CHECK(text->find("fit of spindle.csv") != std::string::npos);
  const MachineProfile back = parse_profile(*text, "fitted.toml");
  CHECK(back.name == "fitted");
  CHECK(back.kinematics.tool_change_s == doctest::Approx(original.kinematics.tool_change_s));
  CHECK(back.kinematics.axes[0].rapid_mm_s ==
        doctest::Approx(original.kinematics.axes[0].rapid_mm_s));
  CHECK(back.power.model == PowerModel::Combined);
  CHECK(back.power.currency == "USD");
  CHECK(back.power.co2_kg_per_kwh == doctest::Approx(0.42));
  CHECK(back.power.price_per_kwh == doctest::Approx(0.19));
  for (std::size_t i = 0; i < kPowerParameterCount; ++i) {
    const auto p = static_cast<PowerParameter>(i);
    CAPTURE(parameter_info(p).key);
    CHECK(get_parameter(back.power, p) == doctest::Approx(get_parameter(k, p)).epsilon(1e-9));
  }
}

TEST_CASE("a calibrated profile keeps the base profile's [power] keys that fitting does not set") {
  const std::string path =
      std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/zhou2017-anziani2025.toml";
  std::ifstream in(path);
  REQUIRE(in);
  std::stringstream base;
  base << in.rdbuf();
  MachineProfile original = parse_profile(base.str(), path);
  // Add the keys a shop would have set: the material term and its own material.
  std::string text = base.str();
  const auto at = text.find("[power]\n");
  REQUIRE(at != std::string::npos);
  text.insert(at + 8, "cutting_term = \"material\"\nmaterial = \"mild-steel\"\n"
                      "cutting_efficiency = 0.7\n");
  // The shop's own rating in place of the profile's placeholder.
  const auto rating = text.find("spindle_rated_w = 5500");
  REQUIRE(rating != std::string::npos);
  text.replace(rating, 22, "spindle_rated_w = 7500");
  text += "\n[power.profile_material]\nsource = \"shop table\"\nname = \"house-alloy\"\n"
          "kc_j_mm3 = 0.9\n";
  original = parse_profile(text, path);
  REQUIRE(original.power.cutting_term == CuttingTerm::Material);

  PowerConstants k = original.power;
  k.zhou.c3 = 1.25e-6; // as a fit would change it
  std::vector<SteadyStateReading> rows{
      {1000, 5, 10, 900, 2}, {6000, 5, 40, 2500, 3}, {3000, 5, 0, 600, 4}};
  set_zhou_fitted_ranges(k.zhou, rows);
  CHECK(k.zhou.fitted_rpm_min == 1000);
  CHECK(k.zhou.fitted_rpm_max == 6000);
  CHECK(k.zhou.fitted_mrr_max_mm3_s == 40);

  std::vector<Diagnostic> problems;
  // A refit of the Pavanaskar terms only: the material term stays.
  const auto kept =
      profile_with_power(text, "base.toml", "fitted", original.power, {}, "spindle.csv", problems);
  REQUIRE(kept);
  const MachineProfile same = parse_profile(*kept, "fitted.toml");
  CHECK(same.power.cutting_term == CuttingTerm::Material);
  CHECK(same.power.material == "mild-steel");
  CHECK(same.power.zhou.c3 == doctest::Approx(original.power.zhou.c3));

  // A Zhou fit: its cutting term is what cuts from now on, the other keys stay.
  k.cutting_term = CuttingTerm::Fitted;
  const auto written =
      profile_with_power(text, "base.toml", "fitted", k, {}, "ncjoule calibrate: z.csv", problems);
  REQUIRE(written);
  const MachineProfile back = parse_profile(*written, "fitted.toml");
  CHECK(back.power.cutting_term == CuttingTerm::Fitted);
  CHECK(back.power.material == "mild-steel");
  CHECK(back.power.cutting_efficiency == doctest::Approx(0.7));
  CHECK(back.power.spindle_rated_w == doctest::Approx(7500));
  CHECK(back.power.placeholder_spindle); // a fit of the power says nothing of the spindle
  REQUIRE(back.power.profile_material);
  CHECK(back.power.profile_material->name == "house-alloy");
  CHECK(back.power.zhou.c3 == doctest::Approx(1.25e-6));
  CHECK(back.power.zhou.fitted_rpm_min == doctest::Approx(1000));
  CHECK(back.power.zhou.fitted_mrr_max_mm3_s == doctest::Approx(40));
}

TEST_CASE("a table whose file name holds control bytes still makes a profile that loads") {
  // The source names the files fitted: an ESC or a line break in a name is escaped in the TOML
  // string (raw, TOML refuses it and the new profile would not load).
  const std::string path = std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/generic-3axis.toml";
  std::ifstream in(path);
  REQUIRE(in);
  std::stringstream base;
  base << in.rdbuf();
  const MachineProfile original = parse_profile(base.str(), path);
  std::vector<Diagnostic> problems;
  const std::string name = "spindle\x1b]0;title\x07\nnext.csv";
  // profile_with_power loads what it wrote: a profile that would not load is a diagnostic.
  const auto text = profile_with_power(base.str(), path, "fitted", original.power, {},
                                       "ncjoule calibrate: " + name, problems);
  REQUIRE(text);
  CHECK(problems.empty());
  CHECK(text->find('\x1b') == std::string::npos);
  CHECK(text->find("spindle\\u001B]0;title\\u0007\\u000Anext.csv") != std::string::npos);
  CHECK_NOTHROW(parse_profile(*text, "fitted.toml"));
}

TEST_CASE("a base profile that is not TOML is reported at its line and column") {
  std::vector<Diagnostic> problems;
  const auto text = profile_with_power("name = \"mill\"\nrapid = [1, 2\n", "mill.toml", "fitted",
                                       PowerConstants{}, {}, "x.csv", problems);
  CHECK_FALSE(text);
  REQUIRE(problems.size() == 1);
  CHECK(problems[0].file == "mill.toml");
  CHECK(problems[0].line == 2);
  CHECK(problems[0].column > 0);
  CHECK(problems[0].message.rfind("not valid TOML", 0) == 0);
}

TEST_CASE("readings and logs are checked against what a machine can be, at the cell") {
  auto errors_of = [](const std::string& text, bool log) {
    std::vector<Diagnostic> d;
    const auto csv = parse_numeric_csv("t.csv", text, d);
    REQUIRE(csv);
    if (log)
      (void)power_log_from_csv(*csv, d);
    else
      (void)readings_from_csv(*csv, kFieldRpm | kFieldMrr, d);
    return d;
  };
  // 1e308 W, inf, an absurd speed, an absurd removal rate, a negative power.
  const std::pair<const char*, int> rows[] = {{"3000,5,1e308", 8},
                                              {"3000,5,inf", 8},
                                              {"3e7,5,900", 1},
                                              {"3000,1e9,900", 6},
                                              {"3000,5,-1e-3", 8}};
  for (const auto& [row, column] : rows) {
    CAPTURE(std::string(row));
    const auto d =
        errors_of(std::string("rpm,mrr_mm3_s,power_w\n1000,1,500\n") + row + "\n", false);
    REQUIRE(d.size() == 1); // the cell; the first row stays usable
    CHECK(d[0].severity == Severity::Error);
    CHECK(d[0].line == 3);
    CHECK(d[0].column == column);
  }
  const auto kw = errors_of("rpm,mrr_mm3_s,power_kw\n1000,1,1e300\n", false);
  REQUIRE_FALSE(kw.empty());
  CHECK(kw[0].column == 8);
  CHECK(kw[0].message.find("1e+303 W") != std::string::npos);
  // A log: a negative power or a non-finite time is refused at its cell.
  const auto negative = errors_of("time_s,power_w\n0,100\n1,-50\n2,100\n3,100\n", true);
  REQUIRE(negative.size() == 1);
  CHECK(negative[0].line == 3);
  CHECK(negative[0].column == 3);
  CHECK(negative[0].message.find("negative") != std::string::npos);
  const auto huge = errors_of("time_s,power_w\n0,100\n1e308,100\n", true);
  REQUIRE_FALSE(huge.empty());
  CHECK(huge[0].line == 3);
  CHECK(huge[0].column == 1);
  CHECK(errors_of("time_s,power_kw\n0,0.1\n1,1000\n2,0.1\n", true).empty()); // 1 MW
}
