// The wire format of ncjoule's comments: how one is written and how it is recognised again.
//
// A marked comment is  OPEN "NCJ" {" " FIELD} " CK=" SUM CLOSE  where OPEN/CLOSE are "(" ")" or
// ";" "", every field holds only safe characters, and SUM is six characters of a checksum of
// the text from "NCJ" up to the space before "CK=". The checksum makes a comment ncjoule wrote
// tell itself apart from one a user wrote that merely looks alike: strip() removes only comments
// whose checksum matches. Inline comments and header lines use different checksums, so that
// neither can be taken for the other.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "ncjoule/gcode.hpp"

namespace ncjoule::annotation {

enum class MarkKind { Inline, Header };

struct CommentStyle {
  std::string open = "(";
  std::string close = ")"; // empty: the comment runs to the end of the line
  bool upper_case = false; // the whole comment in upper case (Fanuc family)
};

// How the annotations of one file are written.
struct WriteStyle {
  CommentStyle comment;
  std::size_t max_line_length = 0; // bytes, without the line ending
};

// The dialect's comment syntax when it is one strip() recognises ("(" ")" or ";"), else the
// parenthesis form; in upper case where the dialect's controller wants it.
CommentStyle comment_style(const Dialect& dialect);

// Letters, digits, space and . , = _ - : what every controller accepts in a comment.
bool is_safe_char(char c);

// The checksum field's value for `content` ("NCJ ..."), computed case-insensitively so that a
// file an editor or a controller turned to upper case still strips.
std::string checksum(std::string_view content, MarkKind kind);

// OPEN content " CK=" checksum CLOSE, in upper case if the style says so. `content` must start
// with "NCJ"; a character that is not safe becomes '_'.
std::string marked_comment(std::string_view content, MarkKind kind, const CommentStyle& style);

// Length of the marked comment of the given kind that opens at text[pos] ('(' or ';'), or 0 when
// there is none there.
std::size_t match_marked_comment(std::string_view text, std::size_t pos, MarkKind kind);

} // namespace ncjoule::annotation
