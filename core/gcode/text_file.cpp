#include "ncjoule/text_file.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>

namespace ncjoule {

std::optional<std::string> read_text_file(const std::string& path, std::string_view what,
                                          std::vector<Diagnostic>& diagnostics) {
  auto fail = [&](std::string message) -> std::optional<std::string> {
    diagnostics.push_back({Severity::Error, path, 0, 0, std::move(message)});
    return std::nullopt;
  };
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return fail("is a directory, not " + std::string(what));
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail("cannot be opened: no such file or not readable");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return fail("could not be read to the end");
  return text;
}

} // namespace ncjoule
