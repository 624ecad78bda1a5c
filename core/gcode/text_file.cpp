#include "ncjoule/text_file.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <sys/stat.h>

namespace ncjoule {
namespace {

std::string mib(std::size_t bytes) {
  const std::size_t m = bytes >> 20;
  return m > 0 ? std::to_string(m) + " MiB" : std::to_string(bytes) + " bytes";
}

// Reads until the end or until more than `max_bytes` came; `too_large` says which. `expected`:
// the size the file says it has (0: unknown), taken at once rather than grown into.
bool read_all(std::FILE* f, std::size_t max_bytes, std::string& text, bool& too_large,
              std::size_t expected = 0) {
  std::array<char, 1 << 16> buffer{};
  too_large = false;
  text.reserve(std::min(expected, max_bytes));
  for (;;) {
    const std::size_t n = std::fread(buffer.data(), 1, buffer.size(), f);
    if (n > 0) {
      if (text.size() + n > max_bytes) {
        too_large = true;
        return true;
      }
      text.append(buffer.data(), n);
    }
    if (n < buffer.size()) return std::ferror(f) == 0;
  }
}

std::string too_large_message(std::size_t max_bytes, std::string_view what,
                              std::string_view limit_option) {
  std::string out = "is larger than " + mib(max_bytes) + ", the limit for " + std::string(what);
  if (!limit_option.empty()) out += " (" + std::string(limit_option) + " sets it)";
  return out;
}

} // namespace

std::optional<std::string> read_text_file(const std::string& path, std::string_view what,
                                          std::vector<Diagnostic>& diagnostics,
                                          std::size_t max_bytes, std::string_view limit_option) {
  auto fail = [&](std::string message) -> std::optional<std::string> {
    diagnostics.push_back({Severity::Error, path, 0, 0, std::move(message)});
    return std::nullopt;
  };
  struct stat info {};
  std::size_t expected = 0;
  if (::stat(path.c_str(), &info) == 0) {
    if (S_ISREG(info.st_mode)) expected = std::size_t(info.st_size);
    if (S_ISDIR(info.st_mode)) return fail("is a directory, not " + std::string(what));
    // A regular file's size is known before a byte is read.
    if (S_ISREG(info.st_mode) && std::size_t(info.st_size) > max_bytes)
      return fail(too_large_message(max_bytes, what, limit_option));
  }
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return fail("cannot be opened: " + std::string(std::strerror(errno)));
  std::string text;
  bool too_large = false;
  const bool read = read_all(f, max_bytes, text, too_large, expected);
  std::fclose(f);
  if (too_large) return fail(too_large_message(max_bytes, what, limit_option));
  if (!read) return fail("could not be read to the end");
  return text;
}

std::optional<std::string> read_text_stream(std::FILE* stream, const std::string& name,
                                            std::string_view what,
                                            std::vector<Diagnostic>& diagnostics,
                                            std::size_t max_bytes, std::string_view limit_option) {
  std::string text;
  bool too_large = false;
  const bool read = read_all(stream, max_bytes, text, too_large);
  if (too_large) {
    diagnostics.push_back(
        {Severity::Error, name, 0, 0, too_large_message(max_bytes, what, limit_option)});
    return std::nullopt;
  }
  if (!read) {
    diagnostics.push_back({Severity::Error, name, 0, 0, "could not be read to the end"});
    return std::nullopt;
  }
  return text;
}

std::string non_text_encoding(std::string_view bytes) {
  auto starts = [&](std::string_view bom) { return bytes.substr(0, bom.size()) == bom; };
  using namespace std::string_view_literals;
  // Byte order marks: UTF-32's first, since UTF-16's little-endian mark begins it.
  if (starts("\xFF\xFE\x00\x00"sv)) return "UTF-32 (little-endian) text";
  if (starts("\x00\x00\xFE\xFF"sv)) return "UTF-32 (big-endian) text";
  if (starts("\xFF\xFE"sv)) return "UTF-16 (little-endian) text";
  if (starts("\xFE\xFF"sv)) return "UTF-16 (big-endian) text";

  const std::string_view head = bytes.substr(0, std::size_t(1) << 16);
  if (head.empty()) return {};
  // Wide text without a mark: ASCII characters with NUL bytes beside them, at odd offsets
  // (UTF-16 little-endian), even ones (big-endian), or three in four (UTF-32).
  std::array<std::size_t, 4> nul_at{};
  std::size_t nuls = 0;
  for (std::size_t i = 0; i < head.size(); ++i)
    if (head[i] == '\0') ++nul_at[i % 4], ++nuls;
  const double quarter = double(head.size()) / 4;
  auto mostly = [&](std::size_t k) { return double(nul_at[k]) > 0.8 * quarter; };
  if (head.size() >= 8) {
    if (mostly(1) && mostly(2) && mostly(3)) return "UTF-32 (little-endian) text";
    if (mostly(0) && mostly(1) && mostly(2)) return "UTF-32 (big-endian) text";
    if (mostly(1) && mostly(3)) return "UTF-16 (little-endian) text";
    if (mostly(0) && mostly(2)) return "UTF-16 (big-endian) text";
  }
  // Binary: bytes no text holds (control bytes other than tab, line endings and form feed, and
  // bytes that do not form UTF-8) are more than a tenth of the head. A one-byte code page's
  // accented letters are not UTF-8 either, but no program is a tenth accents.
  std::size_t odd = 0;
  for (std::size_t i = 0; i < head.size();) {
    const auto c = static_cast<unsigned char>(head[i]);
    if (c < 0x80) {
      if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f') || c == 0x7f) ++odd;
      ++i;
      continue;
    }
    const int length = c >= 0xf0 && c < 0xf5 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 && c < 0xe0 ? 2 : 0;
    bool valid = length > 0 && c < 0xf5 && i + length <= head.size();
    for (int k = 1; valid && k < length; ++k)
      valid = (static_cast<unsigned char>(head[i + k]) & 0xc0) == 0x80;
    if (valid) {
      i += std::size_t(length);
    } else {
      ++odd;
      ++i;
    }
  }
  if (double(odd) > 0.1 * double(head.size()) ||
      (nuls >= 8 && double(nuls) > 0.01 * double(head.size())))
    return "binary data";
  return {};
}

} // namespace ncjoule
