// ncjoule stage 5: annotate. Writes a program back with its predictions as comments, and takes
// them out again (docs/annotation.md describes the grammar).
//
// Every source line is kept byte for byte. A block that moves or takes time gets one comment
// after its code and before any comment already on the line (or, when the line has no room, on
// a line of its own before it); a few header lines with the totals go after the program's
// leading %, O-number and title lines. Every inserted comment starts with the marker "NCJ"; the
// header's first line, the seal, counts them and holds a hash of them all, so that strip()
// removes exactly what annotate() inserted and nothing a user wrote, nor an annotation copied
// from another file: strip(annotate(x)) == x, annotate(annotate(x)) == annotate(x). No I/O here:
// the command line reads and writes the files.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "ncjoule/estimate.hpp"
#include "ncjoule/gcode.hpp"
#include "ncjoule/machine.hpp"

namespace ncjoule {

// Longest line (bytes, without its line ending) written when the dialect names no limit:
// LinuxCNC's rs274 refuses a line of 253 bytes with its line ending ("Command too long").
inline constexpr std::size_t kDefaultMaxLineLength = 250;

// Which fields a block's comment holds: T (block time), E (energy), P (mean power), MRR (mean
// removal rate), CUM (time at the block's end), OP (the operation's name, time and energy on the
// line that starts it). LOAD (a cut over the spindle's rating) is always written.
struct BlockFields {
  bool time = true, energy = true, power = true, mrr = true, cumulative = true, operation = true;
  bool omit_zero = false; // leave out a field whose value is 0 (MRR=0 on rapids, E=0)
};
// The compact style: T, E, MRR and OP, zeros left out: about 60% of the bytes the default adds
// (docs/annotation.md gives the sizes).
BlockFields compact_block_fields();
// "T,E,MRR" (any case, any order) -> those fields; std::nullopt, with an error in `diagnostics`,
// for a name that is not one of T, E, P, MRR, CUM, OP or an empty list.
std::optional<BlockFields> parse_block_fields(std::string_view list,
                                              std::vector<Diagnostic>& diagnostics,
                                              const TextOrigin& origin);

struct AnnotateOptions {
  bool header = true;              // the summary header after the % and O-number lines
  bool operations = true;          // per-operation subtotals on tool-change lines
  std::size_t max_line_length = 0; // 0: the dialect's, else kDefaultMaxLineLength
  BlockFields fields;              // what each block's comment says
};

// The program in `source` with its predictions as comments. `estimate` must come from
// estimate_program() on the program without annotations, strip(source.text) (the source itself
// when it holds none): an annotation's own comment line would be read as a comment of the
// program. Annotations already in the source are replaced: the result is the same as annotating
// strip(source.text).
std::string annotate(const SourceFile& source, const Estimate& estimate,
                     const MachineProfile& machine, const AnnotateOptions& options = {});

// The whole job of annotating a program's text, as the command line and the C API do it: old
// annotations are taken out, the program is estimated, and written back with its predictions.
// `text` is empty when no estimate could be made (estimate.failed). A program with errors its
// controller would refuse is annotated all the same (the header lists them): has_errors says so.
struct AnnotatedProgram {
  std::string text;
  Estimate estimate;
  bool has_errors = false;
};
AnnotatedProgram annotate_program(std::string path, std::string_view text,
                                  const MachineProfile& machine, const EstimateOptions& options,
                                  const AnnotateOptions& annotate_options = {});

// The text without ncjoule's annotations: inserted header lines (with their line endings) and
// inserted comments (with the space before them) are removed; every other byte is kept.
std::string strip(std::string_view text);

// strip(), and whether the annotations were taken out by their form rather than by the seal
// that counts them (the file was edited after it was annotated, or its header deleted): then a
// comment of that form a user added since went too (docs/annotation.md).
struct StripResult {
  std::string text;
  bool by_form = false;
};
StripResult strip_checked(std::string_view text);

// True when the text holds at least one annotation strip() would remove.
bool has_annotations(std::string_view text);

} // namespace ncjoule
