// The agent's device file gives SHDR item names their MTConnect types.
#include "log_fixtures.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("device file: NIST's Hurco04, its items' types and components") {
  const DeviceFile devices = hurco04_devices();
  const DataItemInfo* line = devices.find("Block_Number");
  REQUIRE(line);
  CHECK(line->type == "LINE");
  CHECK(line->device == "Hurco04");
  CHECK(line->component == "Path");
  const DataItemInfo* rapid = devices.find("Rapid_Override");
  REQUIRE(rapid);
  CHECK(rapid->type == "PATH_FEEDRATE_OVERRIDE");
  CHECK(rapid->sub_type == "RAPID");
  // Found by id as well as by name.
  CHECK(devices.find("Hurco04-path_11") == rapid);
  const DataItemInfo* spindle = devices.find("Spindle_Speed");
  REQUIRE(spindle);
  CHECK(spindle->component == "Rotary");
  CHECK(spindle->component_name == "C");
  CHECK(signal_of(spindle->type, spindle->sub_type, spindle->component, spindle->component_name) ==
        LogSignal::SpindleSpeed);
  CHECK_FALSE(devices.find("Block_Number", "Hurco02"));
}

TEST_CASE("device file: what is not one is said") {
  std::vector<Diagnostic> d;
  CHECK_FALSE(parse_device_file("<MTConnectDevices><Devices>", "bad.xml", d));
  REQUIRE(d.size() == 1);
  CHECK(d[0].file == "bad.xml");
  CHECK(d[0].message.find("not well-formed XML") != std::string::npos);
  d.clear();
  CHECK_FALSE(parse_device_file("<MTConnectStreams/>", "streams.xml", d));
  CHECK(mentions(d, "not an MTConnect device file"));
}
