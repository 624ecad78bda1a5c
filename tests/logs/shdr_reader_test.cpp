// SHDR logs: read by MTConnect type through the device file, with what is wrong with them said.
#include "log_fixtures.hpp"

#include <cmath>

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

std::vector<Diagnostic> parse(ControllerLog& log, std::string_view text,
                              const DeviceFile* devices = nullptr,
                              const LogMapping* mapping = nullptr) {
  std::vector<Diagnostic> d;
  LogReadOptions options;
  options.devices = devices;
  options.mapping = mapping;
  parse_controller_log(text, "test.shdr", log, options, d);
  finish_controller_log(log, d);
  return d;
}

std::size_t count(const ControllerLog& log, LogSignal s) {
  std::size_t n = 0;
  for (const LogObservation& o : log.observations)
    n += o.signal == s;
  return n;
}

} // namespace

TEST_CASE("SHDR: NIST's cover run read through the device file") {
  const DeviceFile devices = hurco04_devices();
  ControllerLog log;
  const auto d = read_logs(log, {log_data("cover-run.shdr")}, &devices);
  CHECK_FALSE(mentions(d, "no LINE"));
  REQUIRE(log.files.size() == 1);
  CHECK(log.files[0].format == "SHDR");
  CHECK(log.devices == std::vector<std::string>{"Hurco04"}); // the device file's only device
  CHECK(log.items[0][size_t(LogSignal::Line)] == "Block_Number (LINE)");
  CHECK(log.items[0][size_t(LogSignal::RapidOverride)] ==
        "Rapid_Override (PATH_FEEDRATE_OVERRIDE RAPID)");
  CHECK(count(log, LogSignal::Line) == 288);
  // Program_Runtime_Seconds is an ACCUMULATED_TIME: read, and listed as not used.
  CHECK(mentions(log.unused_items, "Program_Runtime_Seconds (ACCUMULATED_TIME)"));
  for (std::size_t i = 1; i < log.observations.size(); ++i)
    CHECK(log.observations[i - 1].t_s <= log.observations[i].t_s);
}

TEST_CASE("SHDR: without a device file, items named by their type are still read") {
  ControllerLog log;
  const auto d = parse(log, "2020-01-01T00:00:00Z|execution|ACTIVE|line|12|Fovr|100\n"
                            "2020-01-01T00:00:01Z|path_feedrate|20.5\n");
  CHECK(count(log, LogSignal::Execution) == 1);
  CHECK(count(log, LogSignal::Line) == 1);
  CHECK(count(log, LogSignal::PathFeedrate) == 1);
  CHECK(mentions(log.unused_items, "Fovr")); // not a type's name: a mapping file must say it
}

TEST_CASE("SHDR: broken records, clock jumps, conditions, bad values and UNAVAILABLE") {
  ControllerLog log;
  const auto d = parse(log, "* shdrVersion: 2\n"
                            "2020-01-01T00:00:10Z|execution|ACTIVE|line|2\n"
                            "2017\n" // NIST's cleaning broke "22017" in two
                            "2020-01-01T00:00:11Z|system|FAULT|E12|1|HIGH|Overtemp|line|3\n"
                            "2020-01-01T00:00:12Z|path_feedrate|fast\n"
                            "2020-01-01T00:00:05Z|line|4\n"
                            "2020-99-01T00:00:06Z|line|5\n"
                            "2020-01-01T00:00:20Z|line|UNAVAILABLE\n");
  std::vector<double> lines;
  bool unavailable = false;
  for (const LogObservation& o : log.observations)
    if (o.signal == LogSignal::Line) {
      if (o.unavailable)
        unavailable = true;
      else
        lines.push_back(o.value);
    }
  // 22017 glued back; the condition's four fields skipped, so line 3 is read.
  CHECK(lines == std::vector<double>{4, 22017, 3});
  CHECK(unavailable);
  CHECK(mentions(d, "continue the line before"));
  CHECK(mentions(d, "the clock jumps back 7 s"));
  CHECK(log.clock_jumps.size() == 1);
  CHECK(mentions(d, "not numbers"));
  CHECK(mentions(d, "without a readable time stamp"));
}

TEST_CASE("SHDR: what holds no SHDR line is an error") {
  ControllerLog log;
  std::vector<Diagnostic> d;
  CHECK_FALSE(parse_controller_log("just some text\nand more\n", "x.txt", log, {}, d));
  CHECK(mentions(d, "no SHDR line"));
  d.clear();
  CHECK_FALSE(parse_controller_log(std::string("\x00\x01\x02\x03", 4) + std::string(100, '\0'),
                                   "x.bin", log, {}, d));
  CHECK(mentions(d, "not an MTConnect log"));
  d.clear();
  CHECK_FALSE(parse_controller_log("", "empty.txt", log, {}, d));
  CHECK(mentions(d, "empty"));
}

TEST_CASE("SHDR: a device's prefix names its device") {
  ControllerLog log;
  parse(log, "2020-01-01T00:00:00Z|mill1:execution|ACTIVE|mill2:execution|READY\n");
  CHECK(log.devices.size() == 3); // the unprefixed device, mill1, mill2
  CHECK(log.devices[1] == "mill1");
  CHECK(log.devices[2] == "mill2");
}
