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
#include <iomanip>
#include <sstream>
#include <sys/sysmacros.h>
#include <thread>
#include <unistd.h>
#include <vector>
#ifdef __linux__
#include <linux/magic.h>
#include <sys/vfs.h>
#endif

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
  return name.empty() ? "process " + pid : "process " + pid + " (" + printable(name) + ")";
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

// The kind of network file system the file is on ("nfs", "cifs", ...), or empty for a local
// one: there, a program on another computer may write the file without this system knowing.
std::string network_file_system(int fd) {
#ifdef __linux__
  struct statfs fs {};
  if (::fstatfs(fd, &fs) != 0) return {};
  switch (static_cast<unsigned long>(fs.f_type)) {
  case NFS_SUPER_MAGIC:
    return "nfs";
  case SMB_SUPER_MAGIC:
  case static_cast<unsigned long>(CIFS_SUPER_MAGIC):
  case static_cast<unsigned long>(SMB2_SUPER_MAGIC):
    return "cifs (a Windows or Samba share)";
  case AFS_SUPER_MAGIC:
  case AFS_FS_MAGIC:
    return "afs";
  case CEPH_SUPER_MAGIC:
    return "ceph";
  case CODA_SUPER_MAGIC:
    return "coda";
  case V9FS_MAGIC:
    return "9p";
  case FUSE_SUPER_MAGIC:
    return "fuse (sshfs or another user-space file system)";
  case OCFS2_SUPER_MAGIC:
    return "ocfs2";
  default:
    return {};
  }
#else
  (void)fd;
  return {};
#endif
}

// A lock another process holds on the file, from /proc/locks ("1: POSIX ADVISORY WRITE 1234
// 08:01:5678 0 EOF"): "process 1234 (name)", or empty. Every user's locks are listed there.
std::string lock_holder(const FileStamp& file) {
  std::ifstream locks("/proc/locks");
  if (!locks) return {};
  std::ostringstream id;
  id << std::hex << std::setfill('0') << std::setw(2) << major(file.device) << ':' << std::setw(2)
     << minor(file.device) << ':' << std::dec << file.inode;
  const std::string wanted = id.str();
  const std::string self = std::to_string(::getpid());
  std::string line;
  while (std::getline(locks, line)) {
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;)
      w.push_back(word);
    // A blocked request is "1: -> POSIX ...": the holder's line is what counts.
    if (w.size() < 6 || w[1] == "->") continue;
    if (w[5] != wanted) continue;
    if (w[4] == self) continue; // our own lease
    const std::string kind = printable(w[1]) + " lock";
    // An open file description's lock belongs to no one process ("-1").
    if (!is_number(w[4].c_str())) return "a program (an " + kind + ")";
    return process_name(w[4]) + " (a " + kind + ")";
  }
  return {};
}

#ifdef __linux__
constexpr int kSetLease = F_SETLEASE;
constexpr int kGetLease = F_GETLEASE;
#endif

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

QuietProof::~QuietProof() {
#ifdef __linux__
  if (leased_) ::fcntl(fd_, kSetLease, F_UNLCK);
#endif
  if (fd_ >= 0) ::close(fd_);
  if (io_signal_saved_) ::sigaction(SIGIO, &previous_io_, nullptr);
}

std::string QuietProof::prove() {
  const std::string path = printable(path_);
  // The quiet period first (it may wait), then the checks that hold until the rename.
  if (std::string why = in_place_changed(path_, check_.read, check_.program_end); !why.empty())
    return why;
  fd_ = ::open(path_.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (fd_ < 0) return path + " changed while ncjoule read it: " + std::strerror(errno);
  struct stat info {};
  if (::fstat(fd_, &info) != 0 || !(stamp_of(info) == check_.read))
    return path + " changed while ncjoule read it (another program is writing it?): run ncjoule "
                  "again once it is finished";
  if (const std::string share = network_file_system(fd_); !share.empty())
    return path + " is on a network file system (" + share +
           "): a program on another computer could still be writing it, which ncjoule cannot "
           "see; write the result to another file with -o and move it once the file is complete";
  if (const std::string holder = lock_holder(check_.read); !holder.empty())
    return path + " is locked by " + holder +
           ", which may still be writing it: run ncjoule after it has finished";
#ifdef __linux__
  // A lease break is signalled to the holder with SIGIO, whose default action ends a program:
  // ignored while the lease is held (disturbed() asks the kernel instead).
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  io_signal_saved_ = ::sigaction(SIGIO, &ignore, &previous_io_) == 0;
  if (::fcntl(fd_, kSetLease, F_RDLCK) == 0) {
    leased_ = true;
    return {};
  }
  const int why = errno;
  if (why == EAGAIN || why == EBUSY) {
    const std::string writer = writer_of(check_.read);
    return still_written(path, writer.empty() ? "a program the system does not name (another "
                                                "user's, or the one calling ncjoule)"
                                              : writer);
  }
#endif
  // No lease (a file system without them, or not ours to lease): what /proc shows must do. Other
  // users' processes are not shown to us, so a file they could write is not proven quiet.
  if (::geteuid() != 0 && (info.st_uid != ::geteuid() || (info.st_mode & (S_IWGRP | S_IWOTH))))
    return path + " can be written by other users, whose programs ncjoule cannot see (and the "
                  "file system grants no lease that would tell): write the result to another "
                  "file with -o";
  if (const std::string writer = writer_of(check_.read); !writer.empty())
    return still_written(path, writer);
  return {};
}

bool QuietProof::disturbed() const {
  if (fd_ < 0) return false;
  struct stat info {};
  if (::fstat(fd_, &info) != 0 || !(stamp_of(info) == check_.read)) return true;
#ifdef __linux__
  // A lease being broken reads as the type it is being broken to (F_UNLCK).
  if (leased_ && ::fcntl(fd_, kGetLease) != F_RDLCK) return true;
#endif
  return false;
}

} // namespace ncjoule::cli
