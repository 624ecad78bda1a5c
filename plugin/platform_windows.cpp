// platform.hpp on Windows. Paths are UTF-16 there: every path ncjoule holds is UTF-8 (the program
// is built with a manifest that makes UTF-8 the process's code page, so its arguments and the C
// library's narrow file functions are UTF-8 too), and std::filesystem paths are made from UTF-16,
// because libstdc++ reads narrow strings in another code page.
#include "platform.hpp"

#define WIN32_LEAN_AND_MEAN
#ifndef NOMINMAX
#define NOMINMAX
#endif
#include <windows.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <io.h>

namespace ncjoule::cli::platform {
namespace {

bool is_console(DWORD handle_id) {
  DWORD mode = 0;
  return GetConsoleMode(GetStdHandle(handle_id), &mode) != 0;
}

// The console's code page is the console's, not the process's: put back as it was at exit.
UINT console_output_code_page = 0;
void restore_console_code_page() {
  if (console_output_code_page != 0) SetConsoleOutputCP(console_output_code_page);
}

std::wstring environment(const wchar_t* name) {
  const DWORD size = GetEnvironmentVariableW(name, nullptr, 0);
  if (size == 0) return {};
  std::wstring value(size, L'\0');
  const DWORD got = GetEnvironmentVariableW(name, value.data(), size);
  value.resize(got < size ? got : 0);
  return value;
}

} // namespace

std::wstring widen(std::string_view utf8) {
  if (utf8.empty()) return {};
  const int n = MultiByteToWideChar(CP_UTF8, 0, utf8.data(), int(utf8.size()), nullptr, 0);
  std::wstring out(std::size_t(n > 0 ? n : 0), L'\0');
  if (n > 0) MultiByteToWideChar(CP_UTF8, 0, utf8.data(), int(utf8.size()), out.data(), n);
  return out;
}

std::string narrow(std::wstring_view utf16) {
  if (utf16.empty()) return {};
  const int n = WideCharToMultiByte(CP_UTF8, 0, utf16.data(), int(utf16.size()), nullptr, 0,
                                    nullptr, nullptr);
  std::string out(std::size_t(n > 0 ? n : 0), '\0');
  if (n > 0)
    WideCharToMultiByte(CP_UTF8, 0, utf16.data(), int(utf16.size()), out.data(), n, nullptr,
                        nullptr);
  return out;
}

std::string error_message(unsigned long code) {
  wchar_t* text = nullptr;
  const DWORD n = FormatMessageW(FORMAT_MESSAGE_ALLOCATE_BUFFER | FORMAT_MESSAGE_FROM_SYSTEM |
                                     FORMAT_MESSAGE_IGNORE_INSERTS,
                                 nullptr, code, 0, reinterpret_cast<wchar_t*>(&text), 0, nullptr);
  std::string message = n && text ? narrow(std::wstring_view(text, n)) : std::string();
  if (text) LocalFree(text);
  while (!message.empty() && (message.back() == '\n' || message.back() == '\r' ||
                              message.back() == ' ' || message.back() == '.'))
    message.pop_back();
  return message.empty() ? "Windows error " + std::to_string(code) : message;
}

std::string last_error_message() {
  return error_message(GetLastError());
}

void start_console() {
  // Text mode would turn the program's LF into CR LF on the way out, and CR LF into LF and ^Z
  // into an end of file on the way in: the annotated bytes must be the program's own.
  _setmode(_fileno(stdin), _O_BINARY);
  _setmode(_fileno(stdout), _O_BINARY);
  _setmode(_fileno(stderr), _O_BINARY);
  if (is_console(STD_OUTPUT_HANDLE) || is_console(STD_ERROR_HANDLE)) {
    const UINT previous = GetConsoleOutputCP();
    if (previous != CP_UTF8 && SetConsoleOutputCP(CP_UTF8)) {
      console_output_code_page = previous;
      std::atexit(restore_console_code_page);
    }
  }
}

bool is_standard_output(const std::string& path) {
  std::string name;
  for (char c : path)
    name += char(std::toupper(static_cast<unsigned char>(c)));
  return name == "-" || name == "CON" || name == "CONOUT$";
}

bool stderr_is_terminal() {
  // A console that interprets the bar's escape sequences (Windows 10 and later); a pipe, a file,
  // or an older console gets no bar.
  const HANDLE handle = GetStdHandle(STD_ERROR_HANDLE);
  DWORD mode = 0;
  if (handle == INVALID_HANDLE_VALUE || !GetConsoleMode(handle, &mode)) return false;
  if (!(mode & ENABLE_VIRTUAL_TERMINAL_PROCESSING) &&
      !SetConsoleMode(handle, mode | ENABLE_VIRTUAL_TERMINAL_PROCESSING))
    return false;
  return environment(L"TERM") != L"dumb";
}

std::filesystem::path path_from_utf8(const std::string& utf8) {
  return std::filesystem::path(widen(utf8));
}

std::string utf8_from_path(const std::filesystem::path& path) {
  return narrow(path.native());
}

std::string user_config_folder() {
  // The roaming application data folder, where Windows programs keep a user's settings.
  std::wstring base = environment(L"APPDATA");
  if (base.empty()) {
    const std::wstring profile = environment(L"USERPROFILE");
    if (profile.empty()) return {};
    base = profile + L"\\AppData\\Roaming";
  }
  return narrow(base) + "\\ncjoule";
}

std::string module_file_of(const void* address) {
  HMODULE module = nullptr;
  if (!GetModuleHandleExW(GET_MODULE_HANDLE_EX_FLAG_FROM_ADDRESS |
                              GET_MODULE_HANDLE_EX_FLAG_UNCHANGED_REFCOUNT,
                          static_cast<LPCWSTR>(address), &module))
    return {};
  std::wstring buffer(32768, L'\0');
  const DWORD n = GetModuleFileNameW(module, buffer.data(), DWORD(buffer.size()));
  if (n == 0 || n >= buffer.size()) return {};
  buffer.resize(n);
  return narrow(buffer);
}

bool utf8_code_page() {
  return GetACP() == CP_UTF8;
}

std::filesystem::path program_file() {
  std::wstring buffer(MAX_PATH, L'\0');
  for (;;) {
    const DWORD n = GetModuleFileNameW(nullptr, buffer.data(), DWORD(buffer.size()));
    if (n == 0) return {};
    if (n < buffer.size()) {
      buffer.resize(n);
      return std::filesystem::path(buffer);
    }
    buffer.resize(buffer.size() * 2);
  }
}

} // namespace ncjoule::cli::platform
