// libFuzzer target: the whole interpreter, in two dialects, on arbitrary bytes. It must never
// crash, hang or trip a sanitizer; the limits bound programs that loop or call themselves forever.
#include <cstddef>
#include <cstdint>
#include <string>

#include "ncjoule/gcode.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const ncjoule::SourceFile source =
      ncjoule::make_source("fuzz.ngc", std::string(reinterpret_cast<const char*>(data), size));
  for (const char* name : {"linuxcnc", "fanuc"}) {
    ncjoule::InterpreterOptions options;
    options.dialect = ncjoule::find_dialect(name);
    // Small limits: thousands of runs a second, and the limits themselves are exercised.
    options.max_commands = 500;
    options.max_loop_iterations = 200;
    options.max_cycle_repeats = 50;
    options.max_arc_turns = 20;
    std::size_t printed = 0;
    ncjoule::interpret(source, options, [&printed](const ncjoule::CanonCommand& command) {
      printed += ncjoule::format_canon(command).size();
      // Geometry helpers must cope with whatever the interpreter emits.
      if (command.kind == ncjoule::CanonKind::Arc) (void)ncjoule::arc_geometry(command);
      (void)ncjoule::move_length(command);
    });
  }
  // Detection reads the file too.
  (void)ncjoule::detect_dialect(source);
  return 0;
}
