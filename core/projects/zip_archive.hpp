// Internal: one member of a zip archive (a FreeCAD .FCStd), read from the archive's bytes. Stored
// and deflated members only; no ZIP64, no encryption: a FreeCAD document is none of those.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace ncjoule::projects_detail {

// The bytes of the member named `name` (exactly as the archive names it), at most `max_bytes`
// long; std::nullopt with `error` saying why (not a zip archive, no such member, a method it
// does not read, damaged data, larger than `max_bytes`).
std::optional<std::string> zip_member(std::string_view archive, std::string_view name,
                                      std::size_t max_bytes, std::string& error);

// Whether zip_member can inflate deflated members (this build has zlib).
bool zip_inflates();

} // namespace ncjoule::projects_detail
