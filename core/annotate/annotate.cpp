// annotate(): the program's lines, byte for byte, with one comment per block that moves or takes
// time, per-operation subtotals on tool-change lines, and the header after the % and O-number
// lines.
#include <algorithm>
#include <map>
#include <optional>
#include <vector>

#include "header.hpp"
#include "line_layout.hpp"
#include "marker.hpp"
#include "ncjoule/annotate.hpp"
#include "number_format.hpp"
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
  std::vector<bool> old_header;       // a header line of an earlier run: left out
};

CleanLines clean_lines(const SourceFile& source) {
  CleanLines c;
  const std::size_t n = source.lines.size();
  c.text.resize(n);
  c.eol.resize(n);
  c.old_header.resize(n);
  std::vector<std::pair<std::size_t, std::string>> changed;
  std::string scratch;
  for (std::size_t i = 0; i < n; ++i) {
    const LineSpan& span = source.lines[i];
    c.eol[i] = std::string_view(source.text).substr(span.begin + span.length, span.eol_length);
    const std::string_view line = source.line_text(i);
    c.text[i] = line;
    if (is_header_line(line)) {
      c.old_header[i] = true;
      c.text[i] = {};
      continue;
    }
    scratch.clear();
    if (strip_inline(line, scratch)) changed.emplace_back(i, scratch);
  }
  c.storage.reserve(changed.size()); // no reallocation: the views below point into it
  for (auto& [i, text] : changed) {
    c.storage.push_back(std::move(text));
    c.text[i] = c.storage.back();
  }
  return c;
}

// The index of the first line the header goes before, or nullopt when there is no line to put
// it before (an empty file, or one holding only a % and an O-number line).
std::optional<std::size_t> header_position(const CleanLines& lines) {
  const std::size_t n = lines.text.size();
  std::size_t i = 0;
  auto skip_old_headers = [&] {
    while (i < n && lines.old_header[i])
      ++i;
  };
  skip_old_headers();
  if (i < n && is_percent_line(lines.text[i])) {
    ++i;
    skip_old_headers();
  }
  if (i < n && is_program_number_line(lines.text[i])) {
    ++i;
    skip_old_headers();
  }
  if (i >= n) return std::nullopt;
  return i;
}

// The line ending header lines get: the file's own (that of the line before them, else of the
// first line that has one).
std::string_view header_eol(const CleanLines& lines, std::size_t position) {
  for (std::size_t i = position; i-- > 0;)
    if (!lines.old_header[i] && !lines.eol[i].empty()) return lines.eol[i];
  for (std::size_t i = 0; i < lines.eol.size(); ++i)
    if (!lines.old_header[i] && !lines.eol[i].empty()) return lines.eol[i];
  return "\n";
}

std::vector<Field> block_fields(const LineSummary* summary, double end_s,
                                const OperationSummary* op, const BlockFields& want) {
  std::vector<Field> fields;
  const double time_s = summary ? summary->time_s : 0.0;
  const double energy_j = summary ? summary->energy_j : 0.0;
  const double removed = summary ? summary->removed_mm3 : 0.0;
  const double power_w = time_s > 0 ? energy_j / time_s : 0.0;
  const double mrr = time_s > 0 ? removed / time_s : 0.0;
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

// The block's comment, with as many fields as fit on the line; empty when not even the time
// fits.
std::string block_comment(std::vector<Field> fields, std::size_t room, const WriteStyle& style) {
  while (true) {
    std::string content = "NCJ";
    content.reserve(room);
    for (const Field& f : fields) {
      content += ' ';
      content += f.text;
    }
    std::string comment = marked_comment(content, MarkKind::Inline, style.comment);
    if (comment.size() + 1 <= room) return comment;
    auto last = std::max_element(fields.begin(), fields.end(), [](const Field& a, const Field& b) {
      return a.drop_rank < b.drop_rank;
    });
    if (last == fields.end() || last->drop_rank == 0) return {};
    fields.erase(last);
  }
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
  std::vector<const LineSummary*> summary(n, nullptr);
  for (const LineSummary& s : estimate.lines)
    if (s.line >= 0 && static_cast<std::size_t>(s.line) < n) summary[s.line] = &s;
  // The operations, by the line their fields go on (the tool change that starts them, else
  // their first block).
  std::map<int, const OperationSummary*> operations;
  if (options.operations)
    for (const OperationSummary& op : estimate.operations)
      if (op.line >= 0 && static_cast<std::size_t>(op.line) < n) operations.emplace(op.line, &op);

  std::optional<std::size_t> header_at;
  if (options.header) header_at = header_position(lines);
  WriteStyle header_style = style;
  header_style.max_line_length = std::min(style.max_line_length, kHeaderWidth);
  // Where each source line lands in the output: old header lines leave, the new header comes in
  // at header_at: the summary's lines, then one line for each warning.
  std::vector<std::string> header;
  if (header_at) {
    header = summary_lines(estimate, machine, header_style);
    const std::vector<WarningText> warnings = header_warnings(estimate);
    std::vector<int> output_line(n + 1, 0);
    int next = 1;
    for (std::size_t i = 0; i < n; ++i) {
      if (i == *header_at) next += static_cast<int>(header.size() + warnings.size());
      output_line[i] = next;
      if (!lines.old_header[i]) ++next;
    }
    for (std::string& w : warning_lines(warnings, header_style, [&](int line) {
           return line >= 1 && static_cast<std::size_t>(line) <= n ? output_line[line - 1] : line;
         }))
      header.push_back(std::move(w));
  }

  std::string out;
  out.reserve(source.text.size() + source.text.size() / 2 + 1024);
  for (std::size_t i = 0; i < n; ++i) {
    if (header_at && *header_at == i) {
      const std::string_view eol = header_eol(lines, i);
      for (const std::string& h : header) {
        out += h;
        out += eol;
      }
    }
    if (lines.old_header[i]) continue;
    const std::string_view text = lines.text[i];
    const LineSummary* s = summary[i];
    const auto op = operations.find(static_cast<int>(i));
    const bool op_start = op != operations.end();
    const bool timed = s && (s->has_move || s->time_s > 0);
    const std::optional<std::size_t> at =
        timed || op_start ? insertion_point(text, style.comment) : std::nullopt;
    std::string comment;
    if (at && text.size() < style.max_line_length)
      comment = block_comment(
          block_fields(s, s ? s->end_s : 0.0, op_start ? op->second : nullptr, options.fields),
          style.max_line_length - text.size(), style);
    if (comment.empty()) {
      out += text;
    } else {
      out += text.substr(0, *at);
      out += ' ';
      out += comment;
      out += text.substr(*at);
    }
    out += lines.eol[i];
  }
  return out;
}

AnnotatedProgram annotate_program(std::string path, std::string_view text,
                                  const MachineProfile& machine, const EstimateOptions& options,
                                  const AnnotateOptions& annotate_options) {
  AnnotatedProgram out;
  // The program as it was before any earlier annotation: what is estimated and written back.
  const SourceFile program = make_source(std::move(path), strip(text));
  out.estimate = estimate_program(program, machine, options);
  if (out.estimate.failed) return out;
  for (const Diagnostic& d : out.estimate.diagnostics)
    if (d.severity == Severity::Error) out.has_errors = true;
  out.text = annotate(program, out.estimate, machine, annotate_options);
  return out;
}

} // namespace ncjoule
