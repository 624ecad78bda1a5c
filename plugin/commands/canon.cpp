// `ncjoule canon FILE`: prints the canonical command stream the way `rs274 -g` does, so the
// two can be diffed.
#include <cstdio>
#include <string>

#include "cli_support.hpp"
#include "command_registry.hpp"

namespace ncjoule::cli {
namespace {

struct CanonOptions {
  std::string file;
  std::string dialect;
  std::string tool_table;
  std::string tool_units = "mm";
  bool block_delete = false;
  bool parse_only = false;
  std::size_t max_moves = kDefaultMaxMoves; // the budget of moves (ncjoule/budget.hpp)
};

// rs274's "%5ld N..... " before each line: the sequence number right-aligned in five columns.
void append_sequence(std::string& out, long sequence) {
  char buffer[32];
  char* const end = buffer + sizeof buffer;
  char* p = end;
  do {
    *--p = char('0' + sequence % 10);
    sequence /= 10;
  } while (sequence > 0);
  while (end - p < 5)
    *--p = ' ';
  out.append(p, std::size_t(end - p));
  out += " N..... ";
}

int run_canon(const CanonOptions& o) {
  auto source = read_source(o.file);
  if (!source) return kInputError;
  InterpreterOptions options;
  if (!o.dialect.empty() && o.dialect != "auto") {
    options.dialect = dialect_from_option(o.dialect);
    if (!options.dialect) return kUsage;
  }
  options.block_delete = o.block_delete;
  options.max_commands = o.max_moves;
  if (!o.tool_table.empty()) {
    auto table = read_source(o.tool_table, kMaxSettingsFileBytes);
    if (!table) return kInputError;
    std::vector<Diagnostic> diagnostics;
    options.tools = parse_tool_table(*table, o.tool_units == "inch", diagnostics);
    print_diagnostics(diagnostics);
  }
  // Lines are made in one buffer and written in large pieces: a million-block program prints
  // in a second, where a printf per line took most of the run.
  std::string lines;
  lines.reserve(1 << 17);
  long sequence = 0;
  InterpretResult result = interpret(*source, options, [&](const CanonCommand& c) {
    if (o.parse_only) return;
    const std::size_t start = lines.size();
    append_sequence(lines, sequence + 1);
    const std::size_t text_start = lines.size();
    append_canon(lines, c);
    if (lines.size() == text_start) { // a command rs274 prints no line for
      lines.resize(start);
      return;
    }
    ++sequence;
    lines += '\n';
    if (lines.size() >= (1 << 16)) {
      std::fwrite(lines.data(), 1, lines.size(), stdout);
      lines.clear();
    }
  });
  std::fwrite(lines.data(), 1, lines.size(), stdout);
  std::fflush(stdout);
  print_diagnostics(result.diagnostics);
  if (result.commands > options.max_commands) return kBudgetExceeded; // the budget of moves
  for (const Diagnostic& d : result.diagnostics)
    if (d.severity == Severity::Error) return kInputError;
  return kOk;
}

const Registration registration([](CLI::App& app, int& exit_code) {
  auto options = std::make_shared<CanonOptions>();
  CLI::App* cmd = app.add_subcommand(
      "canon", "Print the canonical motion stream in the form of `rs274 -g`, for diffing");
  cmd->add_option("file", options->file, "NC program (- for standard input)")->required();
  cmd->add_option("--dialect", options->dialect,
                  "Controller dialect (auto, linuxcnc, fanuc, haas, grbl, mach3, siemens, "
                  "heidenhain, reprap); default: detected from the file");
  cmd->add_option("-t,--tool-table", options->tool_table, "LinuxCNC tool table (.tbl)");
  cmd->add_option("--tool-units", options->tool_units,
                  "Units of the tool table's lengths (the machine's units): mm or inch")
      ->check(CLI::IsMember({"mm", "inch"}));
  cmd->add_flag("--block-delete", options->block_delete, "Skip blocks that start with /");
  cmd->add_flag("--parse-only", options->parse_only, "Interpret but print nothing (benchmarks)");
  cmd->add_option("--max-moves", options->max_moves,
                  "Most commands the program may expand to (default 20000000); beyond it the "
                  "listing stops, exit 5")
      ->check(CLI::Range(std::size_t(1), std::size_t(1e15)));
  cmd->callback([options, &exit_code] { exit_code = run_canon(*options); });
});

} // namespace
} // namespace ncjoule::cli
