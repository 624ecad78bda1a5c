// What differs between POSIX systems and Windows outside of writing and replacing files
// (output_file.hpp, in_place.hpp): the console, where the user config and the program live, and
// how a UTF-8 path becomes a path the system opens. platform_posix.cpp and platform_windows.cpp
// implement it; the rest of ncjoule holds paths as UTF-8 std::string on every system.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace ncjoule::cli::platform {

// Called first thing in main(). POSIX: nothing. Windows: standard input and output in binary
// mode (a program's CR LF and bare LF line ends pass through unchanged, and ^Z is not an end of
// file) and the console's output code page set to UTF-8, which the program's messages are in.
void start_console();

// Whether standard error is a terminal that takes the progress bar's escape sequences.
bool stderr_is_terminal();

// Whether writing to `path` writes where standard output goes (/dev/stdout, /dev/fd/1, or the
// very file or terminal the shell sent it to; CON on Windows): a command whose output file is
// its standard output then prints its own messages to standard error, so they do not land in
// the text.
bool is_standard_output(const std::string& path);

// A path from UTF-8 text, and back. On POSIX the bytes are the path; on Windows the path is
// UTF-16 and std::filesystem would read and write narrow strings in a legacy code page.
std::filesystem::path path_from_utf8(const std::string& utf8);
std::string utf8_from_path(const std::filesystem::path& path);

// The folder of ncjoule's own user settings (config.toml): $XDG_CONFIG_HOME/ncjoule or
// ~/.config/ncjoule on POSIX, %APPDATA%\ncjoule on Windows. Empty when it cannot be told.
std::string user_config_folder();

// The running program file (/proc/self/exe, GetModuleFileNameW); empty when it cannot be told.
std::filesystem::path program_file();

// The separator of the PATH variable's folders.
#ifdef _WIN32
inline constexpr char kPathListSeparator = ';';
#else
inline constexpr char kPathListSeparator = ':';
#endif

#ifdef _WIN32
// UTF-8 <-> UTF-16 for the wide-character Windows API (invalid UTF-8 becomes U+FFFD).
std::wstring widen(std::string_view utf8);
std::string narrow(std::wstring_view utf16);
// The system's message for a Windows error code (GetLastError()), in UTF-8, without the final
// period and line end.
std::string error_message(unsigned long code);
// The same for the calling thread's last error (GetLastError()).
std::string last_error_message();
// The file of the program or DLL that holds `address`; empty when it cannot be told.
std::string module_file_of(const void* address);
// Whether the process's code page is UTF-8 (the manifest is honoured: Windows 10 1903 and later).
bool utf8_code_page();
#endif

} // namespace ncjoule::cli::platform
