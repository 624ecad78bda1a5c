// Test helpers: run a program held in memory through the interpreter and look at what came out.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::test {

// Interprets `text` as file "test.ngc" in the named dialect ("" = detect from the text).
inline Toolpath run(const std::string& text, const std::string& dialect = "linuxcnc",
                    ToolTable tools = {}) {
  const SourceFile source = make_source("test.ngc", text);
  InterpreterOptions options;
  if (!dialect.empty()) options.dialect = find_dialect(dialect);
  options.tools = std::move(tools);
  options.max_commands = 100000;
  return interpret(source, options);
}

// The rs274-style lines of the commands that have one.
inline std::vector<std::string> canon(const Toolpath& path) {
  std::vector<std::string> lines;
  for (const CanonCommand& c : path.commands)
    if (std::string line = format_canon(c); !line.empty()) lines.push_back(std::move(line));
  return lines;
}

// Only moves and dwells, as rs274 prints them.
inline std::vector<std::string> moves(const Toolpath& path) {
  std::vector<std::string> lines;
  for (const CanonCommand& c : path.commands)
    if (is_move(c.kind) || c.kind == CanonKind::Dwell) lines.push_back(format_canon(c));
  return lines;
}

// The move commands themselves.
inline std::vector<CanonCommand> move_commands(const Toolpath& path) {
  std::vector<CanonCommand> out;
  for (const CanonCommand& c : path.commands)
    if (is_move(c.kind)) out.push_back(c);
  return out;
}

inline std::vector<CanonCommand> of_kind(const Toolpath& path, CanonKind kind) {
  std::vector<CanonCommand> out;
  for (const CanonCommand& c : path.commands)
    if (c.kind == kind) out.push_back(c);
  return out;
}

inline std::vector<Diagnostic> with_severity(const Toolpath& path, Severity severity) {
  std::vector<Diagnostic> out;
  for (const Diagnostic& d : path.result.diagnostics)
    if (d.severity == severity) out.push_back(d);
  return out;
}

inline std::size_t errors(const Toolpath& path) {
  return with_severity(path, Severity::Error).size();
}
inline std::size_t warnings(const Toolpath& path) {
  return with_severity(path, Severity::Warning).size();
}

inline std::size_t notes(const Toolpath& path) {
  return with_severity(path, Severity::Note).size();
}

// Canonical lines as format_canon prints them, for expected move lists in tests.
inline std::string T(double x, double y, double z) {
  char b[128];
  std::snprintf(b, sizeof b, "STRAIGHT_TRAVERSE(%.4f, %.4f, %.4f, 0.0000, 0.0000, 0.0000)", x, y,
                z);
  return b;
}
inline std::string F(double x, double y, double z) {
  char b[128];
  std::snprintf(b, sizeof b, "STRAIGHT_FEED(%.4f, %.4f, %.4f, 0.0000, 0.0000, 0.0000)", x, y, z);
  return b;
}
inline std::string D(double seconds) {
  char b[64];
  std::snprintf(b, sizeof b, "DWELL(%.4f)", seconds);
  return b;
}

} // namespace ncjoule::test
