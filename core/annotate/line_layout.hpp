// Where things go on a line and in a file: after a block's code and before its comments, and
// after a program's leading lines (its '%', Sinumerik's %_N_ and ;$PATH lines, its O-number and
// its title comment). Where a line's code ends comes from the dialect's own scanner
// (comment_syntax in gcode), so that nothing is put inside a call, an expression or a string.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

#include "marker.hpp"

namespace ncjoule::annotation {

// Where a block's comment goes on `line` (a byte offset, before which annotate puts a space):
// - "( )" comments: right after the last code character before the first comment or end-of-block
//   mark, so that a comment a controller acts on (LinuxCNC's MSG, DEBUG, PRINT count only as the
//   last comment of a line) stays last;
// - ';' comments, which run to the end of the line: before an existing ';' comment, else at the
//   end of the line (after any "( )" comment and a Heidenhain block's '*'), never before the end
//   of the code.
// nullopt when the line has no code before that point, or ends inside an argument list or a
// string (MSG("a;b), or, for ';' comments, inside a "( )" comment that does not close: the
// comment then goes on a line of its own.
std::optional<std::size_t> insertion_point(std::string_view line, const Dialect& dialect,
                                           const CommentStyle& style);

bool is_blank(std::string_view line);
// A line with at least one comment and nothing else but blanks.
bool is_comment_only(std::string_view line);
// The text of the line's first comment (inside "( )" or after ';'), trimmed; empty if none.
std::string_view first_comment(std::string_view line);

// A tape start/end mark: the first non-blank character is '%'.
bool is_percent_line(std::string_view line);
// A program number or name line: O1234, o0012 (NAME), :1234.
bool is_program_number_line(std::string_view line);
// Sinumerik's path line, after the %_N_NAME_MPF line of a program in punch tape format:
// ";$PATH=/_N_WKS_DIR/_N_PART_WPD".
bool is_sinumerik_path_line(std::string_view line);
// The line holds a comment after its code or mark ("O1234 (NAME)", "%(NAME)").
bool has_trailing_comment(std::string_view line);

} // namespace ncjoule::annotation
