#include "zip_archive.hpp"

#include <cstdint>

#ifdef NCJOULE_HAVE_ZLIB
#include <zlib.h>
#endif

namespace ncjoule::projects_detail {
namespace {

// Little-endian fields at `at`; 0 past the end (the callers check the sizes first).
std::uint32_t u16(std::string_view b, std::size_t at) {
  if (at + 2 > b.size()) return 0;
  return std::uint32_t(std::uint8_t(b[at])) | std::uint32_t(std::uint8_t(b[at + 1])) << 8;
}
std::uint32_t u32(std::string_view b, std::size_t at) {
  return at + 4 > b.size() ? 0 : u16(b, at) | u16(b, at + 2) << 16;
}

constexpr std::uint32_t kEndOfDirectory = 0x06054b50, kDirectoryEntry = 0x02014b50,
                        kLocalHeader = 0x04034b50;

std::optional<std::string> inflated(std::string_view data, std::size_t size, std::size_t max_bytes,
                                    std::string& error) {
#ifdef NCJOULE_HAVE_ZLIB
  if (size > max_bytes)
    return error = "is larger than " + std::to_string(max_bytes) + " bytes", std::nullopt;
  std::string out(size, '\0');
  z_stream z{};
  if (inflateInit2(&z, -MAX_WBITS) != Z_OK) return error = "cannot be inflated", std::nullopt;
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = uInt(data.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = uInt(out.size());
  const int status = inflate(&z, Z_FINISH);
  const std::size_t made = z.total_out;
  inflateEnd(&z);
  if (status != Z_STREAM_END || made != size)
    return error = "is damaged (its deflated data does not inflate to its stated size)",
           std::nullopt;
  return out;
#else
  (void)data, (void)size, (void)max_bytes;
  return error = "is deflated, and this build of ncjoule has no zlib to inflate it", std::nullopt;
#endif
}

} // namespace

bool zip_inflates() {
#ifdef NCJOULE_HAVE_ZLIB
  return true;
#else
  return false;
#endif
}

std::optional<std::string> zip_member(std::string_view archive, std::string_view name,
                                      std::size_t max_bytes, std::string& error) {
  // The end-of-directory record: the last 22 bytes, or before a comment of up to 64 KiB.
  if (archive.size() < 22) return error = "is not a zip archive (too short)", std::nullopt;
  std::size_t end = std::string_view::npos;
  for (std::size_t at = archive.size() - 22;; --at) {
    if (u32(archive, at) == kEndOfDirectory && at + 22 + u16(archive, at + 20) == archive.size()) {
      end = at;
      break;
    }
    if (at == 0 || archive.size() - at > 22 + 0xffff) break;
  }
  if (end == std::string_view::npos)
    return error = "is not a zip archive (no end-of-directory record)", std::nullopt;
  const std::size_t entries = u16(archive, end + 10);
  const std::size_t directory = u32(archive, end + 16);
  if (directory == 0xffffffff || entries == 0xffff)
    return error = "is a ZIP64 archive, which ncjoule does not read", std::nullopt;
  std::size_t at = directory;
  for (std::size_t k = 0; k < entries; ++k) {
    if (at + 46 > archive.size() || u32(archive, at) != kDirectoryEntry)
      return error = "is damaged (its directory is cut short)", std::nullopt;
    const std::uint32_t flags = u16(archive, at + 8), method = u16(archive, at + 10);
    const std::size_t packed = u32(archive, at + 20), size = u32(archive, at + 24);
    const std::size_t name_length = u16(archive, at + 28), extra = u16(archive, at + 30),
                      comment = u16(archive, at + 32), local = u32(archive, at + 42);
    if (at + 46 + name_length > archive.size())
      return error = "is damaged (its directory is cut short)", std::nullopt;
    if (archive.substr(at + 46, name_length) != name) {
      at += 46 + name_length + extra + comment;
      continue;
    }
    const std::string what = std::string(name);
    if (flags & 1) return error = what + " is encrypted", std::nullopt;
    if (local + 30 > archive.size() || u32(archive, local) != kLocalHeader)
      return error = what + " is damaged (no local header where the directory says)", std::nullopt;
    const std::size_t data = local + 30 + u16(archive, local + 26) + u16(archive, local + 28);
    if (data > archive.size() || archive.size() - data < packed)
      return error = what + " is cut short", std::nullopt;
    const std::string_view bytes = archive.substr(data, packed);
    if (method == 0) {
      if (packed != size) return error = what + " is damaged (stored with two sizes)", std::nullopt;
      if (size > max_bytes)
        return error = what + " is larger than " + std::to_string(max_bytes) + " bytes",
               std::nullopt;
      return std::string(bytes);
    }
    if (method != 8)
      return error = what + " is compressed with method " + std::to_string(method) +
                     " (ncjoule reads stored and deflated members)",
             std::nullopt;
    std::string why;
    auto out = inflated(bytes, size, max_bytes, why);
    if (!out) error = what + " " + why;
    return out;
  }
  return error = "holds no " + std::string(name), std::nullopt;
}

} // namespace ncjoule::projects_detail
