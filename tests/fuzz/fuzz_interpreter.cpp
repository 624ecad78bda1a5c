// libFuzzer target: the whole interpreter on arbitrary bytes, in the dialect the first byte picks
// (one run per input, every dialect reached). It must never crash, hang or trip a sanitizer; the
// limits bound programs that loop or call themselves forever.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace {

const std::vector<ncjoule::Dialect>& dialects() {
  static const std::vector<ncjoule::Dialect> all = [] {
    std::vector<ncjoule::Dialect> out;
    for (const std::string& name : ncjoule::dialect_names())
      out.push_back(*ncjoule::find_dialect(name));
    return out;
  }();
  return all;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const ncjoule::SourceFile source = ncjoule::make_source(
      "fuzz.ngc", std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  ncjoule::InterpreterOptions options;
  options.dialect = dialects()[data[0] % dialects().size()];
  // Small limits: thousands of runs a second, and the limits themselves are exercised.
  options.max_commands = 100;
  options.max_loop_iterations = 25;
  options.max_cycle_repeats = 20;
  options.max_arc_turns = 10;
  std::size_t printed = 0;
  ncjoule::interpret(source, options, [&printed](const ncjoule::CanonCommand& command) {
    printed += ncjoule::format_canon(command).size();
    // Geometry helpers must cope with whatever the interpreter emits.
    if (command.kind == ncjoule::CanonKind::Arc) (void)ncjoule::arc_geometry(command);
    (void)ncjoule::move_length(command);
  });
  // Detection reads the file too.
  (void)ncjoule::detect_dialect(source);
  return 0;
}
