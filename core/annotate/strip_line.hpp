// Taking ncjoule's annotations out of one line, shared by strip() and by annotate(), which
// replaces old annotations: both must agree byte for byte on what an annotation is.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::annotation {

// The line (without its line ending) is a header line annotate() inserted.
bool is_header_line(std::string_view line);

// Appends `line` without its inline annotations (each with the space before it) to `out`.
// Returns whether there was any.
bool strip_inline(std::string_view line, std::string& out);

// Splits text into lines as make_source() does, without copying it.
std::vector<LineSpan> split_lines(std::string_view text);

} // namespace ncjoule::annotation
