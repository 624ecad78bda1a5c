// CAMotics projects: the workpiece its author set (not an automatic one), the tools with their
// own units and shapes, and what a damaged project says.
#include <doctest/doctest.h>

#include <cmath>

#include "ncjoule/projects.hpp"

using namespace ncjoule;

namespace {

// CAMotics' own bear example (examples/bear/bear.camotics), as CAMotics writes it.
const char* kBear = R"({
      "units": "metric",
      "resolution-mode": "high",
      "resolution": 0.294723,
      "tools": {
        "1": {
          "units": "imperial",
          "shape": "ballnose",
          "length": 1,
          "diameter": 0.125,
          "description": ""
        }
      },
      "workpiece": {
        "automatic": false,
        "margin": 0,
        "bounds": {
          "min": [0, 0, -20],
          "max": [80, 80, 0]
        }
      },
      "files": [
        "bear.nc"
      ]
    })";

std::string with_workpiece(const std::string& workpiece, const std::string& tools = "{}") {
  return R"({"units": "imperial", "tools": )" + tools + R"(, "workpiece": )" + workpiece +
         R"(, "files": ["part.ngc", "other.ngc"]})";
}

} // namespace

TEST_CASE("a CAMotics project gives its workpiece in mm and its tools in their own units") {
  std::vector<Diagnostic> d;
  const auto p = parse_camotics_project(kBear, "job/bear.camotics", "job/bear.nc", d);
  REQUIRE(p);
  CHECK(d.empty());
  REQUIRE(p->stock);
  CHECK(p->stock->kind == StockSpec::Kind::Box);
  CHECK(p->stock->from == "camotics");
  CHECK(p->stock->origin == "CAMotics project bear.camotics");
  CHECK(p->stock->box.zmin == -20);
  CHECK(p->stock->box.xmax == 80);
  // The bounds are mm even in an inch program: the units say so.
  CHECK(p->stock->in_mm(true).box.xmax == 80);
  REQUIRE(p->tools.count(1));
  const Tool& t = p->tools.at(1);
  CHECK(t.shape == ToolShape::BallEndMill);
  CHECK(t.diameter_mm == doctest::Approx(3.175));
  CHECK(t.corner_radius_mm == doctest::Approx(1.5875));
  // A project that names another program is not this one's.
  CHECK_FALSE(parse_camotics_project(kBear, "job/bear.camotics", "job/tiger.nc", d));
  CHECK_FALSE(parse_camotics_project(kBear, "job/bear.camotics", "elsewhere/bear.nc", d));
  CHECK(d.empty());
}

TEST_CASE("a CAMotics project's automatic workpiece is CAMotics' guess and is not taken") {
  std::vector<Diagnostic> d;
  const auto p = parse_camotics_project(
      with_workpiece(R"({"automatic": true, "bounds": {"min": [0,0,-3], "max": [9,9,0]}})"),
      "a/p.camotics", "a/part.ngc", d);
  REQUIRE(p);
  CHECK_FALSE(p->stock);
  REQUIRE(d.size() == 1);
  CHECK(d[0].severity == Severity::Note);
  CHECK(d[0].message.find("automatic") != std::string::npos);
}

TEST_CASE("CAMotics tools: cones take their angle from diameter and length, spheroids only balls") {
  std::vector<Diagnostic> d;
  const std::string tools = R"({
    "2": {"units": "metric", "shape": "conical", "length": 5, "diameter": 10},
    "3": {"units": "imperial", "shape": "snubnose", "length": 0.5, "diameter": 0.5,
          "snub_diameter": 0.1},
    "4": {"units": "metric", "shape": "spheroid", "length": 6, "diameter": 6},
    "5": {"units": "metric", "shape": "spheroid", "length": 9, "diameter": 6},
    "6": {"units": "metric", "shape": "cylindrical", "length": 9, "diameter": 0},
    "7": {"units": "furlong", "shape": "cylindrical", "length": 9, "diameter": 6},
    "8": {"shape": "cylindrical", "diameter": 6},
    "x": {"shape": "cylindrical", "diameter": 6}})";
  const auto p = parse_camotics_project(
      with_workpiece(R"({"automatic": false, "bounds": {"min": [0,0,-3], "max": [9,9,0]}})", tools),
      "a/p.camotics", "a/other.ngc", d);
  REQUIRE(p);
  REQUIRE(p->tools.count(2));
  CHECK(p->tools.at(2).shape == ToolShape::Chamfer);
  CHECK(p->tools.at(2).tip_angle_deg == doctest::Approx(90)); // radius 5 over 5 long
  REQUIRE(p->tools.count(3));
  CHECK(p->tools.at(3).tip_diameter_mm == doctest::Approx(2.54));
  CHECK(p->tools.at(3).tip_angle_deg ==
        doctest::Approx(2 * std::atan(0.2 / 0.5) * 180 / 3.14159265358979));
  CHECK(p->tools.at(4).shape == ToolShape::BallEndMill);
  CHECK(p->tools.at(8).shape == ToolShape::FlatEndMill); // metric when it says none
  CHECK(p->tools.at(8).diameter_mm == 6);
  for (int left_out : {5, 6, 7})
    CHECK_FALSE(p->tools.count(left_out));
  // One warning for each tool left out, naming it.
  int warnings = 0;
  for (const Diagnostic& w : d)
    if (w.severity == Severity::Warning) ++warnings;
  CHECK(warnings == 4);
  CHECK(d.back().message.find("'x'") != std::string::npos);
}

TEST_CASE("a damaged CAMotics project is a warning at its line and column, never a stock") {
  std::vector<Diagnostic> d;
  CHECK_FALSE(parse_camotics_project("{\n  \"files\": [\"part.ngc\",\n  }\n", "a/p.camotics",
                                     "a/part.ngc", d));
  REQUIRE(d.size() == 1);
  CHECK(d[0].severity == Severity::Warning);
  CHECK(d[0].file == "a/p.camotics");
  CHECK(d[0].line == 3);
  CHECK(d[0].column == 3);
  CHECK(d[0].message.find("not JSON") != std::string::npos);
  for (const char* workpiece :
       {R"({"automatic": false})",
        R"({"automatic": false, "bounds": {"min": [0,0], "max": [1,1,1]}})",
        R"({"automatic": false, "bounds": {"min": [0,0,"a"], "max": [1,1,1]}})",
        R"({"automatic": false, "bounds": {"min": [5,0,0], "max": [1,1,1]}})"}) {
    CAPTURE(std::string(workpiece));
    d.clear();
    const auto p =
        parse_camotics_project(with_workpiece(workpiece), "a/p.camotics", "a/part.ngc", d);
    REQUIRE(p);
    CHECK_FALSE(p->stock);
    REQUIRE(d.size() == 1);
    CHECK(d[0].severity == Severity::Warning);
  }
  d.clear();
  CHECK_FALSE(parse_camotics_project("[1, 2]", "a/p.camotics", "a/part.ngc", d));
  CHECK(d.size() == 1);
  d.clear();
  CHECK_FALSE(parse_camotics_project(R"({"files": "part.ngc"})", "a/p.camotics", "a/part.ngc", d));
  CHECK(d.empty()); // no list of files: not a project of this program
}
