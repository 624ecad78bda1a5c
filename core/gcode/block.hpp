// Internal: one parsed line of G-code.
//
// The lexer strips white space and comments, lower-cases the code, and cuts it into words
// whose values are still unevaluated expression text: values depend on parameters, which change
// as the program runs, so they are evaluated only when the block executes.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::detail {

struct Word {
  char letter = 0;        // 'a'..'z', or '@' and '^' (LinuxCNC polar radius and angle)
  int column = 0;         // 1-based column of the letter in the source line
  std::string_view value; // expression text in Block::code (lower case, no blanks)
};

// #<index-or-name> = value, applied after every word of the line has been read.
struct Assignment {
  std::string_view target; // text after '#': "1", "<name>", "[expr]"
  std::string_view value;
  int column = 0;
  // Fanuc macro B: the value is an expression without brackets ("#3=#1-#2*2"), read to the
  // end of its operators with their precedence.
  bool bare_expression = false;
};

// A word of two or more letters (Sinumerik MCALL, TRANS, CYCLE81(...), RPL=45; Fanuc macro B
// keywords), kept by name for the interpreter to honour or warn about.
struct Keyword {
  std::string_view name; // lower case, letters, digits and '_'
  std::string_view args; // inside "( )", or after '=': unevaluated, lower case, no blanks
  bool has_parens = false;
  int column = 0;
};

struct Comment {
  std::string_view text; // inside the parentheses, or after ';', as written
  int column = 0;
};

// The matching ']' of every '[' of a text, found in one pass: the lexer then finds where each
// value ends by a lookup, where a scan to the end of the line for each word made a line of
// unclosed brackets ("x[x[x[...") quadratic in its length. Four bytes per byte of a line that
// has a '[' (as Block::columns), none for the others.
class BracketMatches {
public:
  void assign(std::string_view text);
  // Length from the '[' at `pos` to its matching ']', both included; 0 when it has none.
  std::size_t length(std::size_t pos) const;

private:
  // At each '[': the position of its ']' (greater), or, while assigning and for one never
  // closed, that of the '[' around it (smaller), or kNone.
  static constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> match_;
  std::string_view text_; // past 4 GiB positions do not fit: scanned instead
};

// Fanuc macro B control flow (Custom Macro B: "IF [c] GOTO n", "IF [c] THEN <assignment>",
// "GOTO n", "WHILE [c] DO m", "DO m", "END m").
enum class MacroFlow { None, If, Goto, While, Do, End };
struct MacroStatement {
  MacroFlow kind = MacroFlow::None;
  std::string_view condition; // "[...]" of IF and WHILE
  std::string_view target;    // the GOTO's N number or the DO/END loop number (a value)
  bool then = false;          // IF ... THEN: the block's words and assignments run if true
  int column = 0;
};

struct Block {
  std::string code;         // lower case, blanks and comments removed
  BracketMatches brackets;  // of code
  std::vector<int> columns; // source column (1-based) of each byte of code
  std::vector<Word> words;
  std::vector<Assignment> assignments;
  std::vector<Keyword> keywords;
  std::vector<Comment> comments;
  bool block_delete = false;     // line starts with '/'
  bool percent = false;          // a '%' delimiter line
  std::string_view percent_name; // text after '%' on that line (Heidenhain "%NAME G71")
  bool percent_bare = false;     // nothing but '%' and blanks on that line
  int percent_column = 0;
  bool dollar = false; // a grbl '$' settings line
  // O-word control flow (LinuxCNC) or O-number program header (Fanuc).
  bool has_o = false;
  std::string o_label;     // "<name>" or digits, lower case
  std::string o_keyword;   // sub, endsub, call, if, elseif, else, endif, while, endwhile,
                           // do, repeat, endrepeat, return, break, continue; empty: header
  std::string_view o_args; // the rest of the line after the keyword
  int o_column = 0;
  MacroStatement macro;
  std::vector<Diagnostic> errors; // lexical errors (line numbers filled in by the caller)
  // Problems that cost one word or character, not the block: the rest of the block runs.
  std::vector<Diagnostic> warnings;

  void clear();
  bool has_code() const {
    return !words.empty() || !assignments.empty() || !keywords.empty() || has_o ||
           macro.kind != MacroFlow::None;
  }
};

// Cuts one source line into a block. `block` is reused to avoid allocations.
void lex_line(std::string_view line, const Dialect& dialect, Block& block);

// Length of the value expression starting at text[pos] (number, [expr], #param, function[..]).
// Returns 0 when there is no valid value there. `brackets`, when given, are those of `text`.
std::size_t value_length(std::string_view text, std::size_t pos,
                         const BracketMatches* brackets = nullptr);

} // namespace ncjoule::detail
