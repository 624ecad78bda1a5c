#include "cli_support.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

namespace ncjoule::cli {

std::optional<SourceFile> read_source(const std::string& path) {
  std::string text;
  if (path == "-") {
    std::ostringstream buffer;
    buffer << std::cin.rdbuf();
    text = buffer.str();
  } else {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
      std::cerr << "ncjoule: cannot read " << path << ": it is a directory, not an NC file\n";
      return std::nullopt;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      std::cerr << "ncjoule: cannot read " << path << ": no such file or not readable\n";
      return std::nullopt;
    }
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad()) {
      std::cerr << "ncjoule: error while reading " << path << "\n";
      return std::nullopt;
    }
  }
  return make_source(path == "-" ? "<stdin>" : path, std::move(text));
}

void print_diagnostics(const std::vector<Diagnostic>& diagnostics, std::size_t dropped) {
  for (const Diagnostic& d : diagnostics)
    std::cerr << format_diagnostic(d) << '\n';
  if (dropped > 0)
    std::cerr << "ncjoule: " << dropped << " more diagnostics not shown (too many)\n";
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
