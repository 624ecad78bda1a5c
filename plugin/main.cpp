// ncjoule: predicts the time and energy of a CNC milling program before it runs.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <iostream>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include "command_registry.hpp"
#include "ncjoule/log.hpp"
#include "platform.hpp"
#include "suggest.hpp"

namespace ncjoule::cli {
std::vector<SetupFunction>& registry() {
  static std::vector<SetupFunction> functions;
  return functions;
}
} // namespace ncjoule::cli

int main(int argc, char** argv) {
  using namespace ncjoule::cli;
  platform::start_console();
  CLI::App app{"ncjoule: predicts the time and energy of a CNC milling program before it runs"};
  app.require_subcommand(1);
  // One command line on every system: CLI11 would take "/x" for an option on Windows, and a path
  // such as /jobs/part.nc (which Windows reads on the current drive) would be lost.
  app.allow_windows_style_options(false);
  app.set_version_flag("--version", std::string("ncjoule ") + NCJOULE_VERSION);
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "Log what ncjoule does (to stderr)");
  // Logs go to stderr (ncjoule::logger()): stdout carries the program's output (listings, JSON).
  spdlog::set_default_logger(spdlog::stderr_logger_st("ncjoule-cli"));
  spdlog::set_level(spdlog::level::warn);
  int exit_code = kOk;
  for (const SetupFunction& setup : registry())
    setup(app, exit_code);
  app.parse_complete_callback([&] {
    if (verbose) {
      spdlog::set_level(spdlog::level::info);
      ncjoule::logger().set_level(spdlog::level::info);
    }
  });
  // Output that did not reach standard output (a full disk, a closed pipe) is a failed run, not
  // a quiet one: whatever read it has only part of it. --help and --version too.
  auto written = [](int code) -> int {
    std::cout.flush();
    if (std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout) {
      std::cerr << "ncjoule: cannot write to standard output: the output is incomplete\n";
      return kOutputError;
    }
    return code;
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    if (code != 0)
      if (const std::string hint = suggestion(app, e, argc, argv); !hint.empty())
        std::cerr << "ncjoule: " << hint << '\n';
    return written(code == 0 ? kOk : kUsage);
  } catch (const std::bad_alloc&) {
    // The memory budget (--memory-limit) is checked before the large allocations: one that
    // still fails is a fault of ncjoule's estimate of its needs.
    std::cerr << "ncjoule: internal error: out of memory (give a smaller --memory-limit, or "
                 "report the input that did this)\n";
    return kInternalError;
  } catch (const std::exception& e) {
    std::cerr << "ncjoule: internal error: " << e.what() << '\n';
    return kInternalError;
  }
  return written(exit_code);
}
