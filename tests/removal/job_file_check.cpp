// Job files: stock and tool table, paths relative to the file, errors that name file, line and
// key; and the tools they give replacing the program's header comments in estimate_program.
#include <doctest/doctest.h>

#include <filesystem>
#include <numbers>

#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"

using namespace ncjoule;

namespace {

std::string errors_of(const std::vector<Diagnostic>& diagnostics) {
  std::string text;
  for (const Diagnostic& d : diagnostics)
    text += format_diagnostic(d) + "\n";
  return text;
}

} // namespace

TEST_CASE("job file: stock box and a tool table") {
  std::vector<Diagnostic> diagnostics;
  const auto job = parse_job_file(R"(
stock = "box:0,0,-20,100,60,0"
[[tool]]
number = 1
type = "flat"
diameter_mm = 12
flute_length_mm = 30
shank_diameter_mm = 12
[[tool]]
number = 2
type = "drill"
diameter_mm = 6.8
point_angle_deg = 130
[[tool]]
number = 3
type = "bullnose"
diameter_mm = 10
corner_radius_mm = 1
[[tool]]
number = 4
type = "ball"
diameter_mm = 8
)",
                                  "jobs/bracket.toml", diagnostics);
  REQUIRE_MESSAGE(job, errors_of(diagnostics));
  CHECK(diagnostics.empty());
  REQUIRE(job->stock);
  CHECK(job->stock->kind == StockSpec::Kind::Box);
  CHECK(job->stock->box.zmin == -20);
  CHECK(job->stock->box.xmax == 100);
  REQUIRE(job->tools.size() == 4);
  CHECK(job->tools.at(1).cutting_length_mm == 30);
  CHECK(job->tools.at(2).shape == ToolShape::Drill);
  CHECK(job->tools.at(2).tip_angle_deg == 130);
  CHECK(job->tools.at(3).corner_radius_mm == 1);
  CHECK(job->tools.at(4).corner_radius_mm == 4);
}

TEST_CASE("job file: units of the stock's values without one") {
  std::vector<Diagnostic> diagnostics;
  const auto inch = parse_job_file("units = \"in\"\nstock = \"box:0,0,-1,4,3,0\"\n",
                                   "part.ncjoule.toml", diagnostics);
  REQUIRE(inch);
  REQUIRE(inch->stock);
  CHECK(inch->stock->in_mm(false).box.xmax == doctest::Approx(101.6)); // whatever the program's
  const auto own = parse_job_file("units = \"in\"\nstock = \"box:0,0,-20mm,100mm,60mm,0\"\n",
                                  "part.ncjoule.toml", diagnostics);
  REQUIRE(own);
  CHECK(own->stock->in_mm(true).box.xmax == doctest::Approx(100)); // a value's own unit wins
  const auto none =
      parse_job_file("stock = \"box:0,0,-1,4,3,0\"\n", "part.ncjoule.toml", diagnostics);
  REQUIRE(none);
  CHECK(none->stock->follows_program_units());
  CHECK(diagnostics.empty());
  CHECK_FALSE(parse_job_file("units = \"cm\"\n", "part.ncjoule.toml", diagnostics));
  REQUIRE(diagnostics.size() == 1);
  CHECK(diagnostics[0].line == 1);
  CHECK(diagnostics[0].message.find("\"mm\" or \"in\"") != std::string::npos);
}

TEST_CASE("job file: a stock per setup and the work offsets") {
  std::vector<Diagnostic> diagnostics;
  const auto job = parse_job_file("units = \"in\"\n"
                                  "[[setup]]\nname = \"top\"\nstock = \"box:0,0,-1,4,3,0\"\n"
                                  "[[setup]]\n"
                                  "[[setup]]\nstock_stl = \"flipped.stl\"\n"
                                  "[work_offsets_mm]\nG54 = [-400, -200, -350.5]\n"
                                  "\"g59.1\" = [-100, -50, -300]\n",
                                  "jobs/part.ncjoule.toml", diagnostics);
  REQUIRE(job);
  CHECK(diagnostics.empty());
  REQUIRE(job->stock);
  CHECK(job->stock->in_mm(false).box.zmin == doctest::Approx(-25.4));
  REQUIRE(job->setup_stocks.size() == 2);
  CHECK_FALSE(job->setup_stocks[0]); // the second setup: from its cuts
  REQUIRE(job->setup_stocks[1]);
  CHECK(job->setup_stocks[1]->kind == StockSpec::Kind::Stl);
  CHECK(job->setup_stocks[1]->stl_units == LengthUnit::Inch);
  REQUIRE(job->work_offsets.size() == 2);
  CHECK(job->work_offsets.at(1).z == -350.5);
  CHECK(job->work_offsets.at(7).x == -100);

  for (const char* bad :
       {"stock = \"box:0,0,-1,4,3,0\"\n[[setup]]\nstock = \"box:0,0,-1,4,3,0\"\n", "setup = 3\n",
        "[work_offsets_mm]\nG60 = [0, 0, 0]\n", "[work_offsets_mm]\nG55 = [0, 0]\n",
        "[[setup]]\nstock = \"box:0,0,x,4,3,0\"\n"}) {
    CAPTURE(std::string(bad));
    std::vector<Diagnostic> problems;
    CHECK_FALSE(parse_job_file(bad, "part.ncjoule.toml", problems));
    REQUIRE_FALSE(problems.empty());
    CHECK(problems[0].line > 0);
  }
}

TEST_CASE("job file: an STL stock is found beside the job file") {
  std::vector<Diagnostic> diagnostics;
  const auto job = parse_job_file("stock_stl = \"parts/blank.stl\"\n", "jobs/a.toml", diagnostics);
  REQUIRE(job);
  REQUIRE(job->stock);
  CHECK(job->stock->kind == StockSpec::Kind::Stl);
  CHECK(std::filesystem::path(job->stock->stl_path) ==
        std::filesystem::path("jobs/parts/blank.stl"));
  const auto same = parse_job_file("stock = \"blank.STL\"\n", "jobs/a.toml", diagnostics);
  REQUIRE(same);
  CHECK(std::filesystem::path(same->stock->stl_path) == std::filesystem::path("jobs/blank.STL"));
}

TEST_CASE("job file: mistakes name the file, the line and the key") {
  struct Case {
    const char* text;
    const char* key;
    int line;
  };
  const Case cases[] = {
      {"stock = \"box:0,0,0,1,1\"\n", "stock", 1},
      {"stock = 5\n", "stock", 1},
      {"stock = \"box:0,0,-1,1,1,0\"\nstock_stl = \"a.stl\"\n", "stock_stl", 2},
      {"[[tool]]\nnumber = 1\ntype = \"square\"\ndiameter_mm = 6\n", "type", 3},
      {"[[tool]]\nnumber = 1\ntype = \"flat\"\n", "diameter_mm", 0},
      {"[[tool]]\nnumber = 1\ntype = \"flat\"\ndiameter_mm = \"six\"\n", "diameter_mm", 4},
      {"[[tool]]\ntype = \"flat\"\ndiameter_mm = 6\n", "number", 0},
      {"[[tool]]\nnumber = 3\ntype = \"bullnose\"\ndiameter_mm = 6\ncorner_radius_mm = 4\n", "T3",
       0},
      {"[[tool]]\nnumber = 1\ntype = \"flat\"\ndiameter_mm = 6\n[[tool]]\nnumber = 1\n"
       "type = \"ball\"\ndiameter_mm = 6\n",
       "defined twice", 0},
      {"stock = \n", "TOML", 1},
  };
  for (const Case& c : cases) {
    CAPTURE(c.text);
    std::vector<Diagnostic> diagnostics;
    CHECK_FALSE(parse_job_file(c.text, "job.toml", diagnostics));
    const std::string text = errors_of(diagnostics);
    CAPTURE(text);
    CHECK(text.find("job.toml") != std::string::npos);
    CHECK(text.find(c.key) != std::string::npos);
    if (c.line > 0) {
      bool at_line = false;
      for (const Diagnostic& d : diagnostics)
        at_line = at_line || (d.severity == Severity::Error && d.line == c.line && d.column > 0);
      CHECK(at_line);
    }
  }
  std::vector<Diagnostic> diagnostics;
  CHECK_FALSE(read_job_file("no/such/job.toml", diagnostics));
  CHECK(errors_of(diagnostics).find("no/such/job.toml") != std::string::npos);
  // Unknown keys are warnings: the job still reads.
  diagnostics.clear();
  CHECK(parse_job_file("stok = \"box:0,0,0,1,1,1\"\n", "job.toml", diagnostics));
  REQUIRE(diagnostics.size() == 1);
  CHECK(diagnostics[0].severity == Severity::Warning);
  CHECK(diagnostics[0].message.find("stok") != std::string::npos);
}

TEST_CASE("tools given to estimate_program replace header comments: a missing one is timed without "
          "removal") {
  const SourceFile source = make_source("slot.ngc", "(T1 D=6. CR=0. - ZMIN=-2. - FLAT END MILL)\n"
                                                    "G21 G90\nT1 M6\nS1000 M3\nG0 X0 Y0 Z5\n"
                                                    "G1 Z-2 F100\nG1 X40 F600\nG0 Z5\nM30\n");
  const MachineProfile machine =
      load_profile(std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/generic-3axis.toml");
  EstimateOptions options;
  StockSpec box;
  box.kind = StockSpec::Kind::Box;
  box.box = {-10, -10, -10, 50, 10, 0};
  options.stock = box;
  options.removal.grid_mm = 0.1;
  const Estimate from_comment = estimate_program(source, machine, options);
  REQUIRE_FALSE(from_comment.failed);
  options.tools[1] = *parse_tool_spec("1:flat:10");
  const Estimate from_option = estimate_program(source, machine, options);
  REQUIRE_FALSE(from_option.failed);
  CHECK(from_option.tools.at(1).diameter_mm == 10);
  // A 2 mm deep slot 40 long with round ends: width 6 from the comment, 10 from the option.
  const double six = (40 * 6 + std::numbers::pi * 9) * 2,
               ten = (40 * 10 + std::numbers::pi * 25) * 2;
  REQUIRE(from_comment.removal);
  REQUIRE(from_option.removal);
  CHECK(from_comment.removal->removed_mm3 == doctest::Approx(six).epsilon(3e-3));
  CHECK(from_option.removal->removed_mm3 == doctest::Approx(ten).epsilon(3e-3));

  const SourceFile bare =
      make_source("bare.ngc", "G21 G90\nT7 M6\nG0 X0 Y0 Z5\nG1 Z-1 F100\nM30\n");
  // A tool described nowhere is timed without removal, and a warning names it.
  const Estimate missing = estimate_program(bare, machine, options);
  CHECK_FALSE(missing.failed);
  REQUIRE(missing.removal);
  CHECK(missing.removal->removed_mm3 == 0);
  CHECK(missing.time_s > 0);
  bool named = false;
  for (const Diagnostic& d : missing.diagnostics)
    named = named || (d.severity == Severity::Warning && d.message.find("T7") != std::string::npos);
  CHECK(named);
}

TEST_CASE("job file: tool numbers and sizes checked like --tool's, with their line and column") {
  auto problems = [](const std::string& tool) {
    std::vector<Diagnostic> d;
    const auto job = parse_job_file("[[tool]]\n" + tool, "job.toml", d);
    CHECK_FALSE(job.has_value());
    return d;
  };
  // 4294967297 is 2^32 + 1: cast to an int it was T1, which then cut with this 50 mm tool.
  std::vector<Diagnostic> d = problems("number = 4294967297\ntype = \"flat\"\ndiameter_mm = 50\n");
  REQUIRE_FALSE(d.empty());
  CHECK(d[0].line == 2);
  CHECK(d[0].column > 0);
  CHECK(d[0].message.find("1000000") != std::string::npos);
  CHECK_FALSE(problems("number = 2\ntype = \"flat\"\ndiameter_mm = inf\n").empty());
  CHECK_FALSE(problems("number = 2\ntype = \"flat\"\ndiameter_mm = 1e9\n").empty());
  CHECK_FALSE(
      problems("number = 2\ntype = \"drill\"\ndiameter_mm = 6\npoint_angle_deg = nan\n").empty());
  CHECK_FALSE(
      problems("number = 2\ntype = \"flat\"\ndiameter_mm = 6\nflute_length_mm = -3\n").empty());
  std::vector<Diagnostic> ok;
  CHECK(parse_job_file("[[tool]]\nnumber = 1000000\ntype = \"flat\"\ndiameter_mm = 6\n", "job.toml",
                       ok)
            .has_value());
  std::vector<Diagnostic> far;
  CHECK_FALSE(parse_job_file("[work_offsets_mm]\nG54 = [1e9, 0, 0]\n", "job.toml", far));
}
