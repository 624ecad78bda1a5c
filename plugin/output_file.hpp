// Writing a command's output so that a failure never leaves a half-written file: the text goes
// to a temporary file next to the target, which is renamed over the target only when every byte
// is on disk. Every command that writes a file uses it (annotate, strip, report, calibrate, and
// the C API).
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

#include "command_registry.hpp"
#include "ncjoule/diagnostic.hpp"

#ifndef _WIN32
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

namespace ncjoule::cli {

#ifdef _WIN32
// Windows (output_file_windows.cpp, part of libncjoule): the same contract with the Windows API,
// a rename over the target that replaces it as one step (ReplaceFileW, MoveFileExW) and the
// temporary file removed on Ctrl-C and Ctrl-Break by a console control handler.
std::string write_output_file(const std::string& target, std::string_view text);
#else
namespace output_file_detail {

inline std::string reason() {
  return std::strerror(errno);
}

// Writes all of `text` to the descriptor; false on the first error (errno set).
inline bool write_all(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    text.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

inline std::string directory_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

// Devices, pipes and terminals cannot be replaced by a rename: they are written in place.
inline std::string write_in_place(const std::string& target, std::string_view text) {
  const int fd = ::open(target.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) return "cannot open " + target + ": " + reason();
  const bool written = write_all(fd, text);
  const std::string why = written ? std::string() : reason();
  if (::close(fd) != 0 && written) return "cannot write " + target + ": " + reason();
  if (!written) return "cannot write " + target + ": " + why;
  return {};
}

// The temporary file being written, removed by SIGINT, SIGTERM or SIGHUP before the signal ends
// the program as it would have: an interrupted write leaves neither a changed target nor a stray
// file. A plain buffer, because a signal handler may only call async-signal-safe functions.
inline char pending_temp[4096] = {};

inline void remove_pending_temp(int signal_number) {
  if (pending_temp[0] != '\0') ::unlink(pending_temp);
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

// For the life of a temporary file: the handler above on the signals that end a program (unless
// they are ignored), and SIGXFSZ ignored, so that a file size limit (ulimit -f) makes the write
// fail with EFBIG and be reported like a full disk instead of killing the program mid-write.
class PendingTemp {
public:
  explicit PendingTemp(const std::string& path) {
    if (path.size() < sizeof pending_temp) std::memcpy(pending_temp, path.c_str(), path.size() + 1);
    struct sigaction cleanup {};
    cleanup.sa_handler = remove_pending_temp;
    sigemptyset(&cleanup.sa_mask);
    for (std::size_t k = 0; k < kCount; ++k) {
      ::sigaction(kSignals[k], nullptr, &previous_[k]);
      if (previous_[k].sa_handler != SIG_IGN) ::sigaction(kSignals[k], &cleanup, nullptr);
    }
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    ::sigaction(SIGXFSZ, &ignore, &previous_file_size_);
  }
  ~PendingTemp() {
    for (std::size_t k = 0; k < kCount; ++k)
      ::sigaction(kSignals[k], &previous_[k], nullptr);
    ::sigaction(SIGXFSZ, &previous_file_size_, nullptr);
    pending_temp[0] = '\0';
  }
  PendingTemp(const PendingTemp&) = delete;
  PendingTemp& operator=(const PendingTemp&) = delete;

private:
  static constexpr std::size_t kCount = 3;
  static constexpr int kSignals[kCount] = {SIGINT, SIGTERM, SIGHUP};
  struct sigaction previous_[kCount] {};
  struct sigaction previous_file_size_ {};
};

} // namespace output_file_detail

// Writes `text` to `target` ("-": standard output). Returns an empty string on success, else
// what went wrong; then the target is as it was and no temporary file is left behind.
inline std::string write_output_file(const std::string& target, std::string_view text) {
  using namespace output_file_detail;
  if (target == "-") {
    if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0)
      return "cannot write to standard output: " + reason();
    return {};
  }
  // A symbolic link keeps pointing where it did: the file it names is replaced.
  std::string path = target;
  struct stat info {};
  if (::lstat(target.c_str(), &info) == 0 && S_ISLNK(info.st_mode)) {
    if (char* real = ::realpath(target.c_str(), nullptr)) {
      path = real;
      std::free(real);
    }
  }
  const bool exists = ::stat(path.c_str(), &info) == 0;
  if (exists && S_ISDIR(info.st_mode)) return "cannot write " + target + ": it is a directory";
  if (exists && !S_ISREG(info.st_mode)) return write_in_place(path, text);
  // Replacing a file with other names would leave them with the old text: said, not done.
  if (exists && info.st_nlink > 1)
    return "cannot replace " + target + ": it has " + std::to_string(info.st_nlink) +
           " hard links, which would keep the old text (write to another file with -o)";

  const std::string directory = directory_of(path);
  std::string base =
      path.substr(path.find_last_of('/') == std::string::npos ? 0 : path.find_last_of('/') + 1);
  std::string temp = directory + "/." + base + ".ncjoule-XXXXXX";
  const int fd = ::mkstemp(temp.data());
  if (fd < 0)
    return "cannot write " + target + ": cannot create a file in " + directory + ": " + reason();
  const PendingTemp pending(temp);
  std::string error;
  // The new file gets the old one's permissions, or the usual ones for a new file (mkstemp
  // makes it private).
  mode_t mode = 0666;
  if (exists) {
    mode = info.st_mode & 07777;
  } else {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    mode &= ~mask;
  }
  if (!write_all(fd, text))
    error = "cannot write " + target + ": " + reason();
  else if (::fchmod(fd, mode) != 0)
    error = "cannot set the permissions of " + temp + ": " + reason();
  // The replacement keeps the old file's owner and group; when it cannot (another user's file
  // in a folder we may write), the file is left alone rather than given to us.
  else if (exists && (info.st_uid != ::geteuid() || info.st_gid != ::getegid()) &&
           ::fchown(fd, info.st_uid, info.st_gid) != 0)
    error = "cannot keep the owner and group of " + target + " (" + reason() +
            "): write to another file with -o";
  else if (::fsync(fd) != 0)
    error = "cannot write " + target + ": " + reason();
  if (::close(fd) != 0 && error.empty()) error = "cannot write " + target + ": " + reason();
  if (error.empty() && ::rename(temp.c_str(), path.c_str()) != 0)
    error = "cannot replace " + target + ": " + reason();
  if (!error.empty()) ::unlink(temp.c_str());
  return error;
}
#endif

// Writes a rewritten program where the command line says: over `file` when `in_place`, else to
// `output` ("" or "-": standard output). Returns the exit code, after saying why on failure.
inline int write_program(const std::string& file, const std::string& output, bool in_place,
                         std::string_view text) {
  const std::string target = in_place ? file : (output.empty() ? "-" : output);
  if (const std::string error = write_output_file(target, text); !error.empty()) {
    // The names in it are the user's: printed so that they cannot drive the terminal.
    std::fprintf(stderr, "ncjoule: %s; %s\n", printable(error).c_str(),
                 in_place ? (printable(file) + " is untouched").c_str() : "nothing was written");
    return kOutputError;
  }
  return 0;
}

} // namespace ncjoule::cli
