// Diagnostics: every reader's problems (programs, profiles, job files, STL files, tool and stock
// texts) are reported one way, with the file, line and column they concern and a severity.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace ncjoule {

enum class Severity { Note, Warning, Error };

struct Diagnostic {
  Severity severity = Severity::Error;
  std::string file;
  int line = 0;   // 1-based
  int column = 0; // 1-based, 0 when the whole line is meant
  std::string message;
};

// "file:line:column: error: message"; "file: error: message" when the line is 0 (a whole file,
// or a command-line option named as the file).
std::string format_diagnostic(const Diagnostic& d);
// Text from a user (a file name, a word of a program) as it may be printed: control bytes, bytes
// that are not UTF-8, C1 controls and bidirectional overrides escaped (\x1b, \u{202e}).
// format_diagnostic prints the file so, and the message too with any run of more than 200
// characters without a blank (a 10 MB word) cut to 160 and the number of bytes left out.
std::string printable(std::string_view text);

// Where a piece of text handed to a reader came from, so that the reader's problems are reported
// like a program's: a file with the line and column of the text's first character (a TOML
// string's value), or a command-line option (file "--tool '1:flot:6'", line 0). Readers of small
// texts (a tool, a stock, a list of fields) take one and add diagnostics made by `at`.
struct TextOrigin {
  std::string file;
  int line = 0;
  int column = 0; // of the text's first character; 0: not known
  // An error `offset` characters into the text.
  Diagnostic at(std::size_t offset, std::string message, Severity severity = Severity::Error) const;
};

} // namespace ncjoule
