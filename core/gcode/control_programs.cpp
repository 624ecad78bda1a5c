// Reading the programs a control holds in its memory (Fanuc/Haas O9xxx macros, probing cycles,
// LinuxCNC subroutine files) from folders the user names: the edge where the interpreter's calls
// to programs outside the file meet the file system.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

#include "ncjoule/gcode.hpp"
#include "ncjoule/text.hpp"
#include "ncjoule/text_file.hpp"

namespace ncjoule {
namespace {

// Whether a file's name (lower case) holds the program `name`: for an O-number, "o9810",
// "o09810.nc" or "9810.min"; for a LinuxCNC o<name>, "name.ngc".
bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c));
  });
}

bool names_program(const std::string& file, const std::string& name) {
  const std::string stem = file.substr(0, file.find('.'));
  if (!all_digits(name)) return file == name + ".ngc";
  const std::string digits = stem.size() > 1 && stem.front() == 'o' ? stem.substr(1) : stem;
  if (!all_digits(digits)) return false;
  const auto nz = [](const std::string& d) {
    const std::size_t k = d.find_first_not_of('0');
    return k == std::string::npos ? std::string("0") : d.substr(k);
  };
  return nz(digits) == nz(name);
}

} // namespace

std::function<std::optional<SourceFile>(const std::string& name)>
control_programs_in(std::vector<std::string> folders, std::vector<Diagnostic>& diagnostics) {
  return [folders = std::move(folders),
          &diagnostics](const std::string& name) -> std::optional<SourceFile> {
    const std::string wanted = to_lower(name);
    for (const std::string& folder : folders) {
      std::error_code ec;
      std::vector<std::filesystem::path> matches;
      for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end;
           it.increment(ec)) {
        if (it->is_regular_file(ec) &&
            names_program(to_lower(it->path().filename().string()), wanted))
          matches.push_back(it->path());
      }
      if (matches.empty()) continue;
      std::sort(matches.begin(), matches.end()); // the same file whatever the folder's order
      const std::string path = matches.front().string();
      std::optional<std::string> text =
          read_text_file(path, "a program", diagnostics, kDefaultMaxProgramBytes);
      if (!text) continue;
      return make_source(path, std::move(*text));
    }
    return std::nullopt;
  };
}

} // namespace ncjoule
