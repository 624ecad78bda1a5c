// Profiles that start from another (`base = "..."`): the base's values with this file's on top,
// the base found beside the profile or among the shipped ones, a cycle refused at its line, and
// every value's file kept for errors and for --show-settings.
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <string>

#include "ncjoule/profile.hpp"

using namespace ncjoule;
namespace fs = std::filesystem;

namespace {

const std::string kSamples = std::string(NCJOULE_SOURCE_DIR) + "/samples/machines";

// A fresh folder for the files of one test.
struct Folder {
  fs::path path;
  explicit Folder(const std::string& name)
      : path(fs::temp_directory_path() / ("ncjoule-base-" + name)) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Folder() { fs::remove_all(path); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return (path / name).string();
  }
};

} // namespace

TEST_CASE("a profile on a shipped base changes only the keys it gives") {
  Folder f("shipped");
  const std::string path = f.write("my-router.toml", "base = \"router-2.2kw-vfd\"\n"
                                                     "name = \"Our router\"\n"
                                                     "[power]\n"
                                                     "machine_rate_per_hour = 40\n"
                                                     "[kinematics.x]\n"
                                                     "rapid_mm_min = 5000\n");
  const MachineProfile base = load_profile(kSamples + "/router-2.2kw-vfd.toml");
  const MachineProfile m = load_profile(path, {kSamples});
  CHECK(m.name == "Our router");
  CHECK(m.power.machine_rate_per_hour == 40);
  CHECK(m.kinematics.axes[0].rapid_mm_s == doctest::Approx(5000.0 / 60));
  // Everything else is the base's: the next key of the same table, other tables, the material.
  CHECK(m.kinematics.axes[0].max_feed_mm_s == base.kinematics.axes[0].max_feed_mm_s);
  CHECK(m.kinematics.axes[1].rapid_mm_s == base.kinematics.axes[1].rapid_mm_s);
  CHECK(m.power.material == "mdf");
  CHECK(m.power.pavanaskar.spindle_kb_w_per_rpm == base.power.pavanaskar.spindle_kb_w_per_rpm);
  REQUIRE(m.base_paths.size() == 1);
  CHECK(fs::path(m.base_paths[0]).filename() == "router-2.2kw-vfd.toml");
  // Each value says which file gives it.
  CHECK(m.values.at("power.machine_rate_per_hour").file == path);
  CHECK(m.values.at("power.machine_rate_per_hour").line == 4);
  CHECK(m.values.at("power.material").file == m.base_paths[0]);
  CHECK(m.values.at("kinematics.x.rapid_mm_min").text == "5000");
}

TEST_CASE(
    "a base beside the profile comes before a shipped one of the same name, and bases chain") {
  Folder f("beside");
  f.write("generic-3axis.toml", "base = \"" + kSamples +
                                    "/generic-3axis.toml\"\n"
                                    "[power]\nprice_per_kwh = 0.33\n");
  const std::string path =
      f.write("mill.toml", "base = \"generic-3axis.toml\"\n[power]\nco2_kg_per_kwh = 0.1\n");
  const MachineProfile m = load_profile(path, {kSamples});
  CHECK(m.power.price_per_kwh == doctest::Approx(0.33)); // the one beside, not the shipped
  CHECK(m.power.co2_kg_per_kwh == doctest::Approx(0.1));
  CHECK(m.base_paths.size() == 2);
  CHECK(m.name == load_profile(kSamples + "/generic-3axis.toml").name);
}

TEST_CASE("profiles that name each other as base are refused at the base line") {
  Folder f("cycle");
  const std::string a = f.write("a.toml", "# a\nbase = \"b\"\n");
  const std::string b = f.write("b.toml", "base = \"a.toml\"\n");
  try {
    (void)load_profile(a);
    FAIL("a cycle of bases was accepted");
  } catch (const ProfileError& e) {
    CHECK(e.key() == "base");
    CHECK(e.file() == b); // the link that closes the cycle
    CHECK(e.line() == 1);
    CHECK(std::string(e.what()).find("start from each other") != std::string::npos);
  }
  const std::string self = f.write("self.toml", "base = \"self\"\n");
  CHECK_THROWS_AS((void)load_profile(self), ProfileError);
}

TEST_CASE("a base that cannot be found, and a bad value in a base, name their files") {
  Folder f("missing");
  const std::string path = f.write("m.toml", "name = \"x\"\nbase = \"no-such-mill\"\n");
  try {
    (void)load_profile(path, {kSamples});
    FAIL("a missing base was accepted");
  } catch (const ProfileError& e) {
    CHECK(e.file() == path);
    CHECK(e.line() == 2);
    CHECK(std::string(e.what()).find("no-such-mill") != std::string::npos);
  }
  // The base says something wrong: the error is the base's file and line, not the child's.
  std::ifstream in(kSamples + "/generic-3axis.toml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = text.find("tool_change_s = ");
  REQUIRE(at != std::string::npos);
  text.replace(at, text.find('\n', at) - at, "tool_change_s = -4");
  const std::string bad_base = f.write("bad-base.toml", text);
  const std::string child = f.write("child.toml", "base = \"bad-base\"\nname = \"c\"\n");
  try {
    (void)load_profile(child);
    FAIL("a negative tool change time was accepted");
  } catch (const ProfileError& e) {
    CHECK(e.file() == bad_base);
    CHECK(e.key() == "kinematics.tool_change_s");
    CHECK(e.line() > 1);
  }
  // A misspelt key in the child is the child's.
  const std::string typo =
      f.write("typo.toml", "base = \"bad-base\"\n[kinematics]\ntool_change_s = 4\nrapidd = 1\n");
  try {
    (void)load_profile(typo);
    FAIL("a misspelt key was accepted");
  } catch (const ProfileError& e) {
    CHECK(e.file() == typo);
    CHECK(e.line() == 4);
  }
}
