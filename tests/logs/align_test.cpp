// Runs found in a log and aligned with the programs they ran: complete or not, usable or not,
// and why.
#include "log_fixtures.hpp"

#include <cmath>
#include <numeric>

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

ProgramOutline outline(const std::string& name, const std::string& text) {
  return outline_program(make_source(name, text));
}

std::vector<LogRun> runs_of(const std::string& shdr) {
  ControllerLog log;
  std::vector<Diagnostic> d;
  REQUIRE(parse_controller_log(shdr, "t.shdr", log, {}, d));
  finish_controller_log(log, d);
  return find_runs(log);
}

// A small program with N words in tens, a tool change at its third line and M30 at its last.
const char* kSmall = "%\nO1000 (SMALL)\nN10 T2 M6\nN20 G0 X10 S1000 M3\nN30 G1 X20 F100\n"
                     "N40 G0 Z50\nN50 M30\n%\n";

} // namespace

TEST_CASE("outline: N words, tool changes, title and end line of NIST's cover") {
  const ProgramOutline p = cover_outline();
  CHECK(p.lines == 1465);
  CHECK(p.title == "O0000(NIST_MTC_CRADA_COVER_REV-A)");
  CHECK(p.end_line == 1464);
  CHECK(p.tool_at[6] == 23);
  CHECK(p.n_word[6] == 120);
  CHECK(p.n_word[1464] == 4800);
  CHECK(p.code[3] == 0); // a comment line
}

TEST_CASE("align: NIST's cover run is a whole, usable run of the cover") {
  const DeviceFile devices = hurco04_devices();
  ControllerLog log;
  read_logs(log, {log_data("cover-run.shdr")}, &devices);
  const auto runs = find_runs(log);
  REQUIRE(runs.size() == 1);
  const auto aligned = align_runs(runs, {outline("other.nc", kSmall), cover_outline()});
  REQUIRE(aligned.size() == 1);
  const RunAlignment& a = aligned[0];
  CHECK(a.program == 1);
  CHECK(a.candidates == 1);
  CHECK(a.numbering == LineNumbering::FileLine); // Block_Number is the file's line
  CHECK(a.complete);
  CHECK(a.usable);
  CHECK(a.why.empty());
  CHECK(a.marks.front().value == 1);
  CHECK(a.marks.back().value == 1464);
  CHECK(a.rapid_override_known);
  CHECK(a.rapid_override_min == doctest::Approx(1));
  CHECK_FALSE(a.feed_override_known);
  CHECK(mentions(a.notes, "feed override not logged"));
  // The stretches between line changes add up to the run.
  const auto groups = line_groups(runs[0], a);
  double sum = 0;
  for (const LineGroup& g : groups)
    sum += g.duration_s;
  CHECK(sum == doctest::Approx(runs[0].end_s - runs[0].start_s));
  CHECK(runs[0].end_s - runs[0].start_s == doctest::Approx(80.14).epsilon(1e-3));
  // One operation from the start: the whole run.
  const auto ops = stretch_times(a, runs[0].end_s, {6});
  REQUIRE(ops.size() == 1);
  CHECK(ops[0] == doctest::Approx(runs[0].end_s - runs[0].start_s));
}

TEST_CASE("align: a held run of another program is found, not fitted, and said") {
  const DeviceFile devices = hurco04_devices();
  ControllerLog log;
  read_logs(log, {log_data("held-run.shdr")}, &devices);
  const auto runs = find_runs(log);
  REQUIRE(runs.size() == 1);
  CHECK(runs[0].ended == "end of log");
  CHECK(runs[0].states.size() >= 8); // FEED_HOLD, ACTIVE, ...
  const auto aligned = align_runs(runs, {cover_outline()});
  CHECK(aligned[0].program == -1);
  CHECK(mentions(aligned[0].why, "fits none of the programs given"));
}

TEST_CASE("align: N numbers, holds, restarts and overrides") {
  const std::vector<ProgramOutline> programs{outline("small.nc", kSmall)};
  SUBCASE("a run logging N numbers is read by them") {
    const auto runs = runs_of("2020-01-01T00:00:00Z|execution|ACTIVE|line|10|tool_number|2\n"
                              "2020-01-01T00:00:05Z|line|20\n2020-01-01T00:00:06Z|line|30\n"
                              "2020-01-01T00:00:09Z|line|40\n2020-01-01T00:00:10Z|line|50\n"
                              "2020-01-01T00:00:11Z|execution|PROGRAM_COMPLETED\n");
    const auto a = align_runs(runs, programs);
    CHECK(a[0].numbering == LineNumbering::NWord);
    CHECK(a[0].usable);
    CHECK(a[0].marks.back().value == 7); // N50 is line 7
    const auto groups = line_groups(runs[0], a[0]);
    REQUIRE(groups.size() == 6);
    CHECK(groups[1].first == 3);
    CHECK(groups[1].next == 4);
    CHECK(groups[1].duration_s == doctest::Approx(5));
  }
  SUBCASE("a feed hold makes the run unusable and its stretch disturbed") {
    const auto runs = runs_of("2020-01-01T00:00:00Z|execution|ACTIVE|line|3\n"
                              "2020-01-01T00:00:05Z|line|4\n"
                              "2020-01-01T00:00:06Z|execution|FEED_HOLD\n"
                              "2020-01-01T00:00:16Z|execution|ACTIVE\n"
                              "2020-01-01T00:00:17Z|line|5\n2020-01-01T00:00:18Z|line|7\n"
                              "2020-01-01T00:00:20Z|execution|PROGRAM_COMPLETED\n");
    const auto a = align_runs(runs, programs);
    CHECK(a[0].complete);
    CHECK_FALSE(a[0].usable);
    CHECK(mentions(a[0].why, "FEED_HOLD at 00:00:06"));
    const auto groups = line_groups(runs[0], a[0]);
    CHECK_FALSE(groups[1].disturbed);
    CHECK(groups[2].disturbed); // line 4, 5 s to 17 s, held from 6 to 16
    CHECK_FALSE(groups[3].disturbed);
  }
  SUBCASE("lines that run backwards are a restart") {
    const auto runs = runs_of("2020-01-01T00:00:00Z|execution|ACTIVE|line|3\n"
                              "2020-01-01T00:00:05Z|line|5\n2020-01-01T00:00:06Z|line|3\n"
                              "2020-01-01T00:00:08Z|line|7\n"
                              "2020-01-01T00:00:20Z|execution|PROGRAM_COMPLETED\n");
    const auto a = align_runs(runs, programs, {LineNumbering::FileLine});
    CHECK(a[0].program == 0);
    CHECK_FALSE(a[0].usable);
    CHECK(mentions(a[0].why, "run backwards at 00:00:06"));
  }
  SUBCASE("a logged rapid override is used, and the knob at zero holds the run") {
    // (Rapid_Override is not a type name: a device file or mapping says what it is.)
    LogMapping mapping;
    mapping.items[LogSignal::RapidOverride] = "Rapid_Override";
    ControllerLog log;
    std::vector<Diagnostic> d;
    LogReadOptions options;
    options.mapping = &mapping;
    REQUIRE(parse_controller_log("2020-01-01T00:00:00Z|Rapid_Override|60|execution|ACTIVE|line|3\n"
                                 "2020-01-01T00:00:05Z|line|7|Rapid_Override|70\n"
                                 "2020-01-01T00:00:09Z|execution|PROGRAM_COMPLETED\n",
                                 "o.shdr", log, options, d));
    finish_controller_log(log, d);
    auto runs = find_runs(log);
    auto a = align_runs(runs, programs, {LineNumbering::FileLine});
    CHECK(a[0].usable);
    CHECK(a[0].rapid_override_min == doctest::Approx(0.6));
    CHECK(a[0].rapid_override_max == doctest::Approx(0.7));
    CHECK(mentions(a[0].notes, "rapid override 60-70% (logged"));
    CHECK(override_at(runs[0].rapid_override, runs[0].start_s + 1) == doctest::Approx(0.6));
    CHECK(override_at(runs[0].rapid_override, runs[0].start_s + 6) == doctest::Approx(0.7));

    ControllerLog held;
    REQUIRE(parse_controller_log("2020-01-01T00:00:00Z|Rapid_Override|0|execution|ACTIVE|line|3\n"
                                 "2020-01-01T00:00:05Z|line|7|Rapid_Override|70\n"
                                 "2020-01-01T00:00:09Z|execution|PROGRAM_COMPLETED\n",
                                 "o.shdr", held, options, d));
    finish_controller_log(held, d);
    runs = find_runs(held);
    a = align_runs(runs, programs, {LineNumbering::FileLine});
    CHECK_FALSE(a[0].usable);
    CHECK(mentions(a[0].why, "rapid override at 0%"));
    CHECK(line_groups(runs[0], a[0])[0].disturbed);
  }
  SUBCASE("a run that stops short, or starts in the middle, is not complete") {
    auto runs = runs_of("2020-01-01T00:00:00Z|execution|ACTIVE|line|3\n"
                        "2020-01-01T00:00:05Z|line|5\n"
                        "2020-01-01T00:00:06Z|execution|STOPPED\n");
    auto a = align_runs(runs, programs, {LineNumbering::FileLine});
    CHECK_FALSE(a[0].complete);
    CHECK(mentions(a[0].why, "ended at line 5 (STOPPED)"));
    runs = runs_of("2020-01-01T00:00:00Z|execution|ACTIVE|line|6\n"
                   "2020-01-01T00:00:05Z|line|7\n"
                   "2020-01-01T00:00:06Z|execution|PROGRAM_COMPLETED\n");
    a = align_runs(runs, programs, {LineNumbering::FileLine});
    CHECK(mentions(a[0].why, "did not start at the top"));
  }
}

TEST_CASE("align: the logged name decides between programs the lines fit alike") {
  const std::string twin = std::string(kSmall);
  const std::vector<ProgramOutline> programs{outline("dir/A.nc", twin), outline("dir/B.nc", twin)};
  auto runs = runs_of("2020-01-01T00:00:00Z|program|B.NC|execution|ACTIVE|line|3\n"
                      "2020-01-01T00:00:05Z|line|7\n"
                      "2020-01-01T00:00:06Z|execution|PROGRAM_COMPLETED\n");
  auto a = align_runs(runs, programs, {LineNumbering::FileLine});
  CHECK(a[0].program == 1);
  CHECK(a[0].name_matches);
  CHECK(a[0].candidates == 2);
  runs = runs_of("2020-01-01T00:00:00Z|program|C.NC|execution|ACTIVE|line|3\n"
                 "2020-01-01T00:00:05Z|line|7\n"
                 "2020-01-01T00:00:06Z|execution|PROGRAM_COMPLETED\n");
  a = align_runs(runs, programs, {LineNumbering::FileLine});
  CHECK(a[0].program == 0);
  CHECK(mentions(a[0].notes, "fit 2 of the programs given alike and the log names C.NC"));
}
