// Shared by the log tests: the excerpts in data/ read the way the command line reads them.
#pragma once

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "ncjoule/logs.hpp"
#include "ncjoule/text_file.hpp"

namespace ncjoule::test {

inline std::string log_data(const std::string& name) {
  return std::string(NCJOULE_SOURCE_DIR) + "/tests/logs/data/" + name;
}

inline DeviceFile hurco04_devices() {
  std::vector<Diagnostic> d;
  auto devices = read_device_file(log_data("Devices-Hurco04.xml"), d);
  REQUIRE(devices);
  return *devices;
}

// Reads the files into one log (with the device file when given); the diagnostics are returned.
inline std::vector<Diagnostic> read_logs(ControllerLog& log, const std::vector<std::string>& files,
                                         const DeviceFile* devices = nullptr,
                                         const LogMapping* mapping = nullptr) {
  std::vector<Diagnostic> d;
  LogReadOptions options;
  options.devices = devices;
  options.mapping = mapping;
  for (const std::string& f : files)
    read_controller_log(f, log, options, d);
  finish_controller_log(log, d);
  return d;
}

inline ProgramOutline cover_outline() {
  std::vector<Diagnostic> d;
  auto text = read_text_file(log_data("cover.nc"), "a program", d, kDefaultMaxProgramBytes);
  REQUIRE(text);
  return outline_program(make_source(log_data("cover.nc"), *text));
}

inline bool mentions(const std::vector<std::string>& texts, const std::string& part) {
  for (const std::string& t : texts)
    if (t.find(part) != std::string::npos) return true;
  return false;
}

inline bool mentions(const std::vector<Diagnostic>& diagnostics, const std::string& part) {
  for (const Diagnostic& d : diagnostics)
    if (d.message.find(part) != std::string::npos) return true;
  return false;
}

} // namespace ncjoule::test
