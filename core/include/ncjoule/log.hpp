// ncjoule's logger: the library never writes to stdout (a program's output may be G-code or
// JSON there). Everything goes to the logger named "ncjoule", on stderr, at warning level
// unless the program that loads the library says otherwise (ncjoule -v sets info).
#pragma once

#include <memory>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

namespace ncjoule {

inline spdlog::logger& logger() {
  static const std::shared_ptr<spdlog::logger> instance = [] {
    if (auto existing = spdlog::get("ncjoule")) return existing;
    auto made = spdlog::stderr_logger_mt("ncjoule");
    made->set_level(spdlog::level::warn);
    return made;
  }();
  return *instance;
}

} // namespace ncjoule
