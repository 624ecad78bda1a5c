#include "in_place.hpp"

#include "ncjoule/diagnostic.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <fstream>
#include <thread>
#include <unistd.h>

namespace ncjoule::cli {
namespace {

FileStamp stamp_of(const struct stat& info) {
  FileStamp s;
  s.device = info.st_dev;
  s.inode = info.st_ino;
  s.size = info.st_size;
  s.modified = info.st_mtim;
  return s;
}

bool is_number(const char* name) {
  if (*name == '\0') return false;
  for (; *name; ++name)
    if (!std::isdigit(static_cast<unsigned char>(*name))) return false;
  return true;
}

// The open flags of one descriptor, from /proc/PID/fdinfo/FD ("flags:\t0100001", octal).
int descriptor_flags(const std::string& pid, const char* fd) {
  std::ifstream info("/proc/" + pid + "/fdinfo/" + fd);
  std::string key;
  while (info >> key) {
    if (key == "flags:") {
      std::string octal;
      info >> octal;
      return int(std::strtol(octal.c_str(), nullptr, 8));
    }
    std::getline(info, key);
  }
  return O_RDONLY;
}

std::string process_name(const std::string& pid) {
  std::ifstream comm("/proc/" + pid + "/comm");
  std::string name;
  std::getline(comm, name);
  return name.empty() ? "process " + pid : "process " + pid + " (" + name + ")";
}

double seconds_since(const timespec& t) {
  timespec now{};
  clock_gettime(CLOCK_REALTIME, &now);
  return double(now.tv_sec - t.tv_sec) + 1e-9 * double(now.tv_nsec - t.tv_nsec);
}

std::string still_written(const std::string& path, const std::string& writer) {
  return path + " is still being written by " + writer +
         ": run ncjoule after the program writing it has finished";
}

} // namespace

bool FileStamp::operator==(const FileStamp& o) const {
  return device == o.device && inode == o.inode && size == o.size &&
         modified.tv_sec == o.modified.tv_sec && modified.tv_nsec == o.modified.tv_nsec;
}

std::string writer_of(const FileStamp& file) {
  DIR* proc = ::opendir("/proc");
  if (!proc) return {};
  const std::string self = std::to_string(::getpid());
  std::string found;
  while (const dirent* process = ::readdir(proc)) {
    if (!is_number(process->d_name) || self == process->d_name) continue;
    const std::string pid = process->d_name;
    const std::string fds = "/proc/" + pid + "/fd";
    DIR* dir = ::opendir(fds.c_str()); // another user's: not readable, not seen
    if (!dir) continue;
    while (const dirent* fd = ::readdir(dir)) {
      if (!is_number(fd->d_name)) continue;
      struct stat info {};
      if (::stat((fds + "/" + fd->d_name).c_str(), &info) != 0) continue;
      if (info.st_dev != file.device || info.st_ino != file.inode) continue;
      if ((descriptor_flags(pid, fd->d_name) & O_ACCMODE) != O_RDONLY) {
        found = process_name(pid);
        break;
      }
    }
    ::closedir(dir);
    if (!found.empty()) break;
  }
  ::closedir(proc);
  return found;
}

std::string in_place_refusal(const std::string& file, bool follow_symlinks, FileStamp& stamp) {
  const std::string path = printable(file);
  struct stat info {};
  if (::lstat(file.c_str(), &info) != 0) return path + ": " + std::strerror(errno);
  if (S_ISLNK(info.st_mode)) {
    if (!follow_symlinks) {
      std::string target = "elsewhere";
      if (char* real = ::realpath(file.c_str(), nullptr)) {
        target = printable(real);
        std::free(real);
      }
      return path + " is a symbolic link (to " + target +
             "): --in-place replaces only the file given; add --follow-symlinks to replace the "
             "file it points to, or write elsewhere with -o";
    }
    if (::stat(file.c_str(), &info) != 0) return path + ": " + std::strerror(errno);
  }
  if (!S_ISREG(info.st_mode)) return path + " is not a regular file: --in-place cannot replace it";
  stamp = stamp_of(info);
  if (const std::string writer = writer_of(stamp); !writer.empty())
    return still_written(path, writer);
  return {};
}

std::string in_place_changed(const std::string& file, const FileStamp& read, bool program_end) {
  const std::string path = printable(file);
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    struct stat now {};
    if (::stat(file.c_str(), &now) != 0)
      return path + " changed while ncjoule read it: " + std::strerror(errno);
    if (!(stamp_of(now) == read))
      return path + " changed while ncjoule read it (another program is writing it?): run "
                    "ncjoule again once it is finished";
    if (const std::string writer = writer_of(read); !writer.empty())
      return still_written(path, writer);
    // A program that ends is complete; one that does not may be a post's output cut short by a
    // post still writing it: only a file left alone for a while is taken as finished.
    // (A time stamp in the future, from another machine's clock, is outwaited by watching.)
    const double quiet =
        std::max(seconds_since(read.modified),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (program_end || quiet >= kQuietSeconds) return {};
    std::this_thread::sleep_for(
        std::chrono::duration<double>(std::min(kQuietSeconds - quiet, 0.25)));
  }
}

} // namespace ncjoule::cli
