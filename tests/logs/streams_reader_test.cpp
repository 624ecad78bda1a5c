// Streams documents: the same run as its SHDR, MTConnect 2.x elements, and what is not a log.
#include "log_fixtures.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("Streams: the cover run's document gives the same run as its SHDR") {
  const DeviceFile devices = hurco04_devices();
  ControllerLog shdr, xml;
  read_logs(shdr, {log_data("cover-run.shdr")}, &devices);
  // The Streams document names its items' types itself: no device file needed.
  const auto d = read_logs(xml, {log_data("cover-run.xml")});
  CHECK(xml.files[0].format == "MTConnectStreams 1.3.0.16");
  CHECK(xml.devices == std::vector<std::string>{"Hurco04"});
  CHECK(xml.items[0][size_t(LogSignal::Line)] == "Block_Number (LINE, from the log)");
  const auto a = find_runs(shdr);
  const auto b = find_runs(xml);
  REQUIRE(a.size() == 1);
  REQUIRE(b.size() == 1);
  CHECK(a[0].start_s == doctest::Approx(b[0].start_s));
  CHECK(a[0].end_s == doctest::Approx(b[0].end_s));
  CHECK(b[0].ended == "PROGRAM_COMPLETED");
  REQUIRE(a[0].lines.size() == b[0].lines.size());
  for (std::size_t i = 0; i < a[0].lines.size(); ++i) {
    CHECK(a[0].lines[i].t_s == doctest::Approx(b[0].lines[i].t_s));
    CHECK(a[0].lines[i].value == b[0].lines[i].value);
  }
}

TEST_CASE("Streams: MTConnect 2.0 names (LineNumber, Program MAIN), in sequence order") {
  const char* doc = R"(<?xml version="1.0"?>
<MTConnectStreams xmlns="urn:mtconnect.org:MTConnectStreams:2.0">
  <Header version="2.0.0.12" instanceId="1"/>
  <Streams>
    <DeviceStream name="VMC" uuid="v1">
      <ComponentStream component="Path" name="path" componentId="p1">
        <Events>
          <LineNumber dataItemId="ln" subType="ABSOLUTE" timestamp="2023-05-01T10:00:02Z" sequence="3">5</LineNumber>
          <LineNumber dataItemId="ln" subType="ABSOLUTE" timestamp="2023-05-01T10:00:01Z" sequence="2">4</LineNumber>
          <LineNumber dataItemId="lninc" subType="INCREMENTAL" timestamp="2023-05-01T10:00:01Z" sequence="4">1</LineNumber>
          <Program dataItemId="pm" subType="MAIN" timestamp="2023-05-01T10:00:00Z" sequence="1">O1234</Program>
          <Execution dataItemId="ex" timestamp="2023-05-01T10:00:00Z" sequence="1">ACTIVE</Execution>
          <PathFeedrateOverride dataItemId="ro" subType="RAPID" timestamp="2023-05-01T10:00:00Z" sequence="1">50</PathFeedrateOverride>
        </Events>
        <Samples>
          <PathFeedrate dataItemId="pf" subType="ACTUAL" timestamp="2023-05-01T10:00:01.5Z" sequence="5">UNAVAILABLE</PathFeedrate>
          <PositionTimeSeries dataItemId="pts" sampleCount="2" timestamp="2023-05-01T10:00:01Z" sequence="6">1 2</PositionTimeSeries>
        </Samples>
        <Condition><Normal dataItemId="sys" type="SYSTEM" timestamp="2023-05-01T10:00:00Z" sequence="1"/></Condition>
      </ComponentStream>
    </DeviceStream>
  </Streams>
</MTConnectStreams>)";
  ControllerLog log;
  std::vector<Diagnostic> d;
  REQUIRE(parse_controller_log(doc, "sample.xml", log, {}, d));
  finish_controller_log(log, d);
  CHECK(log.files[0].format == "MTConnectStreams 2.0.0.12");
  const auto runs = find_runs(log);
  REQUIRE(runs.size() == 1);
  CHECK(runs[0].program == "O1234");
  REQUIRE(runs[0].lines.size() == 2);
  CHECK(runs[0].lines[0].value == 4); // the INCREMENTAL count is not a line
  CHECK(runs[0].lines[1].value == 5);
  CHECK(runs[0].rapid_override.front().value == 50);
  CHECK(runs[0].ended == "end of log");
  CHECK(mentions(runs[0].data_problems, "path_feedrate UNAVAILABLE"));
}

TEST_CASE("Streams: a device file, an error document and broken XML are not logs") {
  std::vector<Diagnostic> d;
  ControllerLog log;
  CHECK_FALSE(read_controller_log(log_data("Devices-Hurco04.xml"), log, {}, d));
  CHECK(mentions(d, "give it with --devices"));
  d.clear();
  CHECK_FALSE(parse_controller_log(
      "<MTConnectError><Errors><Error errorCode=\"OUT_OF_RANGE\">too old</Error></Errors>"
      "</MTConnectError>",
      "err.xml", log, {}, d));
  CHECK(mentions(d, "OUT_OF_RANGE: too old"));
  d.clear();
  CHECK_FALSE(parse_controller_log("<MTConnectStreams>\n<Streams>\n", "cut.xml", log, {}, d));
  REQUIRE_FALSE(d.empty());
  CHECK(d[0].line >= 2);
  CHECK(mentions(d, "not well-formed XML"));
}
