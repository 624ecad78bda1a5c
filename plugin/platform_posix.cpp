// platform.hpp on POSIX systems: paths are bytes, the console needs nothing.
#include "platform.hpp"

#include <cstdlib>
#include <sys/stat.h>
#include <unistd.h>

namespace ncjoule::cli::platform {

void start_console() {}

bool stderr_is_terminal() {
  if (!isatty(STDERR_FILENO)) return false;
  const char* term = std::getenv("TERM");
  return !(term && std::string(term) == "dumb");
}

bool is_standard_output(const std::string& path) {
  if (path == "-") return true;
  struct stat out {
  }, target{};
  return fstat(STDOUT_FILENO, &out) == 0 && stat(path.c_str(), &target) == 0 &&
         out.st_dev == target.st_dev && out.st_ino == target.st_ino;
}

std::filesystem::path path_from_utf8(const std::string& utf8) {
  return utf8;
}

std::string utf8_from_path(const std::filesystem::path& path) {
  return path.string();
}

std::string user_config_folder() {
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg)
    return std::string(xdg) + "/ncjoule";
  const char* home = std::getenv("HOME");
  if (!home || !*home) return {};
  return std::string(home) + "/.config/ncjoule";
}

std::filesystem::path program_file() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe;
}

} // namespace ncjoule::cli::platform
