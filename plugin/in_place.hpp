// Replacing a program in place (`annotate --in-place`, `strip --in-place`) safely: a file that
// another program may still be writing is never replaced. A post that has not finished keeps
// writing into the old file after the new one is renamed over it, and all it writes from then on
// is lost. So the file is checked before it is read and again just before the rename:
//
//  - it is a regular file, and not a symbolic link unless the link is meant to be followed
//    (--follow-symlinks): a link in a watched folder could point anywhere;
//  - no other process holds it open for writing, where the system can tell (Linux: /proc;
//    Windows: the file cannot be opened while denying others the right to write it);
//  - its size, modification time and inode are the ones read;
//  - a program that does not end (no M2/M30 or closing '%': perhaps cut short) must also have
//    been left alone for a quiet period (kQuietSeconds), waited for if need be.
#pragma once

#include <cstdint>
#include <string>
#ifndef _WIN32
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

// Just before the rename: why the file is no longer the one that was read, or is not finished;
// empty when it may be replaced. When `program_end` is false it waits until the file has been
// unchanged for kQuietSeconds (at most that long).
std::string in_place_changed(const std::string& path, const FileStamp& read, bool program_end);

// "process 1234 (python3)" when another process holds the file open for writing, as far as the
// system tells (Linux /proc; processes of other users are seen only by root); else empty. On
// Windows, "another program" when the file cannot be opened without sharing it for writing.
#ifdef _WIN32
std::string writer_of(const std::string& path);
#else
std::string writer_of(const FileStamp& file);
#endif

} // namespace ncjoule::cli
