// Taking ncjoule's annotations out of a text, shared by strip() and by annotate(), which
// replaces old annotations: both must agree byte for byte on what an annotation is.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::annotation {

// Splits text into lines as make_source() does, without copying it.
std::vector<LineSpan> split_lines(std::string_view text);

// What strip() takes out of one annotated text (docs/annotation.md, "Finding its own text
// again"):
// - with a seal line (its own checksum verified) followed by its header lines, anywhere in the
//   file: the seal line, those header lines, and the file's block comments. When the seal's count
//   and sum match them, exactly the comments it covers go and the user's comments of the same
//   form it lists (KEEP) stay; when they do not (the file was edited after it was annotated),
//   every block comment goes but the listed ones, found by their text;
// - without a seal line, a block comment whose SEAL field covers the file exactly (a file
//   annotated without a header) does the same;
// - with neither (a header deleted, a file without a header edited), the block comments go when
//   there are at least 3 and they are on more than half of the lines with code: an annotated
//   file; a program with a few such comments (notes pasted from an annotated file) keeps them;
// - comments written by earlier versions (sealed with CK=, the file's key or their line) go by
//   their checksums, as those versions took them out.
class Annotations {
public:
  Annotations(std::string_view text, const std::vector<LineSpan>& lines);

  // Line i is an annotation as a whole: it goes, with its line ending.
  bool whole_line(std::size_t i) const { return whole_[i]; }
  // Appends line i (without its line ending) without its inline annotations (each with the
  // blank before it) to `out`; returns whether there was any.
  bool strip_inline(std::size_t i, std::string& out) const;
  bool any_whole_line() const { return any_whole_; }
  bool any() const { return any_whole_ || !spans_.empty(); }
  // A seal was found that the file's annotations no longer match, or annotations without any
  // seal: they were taken out by their form (the user may want to look).
  bool by_form() const { return by_form_; }

private:
  struct Span {
    std::size_t line, begin, end;
  };
  std::string_view line(std::size_t i) const;
  // Comments written by earlier versions, sealed with CK= (the file's key or their line).
  void find_legacy();
  // Comments of this version: by the seal, else by their form.
  void find_current();
  bool has_span(std::size_t line, std::size_t begin, std::size_t end) const;

  std::string_view text_;
  const std::vector<LineSpan>& lines_;
  std::vector<bool> whole_;
  std::vector<Span> spans_; // sorted by line, then begin
  bool any_whole_ = false;
  bool by_form_ = false;
};

} // namespace ncjoule::annotation
