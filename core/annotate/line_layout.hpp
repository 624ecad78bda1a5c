// Where things go on a line and in a file: after a block's code and before its comments, and
// after a leading % line and O-number line. Only the characters that start comments matter here
// ('(' and ';' in every dialect: on Fanuc-family controls ';' ends the block, which is as much a
// place not to write after).
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

#include "marker.hpp"

namespace ncjoule::annotation {

// Where a block's comment goes on `line` (a byte offset): right after the last code character
// before the first comment ('(' or ';'), so that a comment a controller acts on (LinuxCNC's MSG,
// DEBUG, PRINT count only as the last comment of a line) stays last. For ';' comments, which run
// to the end of the line, before an existing ';' comment or else at the end of the code.
// nullopt when the line has no code before that point.
std::optional<std::size_t> insertion_point(std::string_view line, const CommentStyle& style);

bool is_blank(std::string_view line);
// A line with at least one comment and nothing else but blanks.
bool is_comment_only(std::string_view line);
// The text of the line's first comment (inside "( )" or after ';'), trimmed; empty if none.
std::string_view first_comment(std::string_view line);

// A tape start/end mark: the first non-blank character is '%'.
bool is_percent_line(std::string_view line);
// A program number or name line: O1234, o0012 (NAME), :1234.
bool is_program_number_line(std::string_view line);

} // namespace ncjoule::annotation
