// Replacing a program in place (`annotate --in-place`, `strip --in-place`, the C API's
// ncjoule_annotate_file without an output) safely: a file that another program may still be
// writing is never replaced. A post that has not finished keeps writing into the old file after
// the new one is renamed over it, and all it writes from then on is lost. So the file is checked
// before it is read, and again once the new text is complete on disk, right before the rename:
//
//  - it is a regular file, and not a symbolic link unless the link is meant to be followed
//    (--follow-symlinks): a link in a watched folder could point anywhere;
//  - no other process holds it open for writing. Linux tells that for every user's processes
//    with a read lease (fcntl F_SETLEASE), which the kernel grants only while nobody has the
//    file open for writing, and which makes a writer that opens it meanwhile wait until the
//    rename is done (and is then noticed: the old file is put back). Where no lease can be had
//    (a file system without them), the processes the system shows (/proc) are looked at, and a
//    file other users' programs could write unseen is refused. Windows: the file cannot be
//    opened while denying others the right to write it;
//  - no other process holds a lock on it (/proc/locks), and it is not on a network file system,
//    where a program on another computer could be writing it unseen: both refused, not ignored;
//  - its size, modification time and inode are the ones read;
//  - a program that does not end (no M2/M30 or closing '%': perhaps cut short) must also have
//    been left alone for a quiet period (kQuietSeconds), waited for if need be.
#pragma once

#include <cstdint>
#include <string>
#ifndef _WIN32
#include <csignal>
#include <sys/stat.h>
#endif

namespace ncjoule::cli {

// How long a file without a program end must have stayed unchanged before it is replaced.
inline constexpr double kQuietSeconds = 2.0;

// What identifies the bytes that were read: a writer changes the size or the time, a post that
// writes a new file and renames it changes the inode.
#ifdef _WIN32
// Windows (in_place_windows.cpp): the volume's serial number and the file's index stand for the
// device and the inode, the last write time (100 ns since 1601) for the modification time.
struct FileStamp {
  std::uint64_t device = 0;
  std::uint64_t inode = 0;
  std::int64_t size = 0;
  std::uint64_t modified = 0;
  bool operator==(const FileStamp& other) const = default;
};
#else
struct FileStamp {
  dev_t device = 0;
  ino_t inode = 0;
  off_t size = 0;
  timespec modified{};
  bool operator==(const FileStamp& other) const;
};
#endif

// Before `path` is read: why it may not be replaced in place (the sentence is the message, the
// exit code is 3), or an empty string; then `stamp` holds what was seen.
std::string in_place_refusal(const std::string& path, bool follow_symlinks, FileStamp& stamp);

// What a replacement in place must still hold once the new text is written: the file is the one
// that was read (`read`), and, when the program has no end, it has been left alone for
// kQuietSeconds. write_output_file (output_file.hpp) checks it right before the rename.
struct InPlaceCheck {
  FileStamp read;
  bool program_end = true;
};

// Whether the file is still the one that was read and is finished (waiting for the quiet period
// when `program_end` is false, at most that long): empty when it may be replaced, else why not.
std::string in_place_changed(const std::string& path, const FileStamp& read, bool program_end);

// "process 1234 (python3)" when another process holds the file open for writing, as far as the
// system tells (Linux /proc; processes of other users are seen only by root); else empty. On
// Windows, "another program" when the file cannot be opened without sharing it for writing.
#ifdef _WIN32
std::string writer_of(const std::string& path);
#else
std::string writer_of(const FileStamp& file);

// The last look before a file is replaced in place, held across the rename (POSIX). prove()
// opens the file, takes a read lease on it where the system grants one and checks everything
// listed above; disturbed() says, after the rename, whether a program opened the old file for
// writing meanwhile (the rename is then undone by the caller). The lease ends with the object.
class QuietProof {
public:
  QuietProof(std::string path, const InPlaceCheck& check) : path_(std::move(path)), check_(check) {}
  ~QuietProof();
  QuietProof(const QuietProof&) = delete;
  QuietProof& operator=(const QuietProof&) = delete;

  // Empty when the file may be replaced now, else why not.
  std::string prove();
  // True when a writer came for the old file after prove() (its lease is being broken) or the
  // file changed.
  bool disturbed() const;

private:
  std::string path_;
  InPlaceCheck check_;
  int fd_ = -1;
  bool leased_ = false;
  bool io_signal_saved_ = false;
  struct sigaction previous_io_ {};
};
#endif

} // namespace ncjoule::cli
