// The wire format of ncjoule's comments: how one is written and how it is recognised again.
//
// A marked comment is  OPEN "NCJ" {" " FIELD} " CK=" SUM CLOSE  where OPEN/CLOSE are "(" ")" or
// ";" "", every field holds only safe characters, and SUM is six characters of a checksum of
// the text from "NCJ" up to the space before "CK=". The checksum makes a comment ncjoule wrote
// tell itself apart from one a user wrote that merely looks alike: strip() removes only comments
// whose checksum matches.
//
// A checksum covers more than the comment's text: its kind (the key line, a header line, a
// block's comment after its code, a block's comment on a line of its own), so that none can be
// taken for another, and a seed: the file's key (kept in the header's key line) or, in a file
// without a header, the text of the line the comment belongs to. An annotation copied from
// another annotated file into a program, as a note, was sealed with another key or another line:
// it does not verify here, and stays the user's text (docs/annotation.md, "Finding its own text
// again").
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "ncjoule/gcode.hpp"

namespace ncjoule::annotation {

enum class MarkKind {
  Key,    // the header's first line: the file's key, sealed with no seed
  Header, // a header line
  Inline, // a block's comment, after its code
  Line,   // a block's comment on a line of its own, right before the block
};

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

// A file's key: six characters (Crockford base 32) of a hash of its program text without
// annotations, so that annotating the same program twice gives the same file. The text is fed
// piece by piece (a program's lines need not be copied into one string).
class FileKey {
public:
  void add(std::string_view text);
  std::string value() const;

private:
  std::uint32_t h_ = 0x3c6ef372u;
};
// The seed of the checksums of a file with that key.
std::string key_seed(std::string_view key);
// The seed of a comment bound to its line (files without a header): the line's text without
// the comment, blanks left out and upper-cased, so that a file turned to upper case or with
// its trailing blanks trimmed still strips.
std::string line_seed(std::string_view line);

// The checksum field's value for `content` ("NCJ ..."), computed case-insensitively so that a
// file an editor or a controller turned to upper case still strips.
std::string checksum(std::string_view content, MarkKind kind, std::string_view seed);

// OPEN content CLOSE, in upper case if the style says so; a character that is not safe becomes
// '_'. What annotate() writes now: the seal (seal.hpp) holds what strip() needs.
std::string plain_comment(std::string_view content, const CommentStyle& style);

// OPEN content " CK=" checksum CLOSE, in upper case if the style says so (earlier versions'
// comments, and the seal line). `content` must start
// with "NCJ"; a character that is not safe becomes '_'.
std::string marked_comment(std::string_view content, MarkKind kind, const CommentStyle& style,
                           std::string_view seed);

// Length of the marked comment of the given kind and seed that opens at text[pos] ('(' or ';'),
// or 0 when there is none there.
std::size_t match_marked_comment(std::string_view text, std::size_t pos, MarkKind kind,
                                 std::string_view seed);

// Length of the block comment that opens at line[space + 1], after the space annotate put
// before it, sealed with the line_seed() of the line without that space and comment; 0 if none.
std::size_t match_line_bound_comment(std::string_view line, std::size_t space);

// The key line's content for a key, and the key a line holds when it is exactly a key line
// ("(NCJ FILE KEY=7H2K9Q CK=......)"), upper-cased.
std::string key_content(std::string_view key);
std::optional<std::string> key_of_line(std::string_view line);

} // namespace ncjoule::annotation
