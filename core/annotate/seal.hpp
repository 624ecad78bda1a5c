// The integrity record of an annotated file: one line of the header, so that no block carries a
// checksum a reader must skip (docs/annotation.md, "Finding its own text again").
//
//   (NCJ SEAL LINES=14 BLOCKS=1234 SUM=7H2K9Q2M CK=R4T1ZP)
//
// LINES header lines follow it; BLOCKS block comments in the file are ncjoule's; SUM is a hash
// of all of them (each as normal_text() reads it, in order) and CK the checksum of the seal line
// itself (a line that merely looks like one is no seal). Comments of the block form that were
// in the program before it was annotated (a user's own, or an annotation pasted from another
// file) are listed in KEEP lines, by their place among the file's comments of that form and a
// short hash of their text:  (NCJ KEEP 5.ABCD 17.EFGH). A file without a header carries the same
// record in a SEAL field of its first block comment: SEAL=1234-7H2K9Q2M[-5.ABCD...].
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "marker.hpp"

namespace ncjoule::annotation {

// A comment of the user's in the block form, to be kept: its place (1-based) among the file's
// comments of that form, and keep_hash() of its text.
struct KeptComment {
  std::size_t ordinal = 0;
  std::string hash;
};

struct Seal {
  std::size_t lines = 0;  // header lines after the seal line
  std::size_t blocks = 0; // block comments of ncjoule's
  std::string sum;        // SealSum::value()
  std::vector<KeptComment> keep;
};

// The running hash of what a seal covers.
class SealSum {
public:
  void add_header(std::string_view normal);
  void add_block(std::string_view normal);
  std::string value(std::size_t lines, std::size_t blocks) const;

private:
  std::uint64_t header_ = 0xcbf29ce484222325ull;
  std::uint64_t blocks_ = 0x84222325cbf29ce4ull;
};

// Four characters of a hash of a kept comment's normal text.
std::string keep_hash(std::string_view normal);

// The seal line, and the seal a line holds when it is exactly one (its CK verified).
std::string seal_line(const Seal& seal, const CommentStyle& style);
std::optional<Seal> seal_of_line(std::string_view line);

// KEEP lines for the seal's kept comments, each within `max_length` bytes; and the entries a
// header line holds when it is one (appended to `keep`; false when it is no KEEP line).
std::vector<std::string> keep_lines(const std::vector<KeptComment>& keep, const CommentStyle& style,
                                    std::size_t max_length);
bool read_keep_line(std::string_view line, std::vector<KeptComment>& keep);

// The SEAL field's value for a file without a header, and the seal it holds.
std::string seal_field(const Seal& seal);
std::optional<Seal> seal_of_field(std::string_view value);

} // namespace ncjoule::annotation
