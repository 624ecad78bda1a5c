#include "cli_support.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <sstream>
#include <tuple>

#include "command_registry.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/text_file.hpp"

namespace ncjoule::cli {

std::optional<SourceFile> read_source(const std::string& path, std::size_t max_bytes,
                                      std::size_t memory_budget) {
  const std::string name = path == "-" ? "<stdin>" : path;
  std::vector<Diagnostic> problems;
  // The limit of a program is an option of the command; that of a tool table is not.
  const std::string_view option = max_bytes == kMaxSettingsFileBytes ? "" : "--input-limit";
  std::optional<std::string> text =
      path == "-" ? read_text_stream(stdin, name, "an NC file", problems, max_bytes, option)
                  : read_text_file(path, "an NC file", problems, max_bytes, option);
  if (text && memory_budget > 0) {
    const std::size_t lines = count_lines(*text);
    if (std::string problem = program_memory_problem(text->size(), lines, memory_budget);
        !problem.empty()) {
      problems.push_back({Severity::Error, name, 0, 0, std::move(problem)});
      text.reset();
    }
  }
  if (!text) {
    print_diagnostics(problems);
    return std::nullopt;
  }
  return make_source(name, std::move(*text));
}

void print_diagnostics(const std::vector<Diagnostic>& diagnostics, std::size_t dropped) {
  // The same message on many lines (a tool controller with no feed rate: every feed move) is
  // one message: its first place, then how many more and the next few lines.
  constexpr std::size_t kLinesNamed = 5;
  struct Repeat {
    std::size_t count = 0;
    std::vector<int> lines;
  };
  std::map<std::tuple<Severity, std::string, std::string>, Repeat> repeats;
  std::vector<const Diagnostic*> firsts;
  for (const Diagnostic& d : diagnostics) {
    Repeat& r = repeats[{d.severity, d.file, d.message}];
    if (r.count++ == 0)
      firsts.push_back(&d);
    else if (r.lines.size() < kLinesNamed && d.line > 0)
      r.lines.push_back(d.line);
  }
  for (const Diagnostic* d : firsts) {
    std::cerr << format_diagnostic(*d);
    const Repeat& r = repeats[{d->severity, d->file, d->message}];
    if (r.count > 1) {
      std::cerr << " (" << r.count - 1 << " more time" << (r.count > 2 ? "s" : "");
      for (std::size_t k = 0; k < r.lines.size(); ++k)
        std::cerr << (k == 0 ? ": line " : ", ") << r.lines[k];
      if (r.lines.size() + 1 < r.count && !r.lines.empty()) std::cerr << ", ...";
      std::cerr << ')';
    }
    std::cerr << '\n';
  }
  if (dropped > 0)
    std::cerr << "ncjoule: " << dropped << " more diagnostics not shown (too many)\n";
}

int failed_status(const Estimate& e) {
  return e.budget_exceeded ? kBudgetExceeded : kInputError;
}

std::optional<Dialect> dialect_from_option(const std::string& name) {
  if (auto d = find_dialect(name)) return d;
  std::cerr << "ncjoule: unknown dialect '" << name << "'; known dialects: auto";
  for (const std::string& n : dialect_names())
    std::cerr << ' ' << n;
  std::cerr << '\n';
  return std::nullopt;
}

} // namespace ncjoule::cli
