// write_output_file (output_file.hpp) on POSIX systems.
#include "output_file.hpp"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <optional>
#include <sys/stat.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/random.h>
#endif

namespace ncjoule::cli {
namespace {

std::string reason() {
  return std::strerror(errno);
}

// Writes all of `text` to the descriptor; false on the first error (errno set).
bool write_all(int fd, std::string_view text) {
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

std::string directory_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string base_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// ---------------------------------------------------------------------------------------------
// Names
// ---------------------------------------------------------------------------------------------

// The descriptor a name stands for: /dev/stdout, /dev/stderr, /dev/fd/N, /proc/self/fd/N and
// /proc/PID/fd/N of this process; -1 for any other name. Opening such a name would open the file
// behind the descriptor anew, at its start: what a shell appends to (>>) or has written to
// already would be overwritten, and renaming over it would replace it.
int descriptor_alias(const std::string& path) {
  if (path == "/dev/stdout") return 1;
  if (path == "/dev/stderr") return 2;
  for (const std::string& prefix : {std::string("/dev/fd/"), std::string("/proc/self/fd/"),
                                    "/proc/" + std::to_string(::getpid()) + "/fd/"}) {
    if (path.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string number = path.substr(prefix.size());
    if (number.empty() || number.size() > 9 ||
        number.find_first_not_of("0123456789") != std::string::npos)
      return -1;
    return std::atoi(number.c_str());
  }
  return -1;
}

struct Resolved {
  std::string path;    // the file the text goes to (links followed)
  int descriptor = -1; // >= 0: write to this open descriptor instead
  std::string error;
};

// Follows the target's symbolic links one at a time, as far as they may be followed: a link is
// followed only when it belongs to the user or to the system (root), so that a link another
// user planted in a shared folder (/tmp, a world-writable work folder) cannot send the text onto
// a file of theirs choosing. The system's own /dev/stdout is root's.
Resolved resolve(const std::string& target) {
  Resolved r;
  r.path = target;
  for (int hop = 0; hop < 40; ++hop) {
    if ((r.descriptor = descriptor_alias(r.path)) >= 0) return r;
    struct stat info {};
    if (::lstat(r.path.c_str(), &info) != 0 || !S_ISLNK(info.st_mode)) return r;
    if (info.st_uid != ::geteuid() && info.st_uid != 0) {
      r.error = "cannot write " + target + ": " + (hop == 0 ? std::string("it") : r.path) +
                " is a symbolic link of another user (uid " + std::to_string(info.st_uid) +
                "), which ncjoule does not follow: write to another name";
      return r;
    }
    std::string next(std::size_t(info.st_size > 0 ? info.st_size : 4096) + 1, '\0');
    const ssize_t n = ::readlink(r.path.c_str(), next.data(), next.size());
    if (n < 0 || std::size_t(n) >= next.size()) {
      r.error = "cannot write " + target + ": cannot read the link " + r.path + ": " + reason();
      return r;
    }
    next.resize(std::size_t(n));
    if (next.empty() || next[0] != '/') next = directory_of(r.path) + "/" + next;
    r.path = next;
  }
  r.error = "cannot write " + target + ": too many levels of symbolic links";
  return r;
}

// ---------------------------------------------------------------------------------------------
// Temporary files
// ---------------------------------------------------------------------------------------------

constexpr std::string_view kTempMark = ".ncjoule-";
// Longest part of the target's name a temporary's name keeps: with the mark, a process number
// and 12 random characters it stays within the 255 bytes a name may have (a 255-byte program
// name can be replaced too).
constexpr std::size_t kTempBaseBytes = 200;
constexpr std::size_t kRandomChars = 12;

std::string random_text() {
  static constexpr char kAlphabet[] = "0123456789abcdefghijklmnopqrstuvwxyz";
  unsigned char bytes[kRandomChars] = {};
  std::size_t got = 0;
#ifdef __linux__
  const ssize_t n = ::getrandom(bytes, sizeof bytes, GRND_NONBLOCK);
  if (n > 0) got = std::size_t(n);
#endif
  if (got < sizeof bytes) {
    const int fd = ::open("/dev/urandom", O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
      const ssize_t n = ::read(fd, bytes, sizeof bytes);
      if (n > 0) got = std::size_t(n);
      ::close(fd);
    }
  }
  // O_EXCL still makes a guessed name harmless; this only keeps names apart without a source.
  for (std::size_t i = got; i < sizeof bytes; ++i) {
    timespec t{};
    clock_gettime(CLOCK_MONOTONIC, &t);
    bytes[i] = static_cast<unsigned char>(t.tv_nsec ^ (::getpid() << i) ^ (i * 131));
  }
  std::string out;
  for (unsigned char b : bytes)
    out += kAlphabet[b % 36];
  return out;
}

// ".NAME.ncjoule-PID-": what every temporary of a target's begins with (NAME cut to
// kTempBaseBytes), and its process number after it.
std::string temp_prefix(const std::string& base) {
  return "." + base.substr(0, kTempBaseBytes) + std::string(kTempMark);
}

// The temporary file being written, removed by a signal that ends the program before the signal
// ends it as it would have: an interrupted write leaves neither a changed target nor a stray
// file. A plain buffer, because a signal handler may only call async-signal-safe functions.
char pending_temp[4096] = {};

void remove_pending_temp(int signal_number) {
  if (pending_temp[0] != '\0') ::unlink(pending_temp);
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

// Every signal whose default action ends the program (SIGKILL and SIGSTOP cannot be caught: the
// temporary's name then tells stale_temporaries() what it was).
constexpr int kEndingSignals[] = {SIGHUP,    SIGINT,  SIGQUIT, SIGILL,    SIGTRAP, SIGABRT,
                                  SIGBUS,    SIGFPE,  SIGUSR1, SIGSEGV,   SIGUSR2, SIGPIPE,
                                  SIGALRM,   SIGTERM, SIGXCPU, SIGVTALRM, SIGPROF, SIGSYS,
#ifdef SIGPWR
                                  SIGPWR,
#endif
#ifdef SIGSTKFLT
                                  SIGSTKFLT,
#endif
                                  SIGIO};
constexpr std::size_t kSignalCount = sizeof kEndingSignals / sizeof kEndingSignals[0];

// For the life of a named temporary file: the handler above on the signals that end a program
// (unless they are ignored), and SIGXFSZ ignored, so that a file size limit (ulimit -f) makes
// the write fail with EFBIG and be reported like a full disk instead of killing the program.
class PendingTemp {
public:
  PendingTemp() {
    struct sigaction cleanup {};
    cleanup.sa_handler = remove_pending_temp;
    sigemptyset(&cleanup.sa_mask);
    for (std::size_t k = 0; k < kSignalCount; ++k) {
      ::sigaction(kEndingSignals[k], nullptr, &previous_[k]);
      if (previous_[k].sa_handler != SIG_IGN) ::sigaction(kEndingSignals[k], &cleanup, nullptr);
    }
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    ::sigaction(SIGXFSZ, &ignore, &previous_file_size_);
  }
  ~PendingTemp() {
    pending_temp[0] = '\0';
    for (std::size_t k = 0; k < kSignalCount; ++k)
      ::sigaction(kEndingSignals[k], &previous_[k], nullptr);
    ::sigaction(SIGXFSZ, &previous_file_size_, nullptr);
  }
  // From now on a signal removes `path` (empty: nothing).
  void name(const std::string& path) {
    if (path.size() < sizeof pending_temp) std::memcpy(pending_temp, path.c_str(), path.size() + 1);
  }
  PendingTemp(const PendingTemp&) = delete;
  PendingTemp& operator=(const PendingTemp&) = delete;

private:
  struct sigaction previous_[kSignalCount] {};
  struct sigaction previous_file_size_ {};
};

// The temporary file of one write: unnamed while it is written where the system allows it
// (O_TMPFILE), named only once complete, just before the rename; removed unless kept.
class TempFile {
public:
  TempFile(std::string folder, const std::string& base)
      : folder_(std::move(folder)), prefix_(temp_prefix(base)) {}
  ~TempFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!name_.empty() && !kept_) ::unlink(name_.c_str());
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  // Opens it: empty, or why not.
  std::string open() {
#ifdef O_TMPFILE
    fd_ = ::open(folder_.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0600);
    if (fd_ >= 0) return {};
#endif
    return open_named();
  }
  int fd() const {
    return fd_;
  }
  const std::string& name() const {
    return name_;
  }

  // Gives the complete file its name (an unnamed one) and closes it: empty, or why not.
  std::string finish(PendingTemp& pending) {
    if (name_.empty()) {
      // linkat of /proc/self/fd/N is how an unnamed file gets a name without privileges.
      for (int attempt = 0; attempt < 100 && name_.empty(); ++attempt) {
        const std::string candidate = new_name();
        pending.name(candidate);
        const std::string self = "/proc/self/fd/" + std::to_string(fd_);
        if (::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, candidate.c_str(), AT_SYMLINK_FOLLOW) == 0)
          name_ = candidate;
        else if (errno != EEXIST)
          return "cannot name the new file in " + folder_ + ": " + reason();
      }
      if (name_.empty()) return "cannot name the new file in " + folder_;
    } else {
      pending.name(name_);
    }
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) return "cannot write " + name_ + ": " + reason();
    return {};
  }
  // The rename took it: nothing to remove.
  void keep() {
    kept_ = true;
  }
  // Without a name yet (unnamed, O_TMPFILE): the system removes it when it is closed.
  bool unnamed() const {
    return name_.empty();
  }
  // Starts over with a named file (where an unnamed one cannot be named: no /proc).
  std::string reopen_named() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    return open_named();
  }

private:
  std::string new_name() const {
    return folder_ + "/" + prefix_ + std::to_string(::getpid()) + "-" + random_text();
  }
  std::string open_named() {
    for (int attempt = 0; attempt < 100; ++attempt) {
      const std::string candidate = new_name();
      fd_ = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
      if (fd_ >= 0) {
        name_ = candidate;
        return {};
      }
      if (errno != EEXIST) return "cannot create a file in " + folder_ + ": " + reason();
    }
    return "cannot create a file in " + folder_ + ": no free name";
  }

  std::string folder_;
  std::string prefix_;
  std::string name_;
  int fd_ = -1;
  bool kept_ = false;
};

// Writes to an open descriptor (standard output or error by another name), where it stands.
std::string write_descriptor(int fd, const std::string& target, std::string_view text) {
  std::fflush(stdout);
  std::fflush(stderr);
  if (::fcntl(fd, F_GETFD) < 0) return "cannot write " + target + ": it is not open";
  if (!write_all(fd, text)) return "cannot write " + target + ": " + reason();
  return {};
}

// Devices, pipes and terminals cannot be replaced by a rename: they are written in place, from
// where they stand (no truncation: a device has nothing to truncate, and a pipe cannot be).
std::string write_direct(const std::string& path, const std::string& target,
                         std::string_view text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) return "cannot open " + target + ": " + reason();
  const bool written = write_all(fd, text);
  const std::string why = written ? std::string() : reason();
  if (::close(fd) != 0 && written) return "cannot write " + target + ": " + reason();
  if (!written) return "cannot write " + target + ": " + why;
  return {};
}

bool process_alive(long pid) {
  if (pid <= 0) return false;
  return ::kill(pid_t(pid), 0) == 0 || errno == EPERM;
}

#ifdef RENAME_EXCHANGE
constexpr unsigned kExchange = RENAME_EXCHANGE;
#else
constexpr unsigned kExchange = 2; // Linux's RENAME_EXCHANGE, for older C libraries' headers
#endif

// Swaps two names (Linux renameat2 RENAME_EXCHANGE); false where the system or the file system
// cannot.
bool exchange(const std::string& a, const std::string& b) {
#ifdef __linux__
  return ::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), kExchange) == 0;
#else
  (void)a;
  (void)b;
  errno = ENOSYS;
  return false;
#endif
}

} // namespace

std::string create_new_file(const std::string& folder, const std::string& stem,
                            std::string_view text, std::string& path) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    path = folder + "/" + stem + random_text();
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd < 0) {
      if (errno == EEXIST) continue;
      return "cannot create a file in " + folder + ": " + reason();
    }
    const bool written = write_all(fd, text);
    const std::string why = written ? std::string() : reason();
    ::close(fd);
    if (!written) {
      ::unlink(path.c_str());
      return "cannot write " + path + ": " + why;
    }
    return {};
  }
  return "cannot create a file in " + folder + ": no free name";
}

std::vector<std::string> stale_temporaries(const std::string& folder, bool remove) {
  std::vector<std::string> found;
  DIR* dir = ::opendir(folder.c_str());
  if (!dir) return found;
  while (const dirent* entry = ::readdir(dir)) {
    const std::string name = entry->d_name;
    // ".NAME.ncjoule-PID-RANDOM"
    if (name.size() < 2 || name[0] != '.') continue;
    const std::size_t mark = name.rfind(kTempMark);
    if (mark == std::string::npos || mark == 0) continue;
    const std::string tail = name.substr(mark + kTempMark.size());
    const std::size_t dash = tail.find('-');
    if (dash == std::string::npos || dash == 0 || tail.size() - dash - 1 != kRandomChars) continue;
    const std::string pid = tail.substr(0, dash);
    if (pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) continue;
    if (tail.find_first_not_of("0123456789abcdefghijklmnopqrstuvwxyz", dash + 1) !=
        std::string::npos)
      continue;
    if (process_alive(std::atol(pid.c_str()))) continue; // a run still writing it
    const std::string path = folder + "/" + name;
    struct stat info {};
    if (::lstat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode) || info.st_uid != ::geteuid())
      continue;
    if (remove) {
      if (::unlink(path.c_str()) == 0)
        found.push_back("removed " + path + ", a temporary file left by an interrupted run (" +
                        std::to_string(info.st_size) + " bytes, process " + pid + ")");
    } else {
      found.push_back(path + " is a temporary file left by an interrupted run (" +
                      std::to_string(info.st_size) + " bytes, process " + pid + ")");
    }
  }
  ::closedir(dir);
  return found;
}

std::string write_output_file(const std::string& target, std::string_view text,
                              const WriteOptions& options) {
  if (target == "-") {
    if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0)
      return "cannot write to standard output: " + reason();
    return {};
  }
  const Resolved resolved = resolve(target);
  if (!resolved.error.empty()) return resolved.error;
  if (resolved.descriptor >= 0) return write_descriptor(resolved.descriptor, target, text);
  const std::string& path = resolved.path;
  struct stat info {};
  const bool exists = ::stat(path.c_str(), &info) == 0;
  if (exists && S_ISDIR(info.st_mode)) return "cannot write " + target + ": it is a directory";
  if (exists && !S_ISREG(info.st_mode)) return write_direct(path, target, text);
  // Replacing a file with other names would leave them with the old text: said, not done.
  if (exists && info.st_nlink > 1)
    return "cannot replace " + target + ": it has " + std::to_string(info.st_nlink) +
           " hard links, which would keep the old text (write to another file with -o)";

  const std::string folder = directory_of(path);
  const std::string base = base_of(path);
  // What killed runs left in the folder (their process has ended) goes now, and the user is told.
  for (std::string& removed : stale_temporaries(folder, true))
    if (options.notes) options.notes->push_back(std::move(removed));

  PendingTemp pending;
  TempFile temp(folder, base);
  if (std::string why = temp.open(); !why.empty()) return "cannot write " + target + ": " + why;
  if (!temp.unnamed()) pending.name(temp.name());
  // The new file gets the old one's permissions, or the usual ones for a new file.
  mode_t mode = 0666;
  if (exists) {
    mode = info.st_mode & 07777;
  } else {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    mode &= ~mask;
  }
  auto fill = [&]() -> std::string {
    if (!write_all(temp.fd(), text)) return "cannot write " + target + ": " + reason();
    if (::fchmod(temp.fd(), mode) != 0)
      return "cannot set the permissions of the new " + target + ": " + reason();
    // The replacement keeps the old file's owner and group; when it cannot (another user's file
    // in a folder we may write), the file is left alone rather than given to us.
    if (exists && (info.st_uid != ::geteuid() || info.st_gid != ::getegid()) &&
        ::fchown(temp.fd(), info.st_uid, info.st_gid) != 0)
      return "cannot keep the owner and group of " + target + " (" + reason() +
             "): write to another file with -o";
    if (::fsync(temp.fd()) != 0) return "cannot write " + target + ": " + reason();
    return {};
  };
  if (std::string why = fill(); !why.empty()) return why;

  // The in-place checks, now that the new text is complete: what was read is still what is
  // there, nobody is writing it, and (held until the rename) nobody starts to.
  std::optional<QuietProof> proof;
  if (options.in_place) {
    proof.emplace(path, *options.in_place);
    if (std::string why = proof->prove(); !why.empty()) return why;
  }
  if (std::string why = temp.finish(pending); !why.empty()) {
    if (!temp.unnamed()) return "cannot write " + target + ": " + why;
    // No /proc to name an unnamed file by: written again under a name.
    if (std::string again = temp.reopen_named(); !again.empty())
      return "cannot write " + target + ": " + again;
    pending.name(temp.name());
    if (std::string again = fill(); !again.empty()) return again;
    if (std::string again = temp.finish(pending); !again.empty())
      return "cannot write " + target + ": " + again;
  }
  if (proof) {
    // Swapped, so that the old file keeps a name until it is known that no program came to
    // write it meanwhile; swapped back if one did.
    if (exchange(temp.name(), path)) {
      if (proof->disturbed()) {
        exchange(temp.name(), path);
        return printable(target) +
               " was opened for writing by another program just as ncjoule replaced it: it is "
               "put back as it was; run ncjoule again once that program has finished";
      }
      return {}; // the temporary's name now holds the old file, which ~TempFile removes
    }
  }
  if (::rename(temp.name().c_str(), path.c_str()) != 0)
    return "cannot replace " + target + ": " + reason();
  temp.keep();
  return {};
}

} // namespace ncjoule::cli
