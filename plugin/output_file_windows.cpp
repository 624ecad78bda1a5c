// write_output_file (output_file.hpp) on Windows: the text goes to a temporary file next to the
// target, flushed to disk, which then replaces the target in one step, so that a failure or a
// Ctrl-C never leaves a half-written program. POSIX's rename() over an open or read-only file
// works differently on Windows, hence the Windows API throughout:
//  - ReplaceFileW keeps the replaced file's attributes and security (as the POSIX code keeps
//    its permissions and owner); where it cannot (some network shares, FAT), MoveFileExW with
//    MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH replaces it all the same;
//  - a console control handler (SetConsoleCtrlHandler, Windows' SIGINT) removes the temporary
//    file on Ctrl-C, Ctrl-Break or the console closing, then lets the program end as it would;
//  - paths are UTF-8 in ncjoule and UTF-16 for the system (platform::widen).
#include "output_file.hpp"

#include "platform.hpp"

#define WIN32_LEAN_AND_MEAN
#ifndef NOMINMAX
#define NOMINMAX
#endif
#include <windows.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <cwchar>
#include <iterator>
#include <random>

namespace ncjoule::cli {
namespace {

using platform::widen;

using platform::last_error_message;

bool write_all(HANDLE handle, std::string_view text) {
  while (!text.empty()) {
    const DWORD chunk = DWORD(std::min<std::size_t>(text.size(), std::size_t(1) << 30));
    DWORD written = 0;
    if (!WriteFile(handle, text.data(), chunk, &written, nullptr)) return false;
    text.remove_prefix(written);
  }
  return true;
}

// Devices (NUL, CON, COM1, pipes) cannot be replaced by a rename: they are written in place.
std::string write_in_place(const std::wstring& path, const std::string& target,
                           std::string_view text) {
  const HANDLE handle = CreateFileW(path.c_str(), GENERIC_WRITE, FILE_SHARE_READ | FILE_SHARE_WRITE,
                                    nullptr, OPEN_EXISTING, 0, nullptr);
  if (handle == INVALID_HANDLE_VALUE) return "cannot open " + target + ": " + last_error_message();
  const bool written = write_all(handle, text);
  const std::string why = written ? std::string() : last_error_message();
  CloseHandle(handle);
  if (!written) return "cannot write " + target + ": " + why;
  return {};
}

// The temporary file being written, removed by the console control handler. The handler runs on
// a thread of its own while the write goes on: the name is a fixed buffer, published by a flag.
wchar_t pending_temp[32768] = {};
std::atomic<bool> has_pending_temp{false};

BOOL WINAPI remove_pending_temp(DWORD) {
  // The file is open (with FILE_SHARE_DELETE): deleting it now removes it when the program ends.
  if (has_pending_temp.load()) DeleteFileW(pending_temp);
  return FALSE; // and the next handler (by default: end the program) runs
}

class PendingTemp {
public:
  explicit PendingTemp(const std::wstring& path) {
    if (path.size() >= std::size(pending_temp)) return;
    std::wmemcpy(pending_temp, path.c_str(), path.size() + 1);
    has_pending_temp.store(true);
    installed_ = SetConsoleCtrlHandler(remove_pending_temp, TRUE) != 0;
  }
  ~PendingTemp() {
    if (installed_) SetConsoleCtrlHandler(remove_pending_temp, FALSE);
    has_pending_temp.store(false);
  }
  PendingTemp(const PendingTemp&) = delete;
  PendingTemp& operator=(const PendingTemp&) = delete;

private:
  bool installed_ = false;
};

// What is at `path` now.
struct Existing {
  bool exists = false;
  bool directory = false;
  bool device = false;
  DWORD links = 1;
};

Existing look_at(const std::wstring& path) {
  Existing e;
  // FILE_FLAG_BACKUP_SEMANTICS opens folders too; symbolic links are followed.
  const HANDLE handle = CreateFileW(path.c_str(), FILE_READ_ATTRIBUTES,
                                    FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE, nullptr,
                                    OPEN_EXISTING, FILE_FLAG_BACKUP_SEMANTICS, nullptr);
  if (handle == INVALID_HANDLE_VALUE) {
    const DWORD error = GetLastError();
    // Something that cannot be looked at (no access) is there: the rename will tell.
    e.exists = error != ERROR_FILE_NOT_FOUND && error != ERROR_PATH_NOT_FOUND &&
               error != ERROR_INVALID_NAME;
    return e;
  }
  e.exists = true;
  if (GetFileType(handle) != FILE_TYPE_DISK) {
    e.device = true;
  } else if (BY_HANDLE_FILE_INFORMATION info{}; GetFileInformationByHandle(handle, &info)) {
    e.directory = (info.dwFileAttributes & FILE_ATTRIBUTE_DIRECTORY) != 0;
    e.links = info.nNumberOfLinks;
  }
  CloseHandle(handle);
  return e;
}

// The file a symbolic link names, as \\?\C:\... (which the wide API takes); empty when `path`
// is not a link or cannot be resolved.
std::wstring link_target(const std::wstring& path) {
  const DWORD attributes = GetFileAttributesW(path.c_str());
  if (attributes == INVALID_FILE_ATTRIBUTES || !(attributes & FILE_ATTRIBUTE_REPARSE_POINT))
    return {};
  const HANDLE handle =
      CreateFileW(path.c_str(), 0, FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE, nullptr,
                  OPEN_EXISTING, FILE_FLAG_BACKUP_SEMANTICS, nullptr);
  if (handle == INVALID_HANDLE_VALUE) return {};
  std::wstring final_path(MAX_PATH, L'\0');
  DWORD n = GetFinalPathNameByHandleW(handle, final_path.data(), DWORD(final_path.size()), 0);
  if (n >= final_path.size()) {
    final_path.resize(n + 1);
    n = GetFinalPathNameByHandleW(handle, final_path.data(), DWORD(final_path.size()), 0);
  }
  CloseHandle(handle);
  if (n == 0 || n >= final_path.size()) return {};
  final_path.resize(n);
  return final_path;
}

// Twelve random characters from 0-9a-z: what makes a temporary's name unguessable.
std::wstring random_text() {
  static constexpr wchar_t kAlphabet[] = L"0123456789abcdefghijklmnopqrstuvwxyz";
  std::random_device source;
  std::wstring out;
  for (int i = 0; i < 12; ++i)
    out += kAlphabet[source() % 36];
  return out;
}

// ".NAME.ncjoule-PID-": the start of every temporary of a target (NAME cut to 200 characters so
// that a name of the longest length a file may have is replaced too).
std::wstring temp_prefix(const std::wstring& base) {
  return L"." + base.substr(0, 200) + L".ncjoule-" + std::to_wstring(GetCurrentProcessId()) + L"-";
}

bool process_alive(DWORD pid) {
  const HANDLE process = OpenProcess(PROCESS_QUERY_LIMITED_INFORMATION, FALSE, pid);
  if (!process) return GetLastError() == ERROR_ACCESS_DENIED;
  DWORD code = 0;
  const bool alive = GetExitCodeProcess(process, &code) && code == STILL_ACTIVE;
  CloseHandle(process);
  return alive;
}

} // namespace

std::string create_new_file(const std::string& folder, const std::string& stem,
                            std::string_view text, std::string& path) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::wstring wide = widen(folder) + L"\\" + widen(stem) + random_text();
    const HANDLE handle = CreateFileW(wide.c_str(), GENERIC_WRITE, 0, nullptr, CREATE_NEW,
                                      FILE_ATTRIBUTE_NORMAL, nullptr);
    if (handle == INVALID_HANDLE_VALUE) {
      if (GetLastError() == ERROR_FILE_EXISTS || GetLastError() == ERROR_ALREADY_EXISTS) continue;
      return "cannot create a file in " + folder + ": " + last_error_message();
    }
    path = platform::narrow(wide);
    const bool written = write_all(handle, text);
    const std::string why = written ? std::string() : last_error_message();
    CloseHandle(handle);
    if (!written) {
      DeleteFileW(wide.c_str());
      return "cannot write " + path + ": " + why;
    }
    return {};
  }
  return "cannot create a file in " + folder + ": no free name";
}

std::vector<std::string> stale_temporaries(const std::string& folder, bool remove) {
  std::vector<std::string> found;
  const std::wstring dir = widen(folder) + L"\\";
  WIN32_FIND_DATAW entry{};
  const HANDLE search = FindFirstFileW((dir + L".*.ncjoule-*").c_str(), &entry);
  if (search == INVALID_HANDLE_VALUE) return found;
  do {
    if (entry.dwFileAttributes & (FILE_ATTRIBUTE_DIRECTORY | FILE_ATTRIBUTE_REPARSE_POINT))
      continue;
    const std::wstring name = entry.cFileName;
    const std::size_t mark = name.rfind(L".ncjoule-");
    if (mark == std::wstring::npos || mark == 0) continue;
    const std::wstring tail = name.substr(mark + 9);
    const std::size_t dash = tail.find(L'-');
    if (dash == std::wstring::npos || dash == 0 || dash > 9 || tail.size() - dash - 1 != 12)
      continue;
    if (tail.find_first_not_of(L"0123456789") < dash) continue;
    if (tail.find_first_not_of(L"0123456789abcdefghijklmnopqrstuvwxyz", dash + 1) !=
        std::wstring::npos)
      continue;
    const DWORD pid = DWORD(std::wcstoul(tail.substr(0, dash).c_str(), nullptr, 10));
    if (process_alive(pid)) continue;
    const std::string path = platform::narrow(dir + name);
    const std::string size =
        std::to_string((std::uint64_t(entry.nFileSizeHigh) << 32) | entry.nFileSizeLow);
    const std::string process = std::to_string(pid);
    if (!remove)
      found.push_back(path + " is a temporary file left by an interrupted run (" + size +
                      " bytes, process " + process + ")");
    else if (DeleteFileW((dir + name).c_str()))
      found.push_back("removed " + path + ", a temporary file left by an interrupted run (" + size +
                      " bytes, process " + process + ")");
  } while (FindNextFileW(search, &entry));
  FindClose(search);
  return found;
}

std::string write_output_file(const std::string& target, std::string_view text,
                              const WriteOptions& options) {
  if (target == "-") {
    if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0)
      return "cannot write to standard output: " + std::string(std::strerror(errno));
    return {};
  }
  // A symbolic link keeps pointing where it did: the file it names is replaced.
  std::wstring path = widen(target);
  if (std::wstring real = link_target(path); !real.empty()) path = real;
  const Existing existing = look_at(path);
  if (existing.directory) return "cannot write " + target + ": it is a directory";
  if (existing.device) return write_in_place(path, target, text);
  // Replacing a file with other names would leave them with the old text: said, not done.
  if (existing.exists && existing.links > 1)
    return "cannot replace " + target + ": it has " + std::to_string(existing.links) +
           " hard links, which would keep the old text (write to another file with -o)";

  // The temporary file: ".NAME.ncjoule-PID-RANDOM" in the target's folder (a rename within one
  // volume is what replaces a file in one step), created only if no such file exists.
  const std::size_t slash = path.find_last_of(L"\\/");
  const std::wstring folder = slash == std::wstring::npos ? L"" : path.substr(0, slash + 1);
  const std::wstring base = slash == std::wstring::npos ? path : path.substr(slash + 1);
  // What killed runs left in the folder goes now, and the user is told.
  for (std::string& removed :
       stale_temporaries(folder.empty() ? std::string(".") : platform::narrow(folder), true))
    if (options.notes) options.notes->push_back(std::move(removed));
  std::wstring temp;
  HANDLE handle = INVALID_HANDLE_VALUE;
  for (int attempt = 0; attempt < 100 && handle == INVALID_HANDLE_VALUE; ++attempt) {
    temp = folder + temp_prefix(base) + random_text();
    handle = CreateFileW(temp.c_str(), GENERIC_WRITE, FILE_SHARE_READ | FILE_SHARE_DELETE, nullptr,
                         CREATE_NEW, FILE_ATTRIBUTE_NORMAL, nullptr);
    if (handle == INVALID_HANDLE_VALUE && GetLastError() != ERROR_FILE_EXISTS &&
        GetLastError() != ERROR_ALREADY_EXISTS)
      break;
  }
  if (handle == INVALID_HANDLE_VALUE)
    return "cannot write " + target + ": cannot create a file in " +
           (folder.empty() ? std::string(".") : platform::narrow(folder)) + ": " +
           last_error_message();
  const PendingTemp pending(temp);
  std::string error;
  if (!write_all(handle, text))
    error = "cannot write " + target + ": " + last_error_message();
  else if (!FlushFileBuffers(handle))
    error = "cannot write " + target + ": " + last_error_message();
  if (!CloseHandle(handle) && error.empty())
    error = "cannot write " + target + ": " + last_error_message();
  // Replacing the file that was read: checked now that the new text is complete, right before
  // the replacement (the file unchanged, nobody holding it open for writing).
  if (error.empty() && options.in_place)
    error = in_place_changed(platform::narrow(path), options.in_place->read,
                             options.in_place->program_end);
  if (error.empty()) {
    const bool replaced = existing.exists && ReplaceFileW(path.c_str(), temp.c_str(), nullptr,
                                                          REPLACEFILE_IGNORE_MERGE_ERRORS |
                                                              REPLACEFILE_IGNORE_ACL_ERRORS,
                                                          nullptr, nullptr);
    if (!replaced && !MoveFileExW(temp.c_str(), path.c_str(),
                                  MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH))
      error = "cannot replace " + target + ": " + last_error_message();
  }
  if (!error.empty()) DeleteFileW(temp.c_str());
  return error;
}

} // namespace ncjoule::cli
