// Which line of an annotated file each line of it was in the original: the annotator adds whole
// lines (its header, a block's comment on a line of its own) and one comment inside a line,
// nothing else. Shared by the annotator's tests and its fuzz target, which check that an
// annotated program runs as the original, block for block.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace annotate_test {

inline bool starts_with_marker(std::string_view text) {
  if (text.size() < 4 || (text[0] != '(' && text[0] != ';')) return false;
  for (std::size_t i = 0; i < 3; ++i)
    if ((text[i + 1] & ~0x20) != "NCJ"[i]) return false;
  return true;
}

// `annotated` is `original` with one " (NCJ ...)" or " ;NCJ ..." inserted somewhere.
inline bool is_annotated_line(std::string_view annotated, std::string_view original) {
  if (annotated.size() <= original.size() + 1) return false;
  std::size_t prefix = 0;
  while (prefix < original.size() && annotated[prefix] == original[prefix])
    ++prefix;
  const std::size_t inserted = annotated.size() - original.size();
  // The insertion may start anywhere from 0 to `prefix` (the bytes around it can repeat).
  for (std::size_t at = 0; at <= prefix; ++at) {
    if (annotated.substr(at + inserted) != original.substr(at)) continue;
    if (annotated[at] == ' ' && starts_with_marker(annotated.substr(at + 1))) return true;
  }
  return false;
}

// For each line of `annotated`, the index of the line of `original` it is (a copy, or a copy
// with an annotation inserted), or -1 for a line the annotator added. Lines are matched in order;
// -2 in the first element when the original's lines are not all found.
inline std::vector<int> original_lines(const std::vector<std::string>& annotated,
                                       const std::vector<std::string>& original) {
  std::vector<int> out(annotated.size(), -1);
  std::size_t i = 0;
  for (std::size_t j = 0; j < annotated.size(); ++j) {
    if (i < original.size() &&
        (annotated[j] == original[i] || is_annotated_line(annotated[j], original[i]))) {
      out[j] = static_cast<int>(i++);
    } else if (!starts_with_marker(annotated[j])) {
      out.assign(annotated.size() + 1, -2); // a line that is neither
      return out;
    }
  }
  if (i != original.size()) out.assign(annotated.size() + 1, -2);
  return out;
}

} // namespace annotate_test
