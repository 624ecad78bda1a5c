// Shared by the annotator's tests: run a program through the real pipeline (without removal, so
// no tools are needed) on the generic sample machine, and look at what was inserted.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "line_alignment.hpp"
#include "ncjoule/annotate.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"

namespace annotate_test {

inline const ncjoule::MachineProfile& machine() {
  static const ncjoule::MachineProfile profile = ncjoule::load_profile(
      std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/generic-3axis.toml");
  return profile;
}

inline ncjoule::Estimate estimate(const ncjoule::SourceFile& source,
                                  std::optional<ncjoule::Dialect> dialect = std::nullopt) {
  ncjoule::EstimateOptions options;
  options.simulate_removal = false;
  options.dialect = std::move(dialect);
  return ncjoule::estimate_program(source, machine(), options);
}

// annotate() of `text`, its old annotations in it, with the estimate of the program without
// them.
inline std::string annotated(const std::string& text,
                             std::optional<ncjoule::Dialect> dialect = std::nullopt,
                             const ncjoule::AnnotateOptions& options = {}) {
  const ncjoule::SourceFile source = ncjoule::make_source("test.ngc", text);
  const ncjoule::SourceFile program = ncjoule::make_source("test.ngc", ncjoule::strip(text));
  return ncjoule::annotate(source, estimate(program, dialect), machine(), options);
}

// The lines of a text without their line endings.
inline std::vector<std::string> lines_of(const std::string& text) {
  const ncjoule::SourceFile source = ncjoule::make_source("lines", text);
  std::vector<std::string> out;
  for (std::size_t i = 0; i < source.lines.size(); ++i)
    out.emplace_back(source.line_text(i));
  return out;
}

inline std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

// The canonical commands a program runs in a dialect, as `ncjoule canon` prints them, comments
// left out (an annotation is one), each with the index of the line it came from in `original`:
// an annotated program must run exactly as the original.
inline std::vector<std::string> canon_of(const std::string& text, const ncjoule::Dialect& dialect,
                                         const std::string& original) {
  const std::vector<int> from = original_lines(lines_of(text), lines_of(original));
  const ncjoule::SourceFile source = ncjoule::make_source("canon.ngc", text);
  ncjoule::InterpreterOptions options;
  options.dialect = dialect;
  std::vector<std::string> out;
  ncjoule::interpret(source, options, [&](const ncjoule::CanonCommand& c) {
    if (c.kind == ncjoule::CanonKind::Comment) return;
    const int line = c.line >= 0 && std::size_t(c.line) < from.size() ? from[c.line] : -3;
    out.push_back(ncjoule::format_canon(c) + " @" + std::to_string(line));
  });
  return out;
}

inline std::string dialect_name_or_default(const std::optional<ncjoule::Dialect>& d) {
  return d ? d->name : "default";
}

} // namespace annotate_test
