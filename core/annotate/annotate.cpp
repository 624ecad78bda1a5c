// annotate(): the program's lines, byte for byte, with one comment per block that moves or takes
// time (after its code, or on a line of its own before it when the line has no room), per-
// operation subtotals on tool-change lines, and the header, its first line the file's key, after
// the program's leading lines.
#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "annotation_form.hpp"
#include "header.hpp"
#include "line_layout.hpp"
#include "marker.hpp"
#include "ncjoule/annotate.hpp"
#include "ncjoule/in_order.hpp"
#include "number_format.hpp"
#include "seal.hpp"
#include "strip_line.hpp"

namespace ncjoule {
namespace annotation {
namespace {

// Header lines wrap at this width when the controller allows longer lines: they are read in an
// editor.
constexpr std::size_t kHeaderWidth = 120;
// Operation names are cut to this many characters.
constexpr std::size_t kOperationNameLength = 24;

// One field of a block's comment. Fields are written in the order of the list and, when the
// line would be too long, dropped by rank: the highest rank goes first; rank 0 is never dropped.
struct Field {
  std::string text;
  int drop_rank = 0;
};

// The source's lines with old annotations taken out: what the result is built from.
struct CleanLines {
  std::vector<std::string> storage;   // texts that changed
  std::vector<std::string_view> text; // every line's text
  std::vector<std::string_view> eol;  // every line's line ending
  std::vector<bool> removed;          // a whole-line annotation of an earlier run: left out
};

CleanLines clean_lines(const SourceFile& source) {
  CleanLines c;
  const std::size_t n = source.lines.size();
  c.text.resize(n);
  c.eol.resize(n);
  c.removed.resize(n);
  const Annotations old(source.text, source.lines);
  std::vector<std::pair<std::size_t, std::string>> changed;
  std::string scratch;
  for (std::size_t i = 0; i < n; ++i) {
    const LineSpan& span = source.lines[i];
    c.eol[i] = std::string_view(source.text).substr(span.begin + span.length, span.eol_length);
    c.text[i] = source.line_text(i);
    if (old.whole_line(i)) {
      c.removed[i] = true;
      c.text[i] = {};
      continue;
    }
    scratch.clear();
    if (old.strip_inline(i, scratch)) changed.emplace_back(i, scratch);
  }
  c.storage.reserve(changed.size()); // no reallocation: the views below point into it
  for (auto& [i, text] : changed) {
    c.storage.push_back(std::move(text));
    c.text[i] = c.storage.back();
  }
  return c;
}

// The index of the first line the header goes before, or nullopt when there is no line to put
// it before. The header comes after the lines a control or a DNC list reads first: a leading
// '%' (and Sinumerik's %_N_NAME_MPF), Sinumerik's ;$PATH line, the O-number line, and the
// program's title comment (the first comment-only line after those, when the O-number line
// carries none): controls show that comment as the program's name, so it stays first.
std::optional<std::size_t> header_position(const CleanLines& lines) {
  const std::size_t n = lines.text.size();
  std::size_t i = 0;
  auto skip_removed = [&] {
    while (i < n && lines.removed[i])
      ++i;
  };
  skip_removed();
  bool leading = false; // a '%', %_N_ or O-number line was passed
  bool named = false;   // the last of them carries its comment (O1234 (NAME))
  while (i < n) {
    const std::string_view line = lines.text[i];
    if (is_percent_line(line) || is_program_number_line(line)) {
      leading = true;
      named = is_program_number_line(line) && has_trailing_comment(line);
    } else if (!(leading && is_sinumerik_path_line(line))) {
      break;
    }
    ++i;
    skip_removed();
  }
  if (leading && !named && i < n && is_comment_only(lines.text[i]) &&
      !is_sinumerik_path_line(lines.text[i])) {
    ++i;
    skip_removed();
  }
  if (i >= n) return std::nullopt;
  return i;
}

// The line ending header lines get: the file's own (that of the line before them, else of the
// first line that has one).
std::string_view file_eol(const CleanLines& lines, std::size_t position) {
  for (std::size_t i = position; i-- > 0;)
    if (!lines.removed[i] && !lines.eol[i].empty()) return lines.eol[i];
  for (std::size_t i = 0; i < lines.eol.size(); ++i)
    if (!lines.removed[i] && !lines.eol[i].empty()) return lines.eol[i];
  return "\n";
}

// An inch program's blocks give MRR in in^3/min, the unit its programmer reads removal rates in
// (the header's MRR_IN3_MIN); a metric program's in mm^3/s.
double block_mrr_scale(bool inch) {
  return inch ? 60 / kMm3PerIn3 : 1.0;
}

std::vector<Field> block_fields(const LineSummary* summary, double end_s,
                                const OperationSummary* op, const BlockFields& want,
                                double mrr_scale) {
  std::vector<Field> fields;
  const double time_s = summary ? summary->time_s : 0.0;
  const double energy_j = summary ? summary->energy_j : 0.0;
  const double removed = summary ? summary->removed_mm3 : 0.0;
  const double power_w = time_s > 0 ? energy_j / time_s : 0.0;
  const double mrr = time_s > 0 ? mrr_scale * removed / time_s : 0.0;
  auto wanted = [&](bool field, double value) { return field && !(want.omit_zero && value == 0); };
  // The block's time is written even when it is 0: a block with no field is a block with no
  // comment, and the time is what says it was estimated.
  if (want.time) fields.push_back({"T=" + format_duration(time_s), 0});
  if (wanted(want.energy, energy_j)) fields.push_back({"E=" + format_si(energy_j, "J"), 1});
  if (wanted(want.power, power_w)) fields.push_back({"P=" + format_si(power_w, "W"), 5});
  if (wanted(want.mrr, mrr)) fields.push_back({"MRR=" + format_significant(mrr, 3, 3), 6});
  if (want.cumulative) fields.push_back({"CUM=" + format_duration(end_s), 7});
  // A cut asking the spindle for more than its rating: said on the block, never dropped.
  if (summary && summary->spindle_load > 1)
    fields.push_back({"LOAD_PCT=" + format_significant(100.0 * summary->spindle_load, 3, 0), 0});
  if (op && want.operation) {
    const std::string name = safe_token(op->name, kOperationNameLength);
    fields.push_back({"OP=" + (name.empty() ? "T" + std::to_string(op->tool) : name), 2});
    fields.push_back({"OPT=" + format_duration(op->time_s), 3});
    fields.push_back({"OPE=" + format_si(op->energy_j, "J"), 4});
  }
  if (fields.empty()) fields.push_back({"T=" + format_duration(time_s), 0});
  return fields;
}

// The block's comment, with as many fields as fit in `room` (the space before it included);
// empty when not even the time fits.
std::string block_comment(std::vector<Field> fields, std::size_t room, const CommentStyle& style) {
  while (true) {
    std::string content = "NCJ";
    content.reserve(room);
    for (const Field& f : fields) {
      content += ' ';
      content += f.text;
    }
    std::string comment = plain_comment(content, style);
    if (comment.size() + 1 <= room) return comment;
    auto last = std::max_element(fields.begin(), fields.end(), [](const Field& a, const Field& b) {
      return a.drop_rank < b.drop_rank;
    });
    if (last == fields.end() || last->drop_rank == 0) return {};
    fields.erase(last);
  }
}

// A block's comment goes on a line of its own, right before the block, when not even its time
// fits after the code (a long line, grbl's short one). Not in Heidenhain's ISO format, where a
// block carries its number and its '*'.
bool takes_comment_lines(const Dialect& dialect) {
  return !dialect.star_block_end;
}

// What a block gets: its comment, and where: after its code at `at`, or on a line of its own.
struct BlockNote {
  std::string comment; // empty: none
  std::size_t at = 0;
  bool own_line = false;
};

// The block's comment on `text`: after its code with the fields that fit there, else, when not
// even its time fits, on a line of its own before it (where the dialect allows such a line).
BlockNote block_note(std::string_view text, const std::vector<Field>& fields,
                     const Dialect& dialect, const WriteStyle& style) {
  BlockNote note;
  const std::optional<std::size_t> at = insertion_point(text, dialect, style.comment);
  if (at && text.size() < style.max_line_length) {
    note.comment = block_comment(fields, style.max_line_length - text.size(), style.comment);
    note.at = *at;
  }
  if (note.comment.empty() && takes_comment_lines(dialect)) {
    note.comment = block_comment(fields, style.max_line_length + 1, style.comment);
    note.own_line = !note.comment.empty();
  }
  return note;
}

// The "NCJ ..." part of a comment as written, as the seal counts it.
std::string normal_of(const std::string& comment, const CommentStyle& style) {
  return normal_text(std::string_view(comment).substr(
      style.open.size(), comment.size() - style.open.size() - style.close.size()));
}

// Where the SEAL field of a file without a header can go: just inside a block comment's end,
// with `room` bytes to spare on its line.
struct SealSpot {
  std::size_t offset = 0;
  std::size_t room = 0;
};

// What writing lines needs to know of the whole program.
struct ChunkContext {
  const CleanLines& lines;
  const std::vector<const LineSummary*>& summary;
  const std::map<std::size_t, const OperationSummary*>& operations;
  const AnnotateOptions& options;
  const Estimate& estimate;
  const WriteStyle& style;
  bool header; // output_line is wanted (the header names blocks by their output line)
  std::size_t header_line;
  double mrr_scale;
};

// A comment of the block form, in the order the file holds them: one of ours (its normal text
// in LineChunk::normals, and where the seal field could go) or one of the program's to keep.
struct CommentEvent {
  bool ours = false;
  std::size_t normal_size = 0;
  std::string keep_hash;
  std::size_t spot_offset = 0; // in the chunk's text
  std::size_t spot_room = 0;   // 0: no spot for the SEAL field
};

// Lines [first, last) written back with their comments, joined in order by annotate().
struct LineChunk {
  std::size_t first = 0, last = 0;
  std::string text;
  std::string normals; // our comments' normal texts, back to back
  std::vector<CommentEvent> events;
  std::vector<int> output_line;             // each line's output line, from 0 in the chunk
  int lines_written = 0;                    // lines of output, comment lines included
  std::optional<std::size_t> header_offset; // in text, where the header goes when it is here
  bool load_used = false, operation_used = false;
};

std::shared_ptr<LineChunk> write_lines(const ChunkContext& c, std::size_t first, std::size_t last) {
  auto chunk = std::make_shared<LineChunk>();
  chunk->first = first, chunk->last = last;
  std::string& out = chunk->text;
  const WriteStyle& style = c.style;
  if (c.header) chunk->output_line.assign(last - first, 0);
  int next = 0;
  auto ours = [&](const std::string& comment, std::size_t line_length) {
    const std::string normal = normal_of(comment, style.comment);
    CommentEvent e;
    e.ours = true;
    e.normal_size = normal.size();
    chunk->normals += normal;
    if (!c.header && line_length < style.max_line_length) {
      e.spot_offset = out.size() - style.comment.close.size();
      e.spot_room = style.max_line_length - line_length;
    }
    chunk->events.push_back(std::move(e));
  };
  for (std::size_t i = first; i < last; ++i) {
    if (i == c.header_line) chunk->header_offset = out.size();
    if (c.lines.removed[i]) continue;
    const std::string_view text = c.lines.text[i];
    const LineSummary* s = c.summary[i];
    const auto op = c.operations.find(i);
    const bool op_start = op != c.operations.end();
    BlockNote note;
    if ((s && (s->has_move || s->time_s > 0)) || op_start) {
      note = block_note(text,
                        block_fields(s, s ? s->end_s : 0.0, op_start ? op->second : nullptr,
                                     c.options.fields, c.mrr_scale),
                        c.estimate.dialect, style);
      chunk->load_used = chunk->load_used || (!note.comment.empty() && s && s->spindle_load > 1);
      chunk->operation_used = chunk->operation_used ||
                              (!note.comment.empty() && op_start && c.options.fields.operation);
    }
    if (note.own_line) {
      out += note.comment;
      ours(note.comment, note.comment.size());
      out += c.lines.eol[i].empty() ? file_eol(c.lines, i) : c.lines.eol[i];
      ++next;
    }
    if (c.header) chunk->output_line[i - first] = next;
    ++next;
    // The program's own comments of the block form, in order with ours.
    const std::vector<FoundComment> alike = block_comments(text);
    const std::size_t at = note.comment.empty() || note.own_line ? text.size() + 1 : note.at;
    std::size_t k = 0;
    auto keep_alike = [&](std::size_t upto) {
      for (; k < alike.size() && alike[k].begin < upto; ++k) {
        CommentEvent e;
        e.keep_hash = keep_hash(alike[k].normal);
        chunk->events.push_back(std::move(e));
      }
    };
    keep_alike(at);
    if (note.comment.empty() || note.own_line) {
      out += text;
    } else {
      out += text.substr(0, note.at);
      out += ' ';
      out += note.comment;
      ours(note.comment, text.size() + 1 + note.comment.size());
      out += text.substr(note.at);
    }
    keep_alike(text.size() + 1);
    out += c.lines.eol[i];
  }
  chunk->lines_written = next;
  return chunk;
}

} // namespace
} // namespace annotation

std::string annotate(const SourceFile& source, const Estimate& estimate,
                     const MachineProfile& machine, const AnnotateOptions& options) {
  using namespace annotation;
  const std::size_t n = source.lines.size();
  WriteStyle style;
  style.comment = comment_style(estimate.dialect);
  style.max_line_length = options.max_line_length            ? options.max_line_length
                          : estimate.dialect.max_line_length ? estimate.dialect.max_line_length
                                                             : kDefaultMaxLineLength;

  const CleanLines lines = clean_lines(source);
  // The estimate numbers the lines of the program without old annotations: line k of it is
  // source line source_of[k].
  std::vector<std::size_t> source_of;
  source_of.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!lines.removed[i]) source_of.push_back(i);
  auto in_source = [&](int line) -> std::optional<std::size_t> {
    if (line < 0 || static_cast<std::size_t>(line) >= source_of.size()) return std::nullopt;
    return source_of[static_cast<std::size_t>(line)];
  };
  std::vector<const LineSummary*> summary(n, nullptr);
  for (const LineSummary& s : estimate.lines)
    if (const auto i = in_source(s.line)) summary[*i] = &s;
  // The operations, by the line their fields go on (the tool change that starts them, else
  // their first block).
  std::map<std::size_t, const OperationSummary*> operations;
  if (options.operations)
    for (const OperationSummary& op : estimate.operations)
      if (const auto i = in_source(op.line)) operations.emplace(*i, &op);

  // The header, when there is a place for it and its seal line fits the dialect's lines.
  std::optional<std::size_t> header_at;
  WriteStyle header_style = style;
  header_style.max_line_length = std::min(style.max_line_length, kHeaderWidth);
  if (options.header) header_at = header_position(lines);
  if (header_at && seal_line(Seal{9999, 999999999, "00000000", {}}, style.comment).size() >
                       header_style.max_line_length)
    header_at.reset();
  const std::size_t header_line = header_at.value_or(n); // n: none
  std::vector<int> output_line;
  if (header_at) output_line.assign(n, 0);

  // Every line as it was, old annotations out, each block with its comment after its code or on
  // a line of its own before it. The lines are written in chunks on all cores and joined in
  // order (LineChunk): a program of millions of blocks keeps none of their comments beyond the
  // chunks in flight. The seal counts our comments, and lists the comments of the same form the
  // program held itself (a user's, or one pasted from an annotated file), to keep.
  std::string out;
  out.reserve(source.text.size() + source.text.size() / 2 + 1024);
  std::size_t header_offset = 0;
  int next = 1; // the output line the next line lands on
  SealSum sum;
  std::size_t blocks = 0, ordinal = 0;
  std::vector<KeptComment> keep;
  std::vector<SealSpot> spots;
  bool load_used = false, operation_used = false;
  const ChunkContext context{lines,
                             summary,
                             operations,
                             options,
                             estimate,
                             style,
                             header_at.has_value(),
                             header_line,
                             block_mrr_scale(estimate.inch)};
  // The chunk's text after what was joined so far; its comments counted in order.
  auto join = [&](LineChunk& chunk) {
    const std::size_t base = out.size();
    if (chunk.header_offset) header_offset = base + *chunk.header_offset;
    if (header_at)
      for (std::size_t i = chunk.first; i < chunk.last; ++i)
        if (!lines.removed[i]) output_line[i] = next + chunk.output_line[i - chunk.first];
    next += chunk.lines_written;
    std::size_t normal_at = 0;
    for (const CommentEvent& e : chunk.events) {
      ++ordinal;
      if (!e.ours) {
        keep.push_back({ordinal, e.keep_hash});
        continue;
      }
      ++blocks;
      sum.add_block(std::string_view(chunk.normals).substr(normal_at, e.normal_size));
      normal_at += e.normal_size;
      if (e.spot_room && spots.size() < 64) spots.push_back({base + e.spot_offset, e.spot_room});
    }
    load_used = load_used || chunk.load_used;
    operation_used = operation_used || chunk.operation_used;
    out += chunk.text;
  };
  constexpr std::size_t kChunkLines = 4096;
  make_in_order<std::shared_ptr<LineChunk>>(
      (n + kChunkLines - 1) / kChunkLines,
      [&](std::size_t k) {
        return write_lines(context, k * kChunkLines, std::min(n, (k + 1) * kChunkLines));
      },
      [&](const std::shared_ptr<LineChunk>& chunk) { join(*chunk); });

  if (header_at) {
    // The header: the summary, the keys, one line for each warning (which names its block's
    // line in the output, known now), the comments to keep; then the seal before them all.
    std::vector<std::string> header = summary_lines(estimate, machine, header_style);
    KeyUse keys;
    keys.fields = options.fields;
    keys.inch = estimate.inch;
    keys.load = load_used;
    keys.operation = operation_used;
    for (std::string& k : key_lines(keys, header_style))
      header.push_back(std::move(k));
    const std::vector<WarningText> warnings = header_warnings(estimate);
    std::vector<std::string> kept = keep_lines(keep, style.comment, header_style.max_line_length);
    // Lines after the header move down by its length (the seal line's included).
    const int header_length = int(1 + header.size() + warnings.size() + kept.size());
    for (std::string& w : warning_lines(warnings, header_style, [&](int line) {
           const auto i = in_source(line - 1);
           if (!i) return line;
           return output_line[*i] + (*i >= header_line ? header_length : 0);
         }))
      header.push_back(std::move(w));
    for (std::string& k : kept)
      header.push_back(std::move(k));
    for (const std::string& h : header)
      sum.add_header(normal_text(h));
    const Seal seal{header.size(), blocks, sum.value(header.size(), blocks), keep};
    const std::string_view eol = file_eol(lines, header_line);
    std::string text = seal_line(seal, style.comment);
    text += eol;
    for (const std::string& h : header) {
      text += h;
      text += eol;
    }
    out.insert(header_offset, text);
  } else if (blocks > 0) {
    // No header: the seal goes in a SEAL field of the first block comment with room for it.
    const Seal seal{0, blocks, sum.value(0, blocks), keep};
    std::string field = " SEAL=" + seal_field(seal);
    if (style.comment.upper_case)
      for (char& c : field)
        c = c >= 'a' && c <= 'z' ? char(c - 'a' + 'A') : c;
    for (const SealSpot& spot : spots) {
      if (spot.room < field.size()) continue;
      out.insert(spot.offset, field);
      break;
    }
  }
  return out;
}

AnnotatedProgram annotate_program(std::string path, std::string_view text,
                                  const MachineProfile& machine, const EstimateOptions& options,
                                  const AnnotateOptions& annotate_options) {
  AnnotatedProgram out;
  // The program as it was before any earlier annotation: what is estimated and written back.
  std::string stripped = strip(text);
  const bool had_annotations = stripped.size() != text.size(); // strip only takes bytes out
  const SourceFile program = make_source(path, std::move(stripped));
  out.estimate = estimate_program(program, machine, options);
  if (out.estimate.failed) return out;
  for (const Diagnostic& d : out.estimate.diagnostics)
    if (d.severity == Severity::Error) out.has_errors = true;
  // The old annotations are taken out of the text as it came, in the one pass strip() made:
  // what remains is exactly the program estimated, even where taking them out would let a
  // second pass find more.
  if (had_annotations)
    out.text = annotate(make_source(std::move(path), std::string(text)), out.estimate, machine,
                        annotate_options);
  else
    out.text = annotate(program, out.estimate, machine, annotate_options);
  return out;
}

} // namespace ncjoule
