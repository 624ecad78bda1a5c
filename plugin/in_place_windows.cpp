// in_place.hpp on Windows. The checks are POSIX's (in_place.cpp); what differs is how they are
// made:
//  - a file still being written: Windows locks files by share modes, and a program writing a
//    file holds a handle with write access. Opening the file for reading while denying others
//    write access (share mode without FILE_SHARE_WRITE) then fails with a sharing violation, for
//    a writer of any user; /proc has no Windows counterpart to name it.
//  - symbolic links are reparse points (GetFileAttributesW), their target
//  GetFinalPathNameByHandleW;
//  - the stamp is the volume serial number, the file index, the size and the last write time
//    (GetFileInformationByHandle).
#include "in_place.hpp"

#include "ncjoule/diagnostic.hpp"
#include "platform.hpp"

#define WIN32_LEAN_AND_MEAN
#ifndef NOMINMAX
#define NOMINMAX
#endif
#include <windows.h>

#include <algorithm>
#include <chrono>
#include <thread>

namespace ncjoule::cli {
namespace {

using platform::widen;

using platform::last_error_message;

constexpr DWORD kShareAll = FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE;

// The stamp of the file `path` names (links followed); false with the error in GetLastError().
bool stamp_of(const std::wstring& path, FileStamp& stamp) {
  const HANDLE handle = CreateFileW(path.c_str(), FILE_READ_ATTRIBUTES, kShareAll, nullptr,
                                    OPEN_EXISTING, FILE_FLAG_BACKUP_SEMANTICS, nullptr);
  if (handle == INVALID_HANDLE_VALUE) return false;
  BY_HANDLE_FILE_INFORMATION info{};
  const bool ok = GetFileInformationByHandle(handle, &info) != 0;
  const DWORD error = GetLastError();
  CloseHandle(handle);
  if (!ok) {
    SetLastError(error);
    return false;
  }
  stamp.device = info.dwVolumeSerialNumber;
  stamp.inode = (std::uint64_t(info.nFileIndexHigh) << 32) | info.nFileIndexLow;
  stamp.size = std::int64_t((std::uint64_t(info.nFileSizeHigh) << 32) | info.nFileSizeLow);
  stamp.modified = (std::uint64_t(info.ftLastWriteTime.dwHighDateTime) << 32) |
                   info.ftLastWriteTime.dwLowDateTime;
  return true;
}

double seconds_since(std::uint64_t file_time) {
  FILETIME now{};
  GetSystemTimeAsFileTime(&now);
  const std::uint64_t t = (std::uint64_t(now.dwHighDateTime) << 32) | now.dwLowDateTime;
  return (double(t) - double(file_time)) * 1e-7;
}

std::string final_path_of(const std::wstring& path) {
  const HANDLE handle = CreateFileW(path.c_str(), 0, kShareAll, nullptr, OPEN_EXISTING,
                                    FILE_FLAG_BACKUP_SEMANTICS, nullptr);
  if (handle == INVALID_HANDLE_VALUE) return {};
  std::wstring buffer(32768, L'\0');
  const DWORD n = GetFinalPathNameByHandleW(handle, buffer.data(), DWORD(buffer.size()), 0);
  CloseHandle(handle);
  if (n == 0 || n >= buffer.size()) return {};
  buffer.resize(n);
  if (buffer.rfind(L"\\\\?\\", 0) == 0) buffer.erase(0, 4); // \\?\C:\... -> C:\...
  return platform::narrow(buffer);
}

std::string still_written(const std::string& path, const std::string& writer) {
  return path + " is still being written by " + writer +
         ": run ncjoule after the program writing it has finished";
}

} // namespace

std::string writer_of(const std::string& file) {
  const HANDLE handle =
      CreateFileW(widen(file).c_str(), GENERIC_READ, FILE_SHARE_READ | FILE_SHARE_DELETE, nullptr,
                  OPEN_EXISTING, FILE_ATTRIBUTE_NORMAL, nullptr);
  if (handle != INVALID_HANDLE_VALUE) {
    CloseHandle(handle);
    return {};
  }
  return GetLastError() == ERROR_SHARING_VIOLATION ? "another program" : std::string();
}

std::string in_place_refusal(const std::string& file, bool follow_symlinks, FileStamp& stamp) {
  const std::string path = printable(file);
  const std::wstring wide = widen(file);
  const DWORD attributes = GetFileAttributesW(wide.c_str());
  if (attributes == INVALID_FILE_ATTRIBUTES) return path + ": " + last_error_message();
  if ((attributes & FILE_ATTRIBUTE_REPARSE_POINT) && !follow_symlinks) {
    const std::string target = final_path_of(wide);
    return path + " is a symbolic link (to " + (target.empty() ? "elsewhere" : printable(target)) +
           "): --in-place replaces only the file given; add --follow-symlinks to replace the "
           "file it points to, or write elsewhere with -o";
  }
  if (!stamp_of(wide, stamp)) return path + ": " + last_error_message();
  const DWORD kind = GetFileAttributesW(wide.c_str()); // of the link's target, when followed
  const HANDLE probe = CreateFileW(wide.c_str(), 0, kShareAll, nullptr, OPEN_EXISTING,
                                   FILE_FLAG_BACKUP_SEMANTICS, nullptr);
  const DWORD type = probe == INVALID_HANDLE_VALUE ? FILE_TYPE_UNKNOWN : GetFileType(probe);
  if (probe != INVALID_HANDLE_VALUE) CloseHandle(probe);
  if (type != FILE_TYPE_DISK ||
      (kind != INVALID_FILE_ATTRIBUTES && (kind & FILE_ATTRIBUTE_DIRECTORY)))
    return path + " is not a regular file: --in-place cannot replace it";
  if (const std::string writer = writer_of(file); !writer.empty())
    return still_written(path, writer);
  return {};
}

std::string in_place_changed(const std::string& file, const FileStamp& read, bool program_end) {
  const std::string path = printable(file);
  const std::wstring wide = widen(file);
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    FileStamp now;
    if (!stamp_of(wide, now))
      return path + " changed while ncjoule read it: " + last_error_message();
    if (!(now == read))
      return path + " changed while ncjoule read it (another program is writing it?): run "
                    "ncjoule again once it is finished";
    if (const std::string writer = writer_of(file); !writer.empty())
      return still_written(path, writer);
    // As on POSIX: a program without an end must have been left alone for kQuietSeconds.
    const double quiet =
        std::max(seconds_since(read.modified),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (program_end || quiet >= kQuietSeconds) return {};
    std::this_thread::sleep_for(
        std::chrono::duration<double>(std::min(kQuietSeconds - quiet, 0.25)));
  }
}

} // namespace ncjoule::cli
