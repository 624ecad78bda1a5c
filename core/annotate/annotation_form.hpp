// What an annotation looks like, read back: the form of a block's comment and of a header line,
// as annotate() writes them (docs/annotation.md, "Finding its own text again").
//
// A block's comment is  OPEN "NCJ" FIELD {FIELD} CLOSE  with OPEN/CLOSE "(" ")" or ";" and the
// end of the line (or a user's ';' comment after it). Its fields come in one order, each once:
// T, E, P, MRR, CUM, LOAD_PCT, OP, OPT, OPE, then SEAL (only in a file without a header), then
// CK (only in files written by earlier versions); each value in the format annotate() writes
// (a duration, a number with an SI prefix and unit, a plain number, a name). Blanks between the
// fields may be missing (a DNC sender that removes blanks) and the case may differ (a file an
// editor turned to upper case): the form is read regardless.
//
// A header line is a whole line  OPEN "NCJ" LABEL ... CLOSE  with one of the header's labels.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace ncjoule::annotation {

// A block's comment found on a line: the bytes to take out, [begin, end) (with the one blank
// annotate() put before it, when it is there), and its text as the seal counts it.
struct FoundComment {
  std::size_t begin = 0;
  std::size_t end = 0;
  bool whole_line = false; // the line is this comment and nothing else
  std::string normal;      // normal_text() of its "NCJ ..." part, without a SEAL field
  std::string seal;        // the value of its SEAL field, if it has one
};

// Every comment of the block form on `line`, in order.
std::vector<FoundComment> block_comments(std::string_view line);

// The line is a header line (the seal's or any other), and nothing else.
bool is_header_line(std::string_view line);

// The text as the seal counts it: blanks (space, tab) left out, upper case.
std::string normal_text(std::string_view text);

} // namespace ncjoule::annotation
