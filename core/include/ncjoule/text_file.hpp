// Reading a user's file whole, with the problems reported as diagnostics: every reader of a
// program, profile, job file, STL, CSV or config opens its file through here, so that a missing
// file, a directory or a read error is said one way.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/diagnostic.hpp"

namespace ncjoule {

// The bytes of the file at `path`; std::nullopt with an error on the file when it cannot be
// opened or read to the end, or is a directory (then named against `what` it was meant to be,
// with its article: "a job file", "an STL file").
std::optional<std::string> read_text_file(const std::string& path, std::string_view what,
                                          std::vector<Diagnostic>& diagnostics);

} // namespace ncjoule
