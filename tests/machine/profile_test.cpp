// Machine profiles: the shipped samples load with their values in internal units, and a
// profile that cannot be trusted is refused with the file, the key and the reason.
#include <doctest/doctest.h>
#include <fstream>
#include <sstream>
#include <string>

#include "ncjoule/profile.hpp"

using namespace ncjoule;

namespace {

std::string sample_path(const std::string& name) {
  return std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/" + name;
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The generic profile with one line replaced (the first line starting with `key`).
std::string with_line(const std::string& key, const std::string& replacement) {
  std::istringstream in(read(sample_path("generic-3axis.toml")));
  std::string out, line;
  bool done = false;
  while (std::getline(in, line)) {
    if (!done && line.rfind(key, 0) == 0) {
      line = replacement;
      done = true;
    }
    out += line + "\n";
  }
  REQUIRE(done);
  return out;
}

ProfileError refusal(const std::string& text) {
  try {
    parse_profile(text, "bad.toml");
  } catch (const ProfileError& e) {
    return e;
  }
  FAIL("the profile was accepted");
  return ProfileError("", "", "");
}

void check_names_file_and_key(const ProfileError& e, const std::string& key) {
  CHECK(e.file() == "bad.toml");
  CHECK(e.key() == key);
  const std::string what = e.what();
  CHECK(what.find("bad.toml") != std::string::npos);
  CHECK(what.find(key) != std::string::npos);
}

} // namespace

TEST_CASE("every shipped profile loads") {
  for (const char* name :
       {"generic-3axis.toml", "haas-vf0-pavanaskar2014.toml", "zhou2017-anziani2025.toml"}) {
    CAPTURE(name);
    const MachineProfile m = load_profile(sample_path(name));
    CHECK_FALSE(m.name.empty());
    CHECK(m.source_path == sample_path(name));
    CHECK(m.sources.size() >= 3); // profile, kinematics, power (+ model tables)
    for (const AxisLimits& a : m.kinematics.axes) {
      CHECK(a.rapid_mm_s > 0);
      CHECK(a.accel_mm_s2 > 0);
      CHECK(a.max_feed_mm_s <= a.rapid_mm_s);
    }
  }
}

TEST_CASE("Haas VF-0 profile: Pavanaskar's timing and constants in internal units") {
  const MachineProfile m = load_profile(sample_path("haas-vf0-pavanaskar2014.toml"));
  const double inch_per_min = 25.4 / 60; // mm/s
  for (const AxisLimits& a : m.kinematics.axes) {
    CHECK(a.accel_mm_s2 == doctest::Approx(1000)); // 1 m/s^2
    CHECK(a.rapid_mm_s == doctest::Approx(710 * inch_per_min));
  }
  CHECK(m.kinematics.junction_rule == JunctionRule::NextFeed);
  CHECK(m.kinematics.feed_profile == FeedProfile::Trapezoid);
  // Pavanaskar's tare, spindle and move lines, and one cutting term from Table 4.1's cut rows.
  CHECK(m.power.model == PowerModel::Combined);
  CHECK(m.power.cutting_term == CuttingTerm::Material);
  CHECK(m.power.material == "6061-vf0");
  REQUIRE(m.power.cutting_material.has_value());
  CHECK(m.power.cutting_material->kc_j_mm3 == doctest::Approx(0.6132));
  CHECK(m.power.cutting_efficiency == doctest::Approx(0.8));
  CHECK(m.power.pavanaskar.tare_w == doctest::Approx(325));
  CHECK(m.power.pavanaskar.spindle_ka_w == doctest::Approx(141.67));
  CHECK(m.power.pavanaskar.spindle_kb_w_per_rpm == doctest::Approx(0.21));
  // Table 4.1's X move line: 1.8571 W per % of the assumed rapid rate.
  const double per_percent = m.kinematics.axes[0].rapid_mm_s / 100;
  CHECK(m.power.pavanaskar.move_kb_w_per_mm_s[0] * per_percent ==
        doctest::Approx(1.8571).epsilon(1e-3));
}

TEST_CASE("Zhou profile: Table 1 constants, to the digits Table 2's model powers give") {
  const MachineProfile m = load_profile(sample_path("zhou2017-anziani2025.toml"));
  CHECK(m.power.model == PowerModel::Zhou);
  CHECK(m.power.zhou.c1_kw == doctest::Approx(0.7765));
  CHECK(m.power.zhou.c3 == doctest::Approx(8.0623e-7));
  CHECK(m.power.zhou.d4 == doctest::Approx(779));
  // Its sources do not describe the spindle: the rating and top speed are marked placeholders.
  CHECK(m.power.placeholder_spindle);
  CHECK(m.power.spindle_rated_w == 5500);
  CHECK(m.power.spindle_max_rpm == 10000);
  CHECK(m.kinematics.axes[0].rapid_mm_s == doctest::Approx(1000.0 / 60));
}

TEST_CASE("units in key names are converted") {
  MachineProfile m = parse_profile(with_line("rapid_mm_min", "rapid_m_min = 30"), "u.toml");
  CHECK(m.kinematics.axes[0].rapid_mm_s == doctest::Approx(500));
  m = parse_profile(with_line("accel_mm_s2", "accel_m_s2 = 2.5"), "u.toml");
  CHECK(m.kinematics.axes[0].accel_mm_s2 == doctest::Approx(2500));
  m = parse_profile(with_line("move_kb_w_per_mm_s", "move_kb_w_per_mm_min = 0.01"), "u.toml");
  CHECK(m.power.pavanaskar.move_kb_w_per_mm_s[0] == doctest::Approx(0.6));
}

TEST_CASE("a missing key is refused with the file and the key") {
  const ProfileError e = refusal(with_line("accel_mm_s2", "# no acceleration"));
  check_names_file_and_key(e, "kinematics.x.accel_mm_s2");
  CHECK(e.reason().find("missing") != std::string::npos);
  check_names_file_and_key(refusal(with_line("tool_change_s", "")), "kinematics.tool_change_s");
  check_names_file_and_key(refusal(with_line("c1_kw", "")), "power.zhou.c1_kw");
}

TEST_CASE("a negative acceleration is refused") {
  const ProfileError e = refusal(with_line("accel_mm_s2", "accel_mm_s2 = -1000"));
  check_names_file_and_key(e, "kinematics.x.accel_mm_s2");
  CHECK(e.reason().find("greater than zero") != std::string::npos);
}

TEST_CASE("a value no machine can have is refused with its line and column, not computed with") {
  // Each gave 150- to 300-digit times and energies, or a negative energy (-59 kWh).
  const std::pair<const char*, const char*> cases[] = {
      {"accel_mm_s2", "accel_mm_s2 = 1e-300"},
      {"jerk_mm_s3", "jerk_mm_s3 = 1e-300"},
      {"cutting_efficiency", "cutting_efficiency = 1e-300"},
      {"move_ka_w", "move_ka_w = -1e6"},
      {"accel_mm_s2", "accel_mm_s2 = 1e300"},
      {"rapid_mm_min", "rapid_mm_min = 1e-9"},
      {"tool_change_s", "tool_change_s = 1e9"},
      {"spindle_max_rpm", "spindle_max_rpm = 1e9"},
      {"price_per_kwh", "price_per_kwh = 1e9"},
      {"c4", "c4 = 50"},
  };
  for (auto [key, line] : cases) {
    const std::string text = line;
    CAPTURE(text);
    const ProfileError e = refusal(with_line(key, line));
    CHECK(e.key().find(key) != std::string::npos);
    CHECK(e.line() > 0);
    CHECK(e.column() > 0);
    CHECK((e.reason().find("no machine's") != std::string::npos ||
           e.reason().find("physically") != std::string::npos ||
           e.reason().find("plausible") != std::string::npos));
  }
  // The range is said in the unit the key was written in.
  CHECK(
      refusal(with_line("accel_mm_s2", "accel_m_s2 = 1e-300")).reason().find("from 0.001 to 100") !=
      std::string::npos);
  // What a real machine has passes: a small negative intercept of a fitted line, zero jerk.
  CHECK_NOTHROW(parse_profile(with_line("move_ka_w", "move_ka_w = -120"), "ok.toml"));
  CHECK_NOTHROW(parse_profile(with_line("jerk_mm_s3", "jerk_mm_s3 = 0"), "ok.toml"));
}

TEST_CASE("a zero rapid rate is refused") {
  check_names_file_and_key(refusal(with_line("rapid_mm_min", "rapid_mm_min = 0")),
                           "kinematics.x.rapid_mm_min");
}

TEST_CASE("a value of the wrong type is refused") {
  const ProfileError e = refusal(with_line("accel_mm_s2", "accel_mm_s2 = \"1 m/s^2\""));
  check_names_file_and_key(e, "kinematics.x.accel_mm_s2");
  CHECK(e.reason().find("expected a number") != std::string::npos);
  check_names_file_and_key(refusal(with_line("rapid_mode", "rapid_mode = \"zigzag\"")),
                           "kinematics.rapid_mode");
  check_names_file_and_key(refusal(with_line("dialect", "dialect = \"klingon\"")), "dialect");
  check_names_file_and_key(
      refusal(with_line("exact_stop_every_block", "exact_stop_every_block = 1")),
      "kinematics.exact_stop_every_block");
}

TEST_CASE("an unknown unit or a misspelt key is refused, not ignored") {
  ProfileError e = refusal(with_line("rapid_mm_min", "rapid_ft_min = 100"));
  check_names_file_and_key(e, "kinematics.x.rapid_ft_min");
  CHECK(e.reason().find("rapid_mm_min") != std::string::npos); // tells what to write instead
  check_names_file_and_key(
      refusal(with_line("rapid_mm_min", "rapid_mm_min = 24000\nrapid_mm_s = 400")),
      "kinematics.x.rapid_mm_s");
  e = refusal(with_line("tool_change_s", "tool_change_s = 6\ntool_chnage_s = 6"));
  check_names_file_and_key(e, "kinematics.tool_chnage_s");
  CHECK(e.reason() == "unknown key");
}

TEST_CASE("a maximum feed above the rapid rate is refused") {
  check_names_file_and_key(refusal(with_line("max_feed_mm_min", "max_feed_mm_min = 90000")),
                           "kinematics.x.max_feed_mm_min");
}

TEST_CASE("text that is not TOML and files that do not exist name the file") {
  const ProfileError e = refusal("name = [unclosed");
  CHECK(e.file() == "bad.toml");
  CHECK(e.line() == 1);
  CHECK(std::string(e.what()).find("not valid TOML") != std::string::npos);
  CHECK_THROWS_AS(load_profile("no/such/profile.toml"), ProfileError);
}

TEST_CASE("a refused profile is a diagnostic with the line and column of the key") {
  // The value that is wrong: its own line and column; a key that is missing: its table's.
  const ProfileError bad = refusal("name = \"x\"\nsource = \"test\"\n[kinematics]\n"
                                   "rapid_mm_min = -5\n");
  const Diagnostic d = bad.diagnostic();
  CHECK(d.severity == Severity::Error);
  CHECK(d.file == "bad.toml");
  CHECK(d.message.find("key '") == 0);
  CHECK(d.line >= 3);
  CHECK(d.column >= 1);
}

TEST_CASE("shipped profiles detect the dialect and carry a default tool with its source") {
  const MachineProfile generic = load_profile(sample_path("generic-3axis.toml"));
  CHECK(generic.dialect == "auto");
  REQUIRE(generic.default_tool.has_value());
  CHECK(generic.default_tool->shape == ToolShape::FlatEndMill);
  CHECK(generic.default_tool->diameter_mm == doctest::Approx(6));
  const MachineProfile haas = load_profile(sample_path("haas-vf0-pavanaskar2014.toml"));
  CHECK(haas.dialect == "auto");
  CHECK(haas.fallback_dialect == "haas");
  REQUIRE(haas.default_tool.has_value());
  CHECK(haas.default_tool->diameter_mm == doctest::Approx(0.375 * 25.4));
  bool sourced = false;
  for (const std::string& s : haas.sources)
    sourced |= s.rfind("default_tool: ", 0) == 0;
  CHECK(sourced);
}

TEST_CASE("[default_tool]: types and sizes are checked like every other key") {
  const std::string base = read(sample_path("generic-3axis.toml"));
  auto with_tool = [&](const std::string& table) {
    std::string text = base;
    const std::size_t at = text.find("[default_tool]");
    const std::size_t end = text.find("\n[", at + 1);
    return text.substr(0, at) + table + text.substr(end);
  };
  const MachineProfile ball = parse_profile(
      with_tool("[default_tool]\nsource = \"t\"\ntype = \"ball\"\ndiameter_mm = 4\n"), "b.toml");
  REQUIRE(ball.default_tool.has_value());
  CHECK(ball.default_tool->corner_radius_mm == doctest::Approx(2));
  check_names_file_and_key(
      refusal(with_tool("[default_tool]\nsource = \"t\"\ntype = \"square\"\ndiameter_mm = 4\n")),
      "default_tool.type");
  check_names_file_and_key(
      refusal(with_tool("[default_tool]\nsource = \"t\"\ntype = \"flat\"\ndiameter_mm = -4\n")),
      "default_tool.diameter_mm");
  check_names_file_and_key(
      refusal(with_tool("[default_tool]\nsource = \"t\"\ntype = "
                        "\"bullnose\"\ndiameter_mm = 4\ncorner_radius_mm = 3\n")),
      "default_tool.diameter_mm");
  check_names_file_and_key(refusal(with_line("dialect", "dialect = \"okuma\"")), "dialect");
}

TEST_CASE("[power]: cutting term, material, efficiency and spindle rating are read and checked") {
  const MachineProfile generic = load_profile(sample_path("generic-3axis.toml"));
  CHECK(generic.power.cutting_term == CuttingTerm::Material);
  CHECK(generic.power.material == "aluminium-alloy");
  CHECK(generic.power.spindle_rated_w == doctest::Approx(5500));
  // The material's k_c over the efficiency, in Zhou's form (kW per mm^3/s, c4 = 0).
  CHECK(generic.power.zhou.c3 ==
        doctest::Approx(find_material("aluminium-alloy")->kc_j_mm3 / 1000 / 0.8));
  CHECK(generic.power.zhou.c4 == 0);
  CHECK(generic.power.cutting_source.find("ISCAR") != std::string::npos);
  const MachineProfile zhou = load_profile(sample_path("zhou2017-anziani2025.toml"));
  CHECK(zhou.power.cutting_term == CuttingTerm::Fitted);
  CHECK(zhou.power.zhou.fitted_rpm_min == 500);
  CHECK(zhou.power.zhou.fitted_mrr_max_mm3_s == 48);
  CHECK(zhou.power.zhou.c4 == doctest::Approx(1.1305));

  check_names_file_and_key(refusal(with_line("material", "material = \"unobtainium\"")),
                           "power.material");
  check_names_file_and_key(refusal(with_line("cutting_efficiency", "cutting_efficiency = 1.5")),
                           "power.cutting_efficiency");
  check_names_file_and_key(refusal(with_line("cutting_term", "cutting_term = \"magic\"")),
                           "power.cutting_term");
  // A placeholder spindle needs a rating or a top speed to stand in for.
  std::string no_spindle = with_line("spindle_rated_w", "placeholder_spindle = true");
  no_spindle.replace(no_spindle.find("spindle_max_rpm ="), 1, "#");
  check_names_file_and_key(refusal(no_spindle), "power.placeholder_spindle");
  // A curve of rated power against speed.
  const MachineProfile curve = parse_profile(
      with_line("spindle_rated_w", "spindle_power_curve_rpm_w = [[1000, 2000], [6000, 5500]]"),
      "c.toml");
  CHECK(rated_spindle_power_w(curve.power, 3500) == doctest::Approx(3750));
  check_names_file_and_key(
      refusal(with_line("spindle_rated_w", "spindle_power_curve_rpm_w = [[6000, 1], [1000, 2]]")),
      "power.spindle_power_curve_rpm_w");
}

TEST_CASE("which way +Z points: up, down, or left to each program") {
  CHECK(parse_profile(read(sample_path("generic-3axis.toml")), "g.toml").kinematics.z_positive ==
        ZDirection::Auto);
  const std::string down = with_line("tool_change_s", "tool_change_s = 6.0\nz_positive = \"down\"");
  CHECK(parse_profile(down, "d.toml").kinematics.z_positive == ZDirection::Down);
  const std::string up = with_line("tool_change_s", "tool_change_s = 6.0\nz_positive = \"up\"");
  CHECK(parse_profile(up, "u.toml").kinematics.z_positive == ZDirection::Up);
  const ProfileError e =
      refusal(with_line("tool_change_s", "tool_change_s = 6.0\nz_positive = \"-1\""));
  check_names_file_and_key(e, "kinematics.z_positive");
  CHECK(e.reason().find("\"down\"") != std::string::npos);
}

TEST_CASE("a control's timing: run-up curve, tool-change sequence, peck distances") {
  const std::string generic = read(sample_path("generic-3axis.toml"));
  const MachineProfile plain = parse_profile(generic, "g.toml");
  CHECK(plain.kinematics.spindle_run_up.empty());
  CHECK(plain.kinematics.tool_change_first_extra_s == 0);
  CHECK_FALSE(plain.kinematics.tool_change_same_tool_s);
  CHECK_FALSE(plain.setup.peck_clearance_mm);

  const std::string timed =
      with_line("spindle_ramp", "spindle_run_up_rpm_s = [[3000, 0], [7500, 3.0], [12000, 7]]\n"
                                "tool_change_first_extra_s = 2\ntool_change_same_tool_s = 2.4\n"
                                "tool_change_spindle_stop_s = 1.2\narc_accel_m_s2 = 0.7");
  const MachineProfile m = parse_profile(timed + "[setup]\npeck_clearance_in = 0.05\n"
                                                 "chip_break_retract_mm = 0.5\n",
                                         "t.toml");
  REQUIRE(m.kinematics.spindle_run_up.size() == 3);
  CHECK(m.kinematics.spindle_run_up[1] == std::pair{7500.0, 3.0});
  CHECK(m.kinematics.spindle_s_per_1000rpm == 0); // the curve replaces the ramp
  CHECK(m.kinematics.tool_change_first_extra_s == 2);
  CHECK(m.kinematics.tool_change_same_tool_s == 2.4);
  CHECK(m.kinematics.tool_change_spindle_stop_s == 1.2);
  CHECK(plain.kinematics.tool_change_spindle_stop_s == 0);
  CHECK(*m.kinematics.arc_accel_mm_s2 == doctest::Approx(700));
  CHECK_FALSE(plain.kinematics.arc_accel_mm_s2);
  check_names_file_and_key(
      refusal(with_line("tool_change_s", "tool_change_s = 6.0\narc_accel_m_s2 = 0")),
      "kinematics.arc_accel_m_s2");
  CHECK(*m.setup.peck_clearance_mm == doctest::Approx(1.27));
  CHECK(*m.setup.chip_break_retract_mm == doctest::Approx(0.5));
  // A curve that falls, or a run-down without a run-up, is refused at its key.
  check_names_file_and_key(
      refusal(with_line("spindle_ramp", "spindle_run_up_rpm_s = [[3000, 2], [7500, 1]]")),
      "kinematics.spindle_run_up_rpm_s");
  check_names_file_and_key(
      refusal(with_line("spindle_ramp", "spindle_ramp_s_per_1000rpm = 1\n"
                                        "spindle_run_down_rpm_s = [[3000, 1]]")),
      "kinematics.spindle_run_down_rpm_s");
}

TEST_CASE("transition_speed_ratio: a share of the feed, and not with the LinuxCNC rule") {
  const std::string generic = read(sample_path("generic-3axis.toml"));
  CHECK(parse_profile(generic, "g.toml").kinematics.transition_speed_ratio == 1);
  auto tolerance_rule = [](const std::string& ratio) {
    return with_line("junction_rule",
                     "junction_rule = \"tolerance\"\ntransition_speed_ratio = " + ratio);
  };
  CHECK(parse_profile(tolerance_rule("0.13"), "t.toml").kinematics.transition_speed_ratio == 0.13);
  for (const char* bad : {"0", "1.5", "-0.2"})
    check_names_file_and_key(refusal(tolerance_rule(bad)), "kinematics.transition_speed_ratio");
  // generic-3axis follows LinuxCNC 2.9, whose transitions are its own.
  check_names_file_and_key(
      refusal(with_line("tool_change_s", "tool_change_s = 6.0\ntransition_speed_ratio = 0.5")),
      "kinematics.transition_speed_ratio");
}

TEST_CASE("lookahead_blocks: a whole number of blocks, and not with the LinuxCNC rule") {
  CHECK(parse_profile(read(sample_path("generic-3axis.toml")), "g.toml")
            .kinematics.lookahead_blocks == 0);
  auto tolerance_rule = [](const std::string& blocks) {
    return with_line("junction_rule",
                     "junction_rule = \"tolerance\"\nlookahead_blocks = " + blocks);
  };
  CHECK(parse_profile(tolerance_rule("80"), "t.toml").kinematics.lookahead_blocks == 80);
  for (const char* bad : {"0", "2.5", "-3", "\"80\""})
    check_names_file_and_key(refusal(tolerance_rule(bad)), "kinematics.lookahead_blocks");
  check_names_file_and_key(
      refusal(with_line("tool_change_s", "tool_change_s = 6.0\nlookahead_blocks = 80")),
      "kinematics.lookahead_blocks");
}

TEST_CASE("[setup]: work offsets, travel, Z home and power-on units") {
  const std::string generic = read(sample_path("generic-3axis.toml"));
  const MachineProfile plain = parse_profile(generic, "g.toml");
  CHECK(plain.setup.work_offsets.empty());
  CHECK_FALSE(plain.setup.travel);
  CHECK(plain.setup.z_home_above_work_mm == 100);
  CHECK_FALSE(plain.setup.power_on_inch);

  const MachineProfile m = parse_profile(generic + R"(
[setup]
source = "the shop's setup sheet"
z_home_above_work_in = 6
power_on_units = "inch"
cutter_compensation = "wear"
work_offsets_mm = { G54 = [-381.0, -203.2, -355.6], "G59.1" = [-100, -50, -300], "G54.1 P2" = [-1, -2, -3], G112 = [-7, -8, -9] }
travel_mm = { x = [-762, 0], y = [-406, 0], z = [-508, 0] }
macro_dirs = ["macros", "/opt/shop/o9000"]
xy_home_in_work_mm = [-381.0, 203.2]
)",
                                         "dir/s.toml");
  CHECK(m.setup.z_home_above_work_mm == doctest::Approx(152.4));
  CHECK(m.setup.power_on_inch == true);
  CHECK(m.setup.cutter_compensation == CutterCompMode::Wear);
  CHECK_FALSE(plain.setup.cutter_compensation);
  REQUIRE(m.setup.work_offsets.size() == 4);
  check_names_file_and_key(
      refusal(generic +
              "[setup]\nwork_offsets_mm = { G112 = [0, 0, 0], \"G154 P3\" = [0, 0, 0] }\n"),
      "setup.work_offsets_mm.G154 P3");
  CHECK(m.setup.work_offsets.at(1).z == doctest::Approx(-355.6));
  CHECK(m.setup.work_offsets.at(7).x == -100);
  // The additional offsets are 9 + P: G54.1 P2, Haas G112 (= G154 P3).
  CHECK(m.setup.work_offsets.at(11).z == -3);
  CHECK(m.setup.work_offsets.at(12).x == -7);
  CHECK(work_offset_name(11) == "G54.1 P2");
  CHECK(work_offset_index("g54.1 p300") == 309);
  CHECK(work_offset_index("G54.1 P301") == 0);
  CHECK(work_offset_index("G130") == 0);
  // Macro folders: a relative one is the profile's folder's.
  CHECK(m.setup.macro_dirs == std::vector<std::string>{"dir/macros", "/opt/shop/o9000"});
  REQUIRE(m.setup.xy_home_in_work_mm);
  CHECK(m.setup.xy_home_in_work_mm->second == doctest::Approx(203.2));
  REQUIRE(m.setup.travel);
  CHECK((*m.setup.travel)[1].first == -406);

  check_names_file_and_key(refusal(generic + "[setup]\nwork_offsets_mm = { G60 = [0, 0, 0] }\n"),
                           "setup.work_offsets_mm.G60");
  check_names_file_and_key(refusal(generic + "[setup]\nwork_offsets_mm = { G54 = [0, 0] }\n"),
                           "setup.work_offsets_mm.G54");
  check_names_file_and_key(
      refusal(generic + "[setup]\ntravel_mm = { x = [0, -1], y = [-1, 0], z = [-1, 0] }\n"),
      "setup.travel_mm.x");
  check_names_file_and_key(refusal(generic + "[setup]\npower_on_units = \"cm\"\n"),
                           "setup.power_on_units");
  check_names_file_and_key(refusal(generic + "[setup]\nhome_above = 3\n"), "setup.home_above");
  check_names_file_and_key(refusal(generic + "[setup]\ncutter_compensation = \"both\"\n"),
                           "setup.cutter_compensation");
}

TEST_CASE("a spindle line that bends: KA + KB n + KC n^2, KC optional and not negative") {
  MachineProfile m = parse_profile(
      with_line("spindle_kb_w_per_rpm", "spindle_kb_w_per_rpm = 0.1\nspindle_kc_w_per_rpm2 = 2e-5"),
      "kc.toml");
  CHECK(m.power.pavanaskar.spindle_kc_w_per_rpm2 == doctest::Approx(2e-5));
  // Without the key the line stays straight.
  CHECK(load_profile(sample_path("generic-3axis.toml")).power.pavanaskar.spindle_kc_w_per_rpm2 ==
        0);
  CHECK_THROWS_WITH_AS(
      parse_profile(with_line("spindle_kb_w_per_rpm", "spindle_kb_w_per_rpm = 0.1\n"
                                                      "spindle_kc_w_per_rpm2 = -1e-5"),
                    "kc.toml"),
      doctest::Contains("spindle_kc_w_per_rpm2"), ProfileError);
}
