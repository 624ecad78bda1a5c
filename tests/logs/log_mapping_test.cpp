// A mapping file for a control that names its data otherwise.
#include "log_fixtures.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("mapping: items, scales and execution words of another control") {
  std::vector<Diagnostic> d;
  const auto mapping = parse_log_mapping(R"(
source = "our Brand X adapter"
line_numbering = "n-word"
[items]
line = "seqno"
execution = "run_state"
path_feedrate = "feed_mm_min"
power = "kw"
[scale]
path_feedrate = 0.0166666667
power = 1000
[execution]
RUN = "ACTIVE"
HOLD = "FEED_HOLD"
END = "PROGRAM_COMPLETED"
)",
                                         "brandx.toml", d);
  REQUIRE(mapping);
  CHECK(d.empty());
  CHECK(mapping->line_numbering == LineNumbering::NWord);
  ControllerLog log;
  LogReadOptions options;
  options.mapping = &*mapping;
  REQUIRE(
      parse_controller_log("2020-01-01T00:00:00Z|run_state|RUN|seqno|100|feed_mm_min|600|kw|3.5\n"
                           "2020-01-01T00:00:05Z|run_state|END\n",
                           "x.shdr", log, options, d));
  finish_controller_log(log, d);
  const auto runs = find_runs(log);
  REQUIRE(runs.size() == 1);
  CHECK(runs[0].ended == "PROGRAM_COMPLETED");
  CHECK(runs[0].lines.at(0).value == 100);
  CHECK(runs[0].feed.at(0).value == doctest::Approx(10));
  CHECK(runs[0].power.at(0).value == doctest::Approx(3500));
  CHECK(log.items[0][size_t(LogSignal::Line)] == "seqno (mapping file)");
}

TEST_CASE("mapping: a misspelt signal or key is an error at its line") {
  std::vector<Diagnostic> d;
  CHECK_FALSE(parse_log_mapping("[items]\nline = \"a\"\nfeedrate = \"b\"\n", "m.toml", d));
  REQUIRE(d.size() == 1);
  CHECK(d[0].line == 3);
  CHECK(mentions(d, "unknown signal 'feedrate'"));
  d.clear();
  CHECK_FALSE(parse_log_mapping("[scale]\npower = -2\n", "m.toml", d));
  CHECK(mentions(d, "above zero"));
  d.clear();
  CHECK_FALSE(parse_log_mapping("line_numbering = \"lines\"\n", "m.toml", d));
  CHECK(mentions(d, "line_numbering"));
  d.clear();
  CHECK_FALSE(parse_log_mapping("[item]\nline = \"x\"\n", "m.toml", d));
  CHECK(mentions(d, "unknown key 'item'"));
  d.clear();
  CHECK_FALSE(parse_log_mapping("[items\n", "m.toml", d));
  CHECK(mentions(d, "not valid TOML"));
}
