// Reading a user's file whole, with the problems reported as diagnostics: every reader of a
// program, profile, job file, STL, CSV or config opens its file through here, so that a missing
// file, a directory, a read error or a file too large to be what it claims is said one way.
#pragma once

#include <cstddef>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/diagnostic.hpp"

namespace ncjoule {

// The largest NC program read unless told otherwise (`--input-limit`): about 20 million blocks
// of real CAM output. A device that never ends (/dev/zero) stops here too.
inline constexpr std::size_t kDefaultMaxProgramBytes = std::size_t(512) << 20;
// The largest settings file (profile, user config, job file, stock file): no real one is near.
inline constexpr std::size_t kMaxSettingsFileBytes = std::size_t(16) << 20;

// The bytes of the file at `path`; std::nullopt with an error on the file when it cannot be
// opened or read to the end, is a directory (then named against `what` it was meant to be, with
// its article: "a job file", "an STL file"), or holds more than `max_bytes` (the error names
// `limit_option`, the option that sets the limit, where there is one).
std::optional<std::string> read_text_file(const std::string& path, std::string_view what,
                                          std::vector<Diagnostic>& diagnostics,
                                          std::size_t max_bytes = kMaxSettingsFileBytes,
                                          std::string_view limit_option = {});

// Reads a stream (standard input) the same way; `name` names it in the error.
std::optional<std::string> read_text_stream(std::FILE* stream, const std::string& name,
                                            std::string_view what,
                                            std::vector<Diagnostic>& diagnostics,
                                            std::size_t max_bytes,
                                            std::string_view limit_option = {});

// What a file's bytes are when they are not text ncjoule can read (ASCII, UTF-8 or a one-byte
// code page): "UTF-16 (little-endian) text", "UTF-32 (big-endian) text", "binary data"; empty
// when they are text. Decided from a byte order mark, the pattern of NUL bytes of a wide
// encoding, or the share of bytes no text holds in the first 64 KiB. A stray control byte in a
// text (an ESC, one NUL) does not make it binary.
std::string non_text_encoding(std::string_view bytes);

} // namespace ncjoule
