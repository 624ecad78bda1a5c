// Taking ncjoule's annotations out of a text, shared by strip() and by annotate(), which
// replaces old annotations: both must agree byte for byte on what an annotation is.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::annotation {

// Splits text into lines as make_source() does, without copying it.
std::vector<LineSpan> split_lines(std::string_view text);

// What strip() takes out of one annotated text:
// - every key line before the first line with code (after blank, comment-only, '%' and O-number
//   lines); the first one's key is the file's;
// - with a key, the header lines, block comments and block comment lines sealed with it;
// - block comments and block comment lines sealed with their own line (files annotated without
//   a header): a comment after a block's code with the line's text around it, a comment line
//   with the next line that stays, as strip() leaves that line.
// Everything else, a look-alike or an annotation pasted from another file, is the user's.
class Annotations {
public:
  Annotations(std::string_view text, const std::vector<LineSpan>& lines);

  // Line i is an annotation as a whole: it goes, with its line ending.
  bool whole_line(std::size_t i) const { return whole_[i]; }
  // Appends line i (without its line ending) without its inline annotations (each with the
  // space before it) to `out`; returns whether there was any.
  bool strip_inline(std::size_t i, std::string& out) const;
  bool any_whole_line() const { return any_whole_; }

private:
  std::string_view line(std::size_t i) const;
  bool is_whole_annotation(std::size_t i, const std::string& next_seed) const;

  std::string_view text_;
  const std::vector<LineSpan>& lines_;
  std::string seed_; // key_seed() of the file's key; empty: no key
  std::vector<bool> whole_;
  bool any_whole_ = false;
};

} // namespace ncjoule::annotation
