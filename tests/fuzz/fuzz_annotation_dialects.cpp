// libFuzzer target: arbitrary bytes annotated in every built-in dialect (estimated without
// removal, small limits), and what an annotated program must be:
// - strip gives the program back byte for byte (the input without any annotations it held);
// - it runs, in that dialect, exactly as the program: the same canonical commands (kind,
//   positions, values, text) from the same blocks, once the lines the annotator added (its
//   header, a block's comment on a line of its own) are set aside;
// - no line is longer than the dialect's limit, unless it was that long before.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "line_alignment.hpp"
#include "ncjoule/annotate.hpp"
#include "ncjoule/profile.hpp"

namespace {

const ncjoule::MachineProfile& machine() {
  static const ncjoule::MachineProfile profile =
      ncjoule::load_profile(NCJOULE_SOURCE_DIR "/samples/machines/generic-3axis.toml");
  return profile;
}

const std::vector<ncjoule::Dialect>& dialects() {
  static const std::vector<ncjoule::Dialect> all = [] {
    std::vector<ncjoule::Dialect> out;
    for (const std::string& name : ncjoule::dialect_names())
      out.push_back(*ncjoule::find_dialect(name));
    return out;
  }();
  return all;
}

void require(bool condition) {
  if (!condition) __builtin_trap();
}

std::vector<std::string> lines_of(const ncjoule::SourceFile& source) {
  std::vector<std::string> out;
  out.reserve(source.lines.size());
  for (std::size_t i = 0; i < source.lines.size(); ++i)
    out.emplace_back(source.line_text(i));
  return out;
}

bool same_number(double a, double b) {
  return a == b || (std::isnan(a) && std::isnan(b));
}

bool same_pose(const ncjoule::Pose& a, const ncjoule::Pose& b) {
  return std::memcmp(&a, &b, sizeof a) == 0 ||
         (same_number(a.x, b.x) && same_number(a.y, b.y) && same_number(a.z, b.z) &&
          same_number(a.a, b.a) && same_number(a.b, b.b) && same_number(a.c, b.c));
}

// What a program runs, comments set aside (an annotation is one).
std::vector<ncjoule::CanonCommand> run(const ncjoule::SourceFile& source,
                                       const ncjoule::Dialect& dialect) {
  ncjoule::InterpreterOptions options;
  options.dialect = dialect;
  options.max_commands = 30;
  options.max_loop_iterations = 10;
  options.max_cycle_repeats = 10;
  options.max_arc_turns = 10;
  options.keep_diagnostics = false;
  std::vector<ncjoule::CanonCommand> out;
  ncjoule::interpret(source, options, [&](const ncjoule::CanonCommand& c) {
    if (c.kind != ncjoule::CanonKind::Comment) out.push_back(c);
  });
  return out;
}

void check_dialect(const std::string& input, const ncjoule::SourceFile& program,
                   const ncjoule::Dialect& dialect) {
  ncjoule::EstimateOptions options;
  options.dialect = dialect;
  options.simulate_removal = false;
  options.limits.max_commands = 30;
  options.limits.max_loop_iterations = 10;
  options.limits.max_cycle_repeats = 10;
  options.limits.max_arc_turns = 10;
  options.max_samples_per_move = 16;
  options.look_ahead_batch = 4;
  const ncjoule::AnnotatedProgram result =
      ncjoule::annotate_program("fuzz.ngc", input, machine(), options);
  if (result.estimate.failed) return;
  require(ncjoule::strip(result.text) == program.text);

  const ncjoule::SourceFile annotated = ncjoule::make_source("fuzz.ngc", result.text);
  const std::vector<std::string> before = lines_of(program);
  const std::vector<std::string> after = lines_of(annotated);
  const std::vector<int> from = annotate_test::original_lines(after, before);
  require(from.size() == after.size()); // every added line is an annotation, in order

  const std::size_t limit =
      dialect.max_line_length ? dialect.max_line_length : ncjoule::kDefaultMaxLineLength;
  for (std::size_t j = 0; j < after.size(); ++j)
    require(after[j].size() <= limit ||
            (from[j] >= 0 && after[j] == before[static_cast<std::size_t>(from[j])]));

  const std::vector<ncjoule::CanonCommand> a = run(program, dialect);
  const std::vector<ncjoule::CanonCommand> b = run(annotated, dialect);
  require(a.size() == b.size());
  auto mapped = [&](int line) {
    return line >= 0 && static_cast<std::size_t>(line) < from.size() ? from[line] : -1;
  };
  for (std::size_t k = 0; k < a.size(); ++k) {
    require(a[k].kind == b[k].kind);
    require(a[k].line == mapped(b[k].line));
    require(a[k].call_line == mapped(b[k].call_line));
    require(same_pose(a[k].start, b[k].start) && same_pose(a[k].end, b[k].end));
    require(same_number(a[k].centre_first, b[k].centre_first) &&
            same_number(a[k].centre_second, b[k].centre_second));
    require(a[k].rotation == b[k].rotation && a[k].plane == b[k].plane);
    require(same_number(a[k].value, b[k].value));
    require(a[k].text == b[k].text);
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // The program as annotate sees it: without annotations the input may itself hold.
  const ncjoule::SourceFile program = ncjoule::make_source("fuzz.ngc", ncjoule::strip(text));
  for (const ncjoule::Dialect& dialect : dialects())
    check_dialect(text, program, dialect);
  return 0;
}
