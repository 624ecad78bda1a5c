// Lexing one line of G-code into words, parameter assignments, comments and O-words.
#include <algorithm>
#include <cctype>
#include <cstring>

#include "block.hpp"
#include "comment_syntax.hpp"
#include "ncjoule/text.hpp"

namespace ncjoule::detail {
namespace {

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
bool is_letter(char c) {
  return c >= 'a' && c <= 'z';
}
// ASCII only, like std::tolower in the "C" locale, without its per-character library call: this
// runs on every byte of the program.
char to_lower(char c) {
  return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c;
}

// Unary functions that may stand where a value is expected (LinuxCNC), e.g. "x abs[#1]".
constexpr const char* kFunctions[] = {"abs", "acos", "asin",  "atan", "cos",  "exp", "fix",
                                      "fup", "ln",   "round", "sin",  "sqrt", "tan", "exists"};

std::size_t bracket_length(std::string_view t, std::size_t pos, const BracketMatches* brackets) {
  // t[pos] == '['; returns the length up to and including the matching ']', or 0.
  if (brackets) return brackets->length(pos);
  int depth = 0;
  for (std::size_t i = pos; i < t.size(); ++i) {
    if (t[i] == '[')
      ++depth;
    else if (t[i] == ']' && --depth == 0)
      return i - pos + 1;
  }
  return 0;
}

// Length of a value with no sign or '#' before it: a number, [expr] or function[..].
std::size_t operand_length(std::string_view t, std::size_t pos, const BracketMatches* brackets) {
  if (pos >= t.size()) return 0;
  const char c = t[pos];
  if (is_digit(c) || c == '.') {
    std::size_t i = pos;
    bool digits = false;
    while (i < t.size() && is_digit(t[i]))
      ++i, digits = true;
    if (i < t.size() && t[i] == '.') {
      ++i;
      while (i < t.size() && is_digit(t[i]))
        ++i, digits = true;
    }
    return digits ? i - pos : 0;
  }
  if (c == '[') return bracket_length(t, pos, brackets);
  if (is_letter(c)) {
    for (const char* f : kFunctions) {
      const std::size_t len = std::strlen(f);
      if (t.compare(pos, len, f) == 0 && pos + len < t.size() && t[pos + len] == '[') {
        std::size_t n = bracket_length(t, pos + len, brackets);
        if (!n) return 0;
        std::size_t end = pos + len + n;
        // ATAN[y]/[x]
        if (len == 4 && t.compare(pos, 4, "atan") == 0 && end + 1 < t.size() && t[end] == '/' &&
            t[end + 1] == '[') {
          std::size_t m = bracket_length(t, end + 1, brackets);
          if (!m) return 0;
          end += 1 + m;
        }
        return end - pos;
      }
    }
  }
  return 0;
}

void add_error(Block& b, int column, std::string message) {
  b.errors.push_back(Diagnostic{Severity::Error, {}, 0, column, std::move(message)});
}
// A line's warnings, at most kMaxLineWarnings of them: a line of millions of stray words (4 MB
// of "x[") made one each, gigabytes of text for the interpreter to drop past its own cap of
// 1000. The message is made only when it is kept.
constexpr std::size_t kMaxLineWarnings = 100;
template <class Message> void add_warning(Block& b, int column, Message&& message) {
  if (b.warnings.size() > kMaxLineWarnings) return;
  if (b.warnings.size() == kMaxLineWarnings) {
    b.warnings.push_back(
        Diagnostic{Severity::Warning, {}, 0, column, "more problems on this line: not listed"});
    return;
  }
  b.warnings.push_back(Diagnostic{Severity::Warning, {}, 0, column, std::string(message())});
}

bool is_name_char(char c) {
  return is_letter(c) || is_digit(c) || c == '_';
}

std::string upper(std::string_view text) {
  std::string out(text);
  for (char& c : out)
    c = char(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// Whether what follows a word's letter at `at` sets out to be a value (a bracket or a parameter
// after any signs) that does not close: a broken expression, not a letter left alone.
bool starts_expression(std::string_view code, std::size_t at) {
  while (at < code.size() && (code[at] == '+' || code[at] == '-'))
    ++at;
  return at < code.size() && (code[at] == '[' || code[at] == '#');
}

// The number around an 'O' at code[p] when it stands inside one, with no blank on either side
// ("F1O8.": a zero typed as the letter O); empty otherwise. An O word of its own in the middle
// of a block is left to the interpreter: nccad's "M10 O6.0" sets an output.
std::string number_around_o(std::string_view code, std::size_t p, const std::vector<int>& columns) {
  auto adjacent = [&](std::size_t q) { return columns[q + 1] == columns[q] + 1; };
  std::size_t begin = p;
  while (begin > 0 && adjacent(begin - 1) && (is_digit(code[begin - 1]) || code[begin - 1] == '.'))
    --begin;
  if (begin == p || begin == 0 || !adjacent(begin - 1) || !is_letter(code[begin - 1]) ||
      p + 1 >= code.size() || !adjacent(p) || !is_digit(code[p + 1]))
    return {};
  std::size_t end = p + 1;
  while (end < code.size() && (is_digit(code[end]) || code[end] == '.'))
    ++end;
  return upper(code.substr(begin - 1, end - begin + 1));
}

} // namespace

void Block::clear() {
  code.clear();
  columns.clear();
  words.clear();
  assignments.clear();
  comments.clear();
  keywords.clear();
  warnings.clear();
  percent_name = {};
  block_delete = percent = percent_bare = dollar = has_o = false;
  percent_column = 0;
  o_label.clear();
  o_keyword.clear();
  o_args = {};
  o_column = 0;
  macro = {};
  errors.clear();
}

void BracketMatches::assign(std::string_view text) {
  match_.clear();
  text_ = {};
  const std::size_t first = text.find('[');
  if (first == std::string_view::npos) return;
  if (text.size() >= kNone) {
    text_ = text;
    return;
  }
  match_.assign(text.size(), kNone);
  std::uint32_t open = kNone; // the innermost '[' not closed yet; each links to the one around it
  for (std::size_t i = first; i < text.size(); ++i) {
    if (text[i] == '[') {
      match_[i] = open;
      open = static_cast<std::uint32_t>(i);
    } else if (text[i] == ']' && open != kNone) {
      const std::uint32_t around = match_[open];
      match_[open] = static_cast<std::uint32_t>(i);
      open = around;
    }
  }
}

std::size_t BracketMatches::length(std::size_t pos) const {
  if (!text_.empty()) return bracket_length(text_, pos, nullptr);
  if (pos >= match_.size() || match_[pos] == kNone || match_[pos] < pos) return 0;
  return match_[pos] - pos + 1;
}

std::size_t value_length(std::string_view t, std::size_t pos, const BracketMatches* brackets) {
  // Signs and numbered parameters' '#' are prefixes ("--#-#1"), passed over in a loop: a chain
  // of them, however long, takes no stack.
  std::size_t i = pos;
  for (; i < t.size(); ++i) {
    if (t[i] == '#' && i + 1 < t.size() && t[i + 1] == '<') {
      std::size_t close = t.find('>', i + 2);
      return close == std::string_view::npos ? 0 : close - pos + 1;
    }
    if (t[i] != '+' && t[i] != '-' && t[i] != '#') break;
  }
  const std::size_t n = operand_length(t, i, brackets);
  return n ? i - pos + n : 0;
}

namespace {

// Fanuc macro B writes an assignment's value without brackets ("#610=#597-#601", "#1=#2*SIN[#3]"):
// from the end of its first operand at `pos`, the length of the operators and operands that
// follow it. An operator is taken only when an operand follows, so "#1=2 X5" ends at "2".
std::size_t bare_tail_length(std::string_view t, std::size_t pos, const BracketMatches* brackets) {
  static constexpr std::string_view kOperators[] = {
      "**", "*", "/", "+", "-", "mod", "and", "xor", "or", "eq", "ne", "gt", "ge", "lt", "le"};
  std::size_t end = pos;
  for (;;) {
    std::size_t operand = 0, op_len = 0;
    for (std::string_view op : kOperators) {
      if (t.compare(end, op.size(), op) != 0) continue;
      operand = value_length(t, end + op.size(), brackets);
      if (operand) {
        op_len = op.size();
        break;
      }
    }
    if (!operand) return end - pos;
    end += op_len + operand;
  }
}

// Reads a Fanuc macro B control statement at code[p] into b.macro; returns where the block's
// remaining words start (after THEN), code.size() when the statement takes the whole block, or
// p when there is none.
std::size_t lex_macro_statement(std::string_view code, std::size_t p, Block& b) {
  const BracketMatches* brackets = &b.brackets;
  auto keyword = [&](std::string_view k) { return code.compare(p, k.size(), k) == 0; };
  auto loop_number = [&](std::size_t at) -> std::size_t {
    std::size_t len = value_length(code, at, brackets);
    if (!len) return 0;
    b.macro.target = code.substr(at, len);
    return at + len;
  };
  auto goto_at = [&](std::size_t at) -> std::size_t {
    if (code.compare(at, 4, "goto") != 0) return 0;
    std::size_t len = value_length(code, at + 4, brackets);
    if (!len) {
      add_error(b, b.columns[at], "GOTO needs the N number to go to");
      return code.size();
    }
    b.macro.target = code.substr(at + 4, len);
    return at + 4 + len;
  };
  auto condition_at = [&](std::size_t at) -> std::size_t {
    std::size_t len = at < code.size() && code[at] == '[' ? bracket_length(code, at, brackets) : 0;
    if (!len) return 0;
    b.macro.condition = code.substr(at, len);
    return at + len;
  };
  b.macro.column = b.columns[p];
  std::size_t end = 0;
  if (keyword("if[")) {
    b.macro.kind = MacroFlow::If;
    const std::size_t c = condition_at(p + 2);
    if (!c) {
      add_error(b, b.columns[p + 2], "IF needs a condition in brackets: IF [...] GOTO n");
      return code.size();
    }
    if (code.compare(c, 4, "then") == 0) {
      b.macro.then = true;
      return c + 4;
    }
    end = goto_at(c);
    if (!end) {
      add_error(b, c < code.size() ? b.columns[c] : b.columns[p],
                "IF [...] must be followed by GOTO n or THEN");
      return code.size();
    }
  } else if (keyword("while[")) {
    b.macro.kind = MacroFlow::While;
    const std::size_t c = condition_at(p + 5);
    end = c && code.compare(c, 2, "do") == 0 ? loop_number(c + 2) : 0;
    if (!end) {
      add_error(b, b.columns[p], "WHILE needs a condition in brackets and DO m: WHILE [...] DO1");
      return code.size();
    }
  } else if (keyword("goto")) {
    b.macro.kind = MacroFlow::Goto;
    end = goto_at(p);
  } else if (const std::size_t n = keyword("do")    ? 2
                                   : keyword("end") ? 3
                                                    : 0;
             n && p + n < code.size() && (is_digit(code[p + n]) || code[p + n] == '#')) {
    b.macro.kind = n == 2 ? MacroFlow::Do : MacroFlow::End;
    end = loop_number(p + n);
  } else {
    b.macro.column = 0;
    return p;
  }
  if (end < code.size())
    add_error(b, b.columns[end],
              "unexpected '" + std::string(code.substr(end)) +
                  "' after a macro statement (it takes the whole block)");
  return code.size();
}

} // namespace

void lex_line(std::string_view line, const Dialect& dialect, Block& b) {
  b.clear();
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n && (line[i] == ' ' || line[i] == '\t'))
    ++i;
  if (i < n && line[i] == '/') {
    b.block_delete = true;
    ++i;
  }
  if (dialect.dollar_lines && i < n && line[i] == '$') {
    b.dollar = true;
    return;
  }
  // Strip comments and blanks; lower-case the rest. Written through pointers into buffers of
  // the line's length, cut to what was kept at the end: this runs on every byte of the program.
  b.code.resize(n);
  b.columns.resize(n);
  char* const code_out = b.code.data();
  int* const column_out = b.columns.data();
  std::size_t kept = 0;
  auto keep = [&](char c, std::size_t at) {
    code_out[kept] = to_lower(c);
    column_out[kept] = int(at) + 1;
    ++kept;
  };
  while (i < n) {
    const char c = line[i];
    // Above '*' and not ';' (no blank, tab, parenthesis, star or semicolon, and no byte past
    // ASCII): code, whatever the dialect. Nearly every byte of a program is such a byte.
    if (c > '*' && c != ';') {
      keep(c, i);
      ++i;
      continue;
    }
    if (c == ' ' || c == '\t') {
      ++i;
    } else if (c == '(' && dialect.paren_argument_lists && opens_argument_list(line, i)) {
      // Copied as code (blanks inside dropped) for the word loop to read as arguments.
      std::size_t len = paren_length(line, i);
      if (!len) len = n - i;
      for (std::size_t k = i; k < i + len; ++k) {
        if (line[k] == ' ' || line[k] == '\t') continue;
        keep(line[k], k);
      }
      i += len;
    } else if (c == '*' && dialect.star_block_end) {
      break; // Heidenhain ISO: the end of the block
    } else if (c == '(' && dialect.paren_comments) {
      const std::size_t close = comment_close(line, i, dialect);
      if (close == std::string_view::npos) {
        // What the controller makes of it varies; the code before it is kept.
        add_warning(b, int(i) + 1, [] {
          return "comment is not closed: expected ')' before the end of the line; taken as a "
                 "comment to the end of the line";
        });
        b.comments.push_back({line.substr(i + 1), int(i) + 1});
        break;
      }
      b.comments.push_back({line.substr(i + 1, close - i - 1), int(i) + 1});
      i = close + 1;
    } else if (c == ';' && dialect.semicolon_comments) {
      b.comments.push_back({line.substr(i + 1), int(i) + 1});
      break;
    } else if (c == ';') {
      // Fanuc family: ';' is the end-of-block character (EOB) of tape format.
      if (line.find_first_not_of(" \t", i + 1) != std::string_view::npos)
        add_warning(b, int(i) + 1, [] { return "text after ';' (end of block) is ignored"; });
      break;
    } else {
      keep(c, i);
      ++i;
    }
  }
  b.code.resize(kept);
  b.columns.resize(kept);
  const std::string_view code = b.code;
  b.brackets.assign(code);
  const BracketMatches* brackets = &b.brackets;
  std::size_t p = 0;
  // N number first: skipped (it is a label, not a command).
  auto skip_n = [&] {
    if (p < code.size() && code[p] == 'n') {
      std::size_t q = p + 1;
      while (q < code.size() && (is_digit(code[q]) || code[q] == '.'))
        ++q;
      if (q > p + 1) p = q;
    }
  };
  skip_n();
  if (p < code.size() && code[p] == '%') {
    // A '%' tape delimiter, or a program name line: "%prog1" (UCCNC), "%PM" (Philips),
    // "%NAME G71" (Heidenhain ISO, where G70/G71 give the units).
    b.percent = true;
    b.percent_name = code.substr(p + 1);
    b.percent_bare = trim(line) == "%";
    b.percent_column = b.columns[p];
    return;
  }
  if (p < code.size() && code[p] == 'o' && p + 1 < code.size() &&
      (code[p + 1] == '<' || is_digit(code[p + 1]) || code[p + 1] == '[')) {
    b.has_o = true;
    b.o_column = b.columns[p];
    std::size_t q = p + 1;
    if (code[q] == '<') {
      std::size_t close = code.find('>', q);
      if (close == std::string_view::npos) {
        add_error(b, b.columns[q], "O-word name is not closed: expected '>'");
        return;
      }
      b.o_label = std::string(code.substr(q, close - q + 1));
      q = close + 1;
    } else if (code[q] == '[') {
      std::size_t len = bracket_length(code, q, brackets);
      if (!len) {
        add_error(b, b.columns[q], "O-word expression is not closed: expected ']'");
        return;
      }
      b.o_label = std::string(code.substr(q, len));
      q += len;
    } else {
      while (q < code.size() && is_digit(code[q]))
        ++q;
      // Numbers are labels: o0100 and o100 are the same.
      std::string digits(code.substr(p + 1, q - p - 1));
      std::size_t nz = digits.find_first_not_of('0');
      b.o_label = nz == std::string::npos ? "0" : digits.substr(nz);
    }
    std::size_t k = q;
    while (k < code.size() && is_letter(code[k]))
      ++k;
    b.o_keyword = std::string(code.substr(q, k - q));
    b.o_args = code.substr(k);
    return;
  }
  if (dialect.g65_macro_calls && p < code.size()) p = lex_macro_statement(code, p, b);
  // Bytes p and p + 1 of code were next to each other in the source (no blank or comment).
  auto adjacent = [&](std::size_t q) { return b.columns[q + 1] == b.columns[q] + 1; };
  while (p < code.size()) {
    const char c = code[p];
    if (is_letter(c) && p + 1 < code.size() && is_letter(code[p + 1]) && adjacent(p) &&
        value_length(code, p + 1, brackets) == 0) {
      // A word of several letters: MCALL, TRANS, CYCLE81(...), RPL=45, GOTO ...
      std::size_t q = p + 1;
      while (q + 1 < code.size() && is_name_char(code[q + 1]) && adjacent(q))
        ++q;
      ++q;
      Keyword k{code.substr(p, q - p), {}, false, b.columns[p]};
      if (q < code.size() && code[q] == '(') {
        std::size_t len = paren_length(code, q);
        if (!len) len = code.size() - q;
        k.has_parens = true;
        k.args = code.substr(q + 1, len >= 2 && code[q + len - 1] == ')' ? len - 2 : len - 1);
        q += len;
      } else if (q < code.size() && code[q] == '=') {
        std::size_t len = value_length(code, q + 1, brackets);
        k.args = code.substr(q + 1, len);
        q += 1 + len;
      }
      b.keywords.push_back(k);
      p = q;
    } else if (const std::string number = c == 'o' && dialect.name != "reprap"
                                              ? number_around_o(code, p, b.columns)
                                              : std::string();
               !number.empty()) {
      add_error(b, b.columns[p],
                "the letter O inside the number '" + number +
                    "' (a zero typed as O?): the control refuses the block (LinuxCNC: bad "
                    "character 'o'; Fanuc and Haas alarm)");
      return;
    } else if (is_letter(c) || c == '@' || c == '^') {
      std::size_t at = p + 1;
      if (at < code.size() && code[at] == '=' && is_letter(c)) ++at; // Sinumerik "X=10"
      std::size_t len = value_length(code, at, brackets);
      // Sinumerik's "Y=COS (0)": a value after '=' this lexer does not read, not a letter alone.
      const bool assigned = at > p + 1 && at < code.size();
      if (len == 0 && is_letter(c) && !dialect.lenient_words && !assigned &&
          !starts_expression(code, at)) {
        add_error(b, b.columns[p],
                  "word '" + upper(std::string_view(&c, 1)) +
                      "' has no value: the control refuses the block (LinuxCNC: no characters "
                      "found in reading real value; Fanuc and Haas alarm)");
        return;
      }
      if (len == 0) {
        add_warning(b, b.columns[p], [&] {
          return std::string("word '") + char(std::toupper(c)) +
                 "' has no number after it: ignored (the rest of the block still runs)";
        });
        ++p;
        continue;
      }
      std::size_t next = at + len;
      if (next < code.size() && code[next] == '.' && !dialect.lenient_words &&
          (is_digit(code[next - 1]) || code[next - 1] == '.')) {
        std::size_t end = next;
        while (end < code.size() && (is_digit(code[end]) || code[end] == '.'))
          ++end;
        add_error(b, b.columns[p],
                  "two decimal points in '" + upper(code.substr(p, end - p)) +
                      "': the control refuses the block (LinuxCNC: bad number format; Fanuc "
                      "and Haas alarm)");
        return;
      }
      if (next < code.size() && code[next] == '=') {
        // "R1=5" (Sinumerik R parameters) and the like: an assignment this interpreter does
        // not keep.
        std::size_t vlen = value_length(code, next + 1, brackets);
        add_warning(b, b.columns[p], [&] {
          return "assignment '" + std::string(code.substr(p, next + 1 + vlen - p)) +
                 "' is not supported: ignored";
        });
        p = next + 1 + vlen;
        continue;
      }
      b.words.push_back({c, b.columns[p], code.substr(at, len)});
      p = next;
    } else if (c == '#') {
      // Parameter assignment: #target=value
      std::size_t t0 = p + 1, t1 = t0;
      if (t1 < code.size() && code[t1] == '<') {
        std::size_t close = code.find('>', t1);
        t1 = close == std::string_view::npos ? code.size() : close + 1;
      } else {
        std::size_t len = value_length(code, t1, brackets);
        t1 += len;
      }
      if (t1 >= code.size() || code[t1] != '=' || t1 == t0) {
        add_error(b, b.columns[p], "expected '#parameter=value'");
        return;
      }
      std::size_t len = value_length(code, t1 + 1, brackets);
      if (len == 0) {
        add_error(b, t1 + 1 < code.size() ? b.columns[t1 + 1] : b.columns[t1],
                  "expected a value after '='");
        return;
      }
      const std::size_t tail =
          dialect.g65_macro_calls ? bare_tail_length(code, t1 + 1 + len, brackets) : 0;
      b.assignments.push_back(
          {code.substr(t0, t1 - t0), code.substr(t1 + 1, len + tail), b.columns[p], tail > 0});
      p = t1 + 1 + len + tail;
    } else {
      // Characters no controller family here gives a meaning to: skipped with a warning.
      std::size_t q = p + 1;
      while (q < code.size() && !is_letter(code[q]) && code[q] != '#' && code[q] != '@' &&
             code[q] != '^')
        ++q;
      add_warning(b, b.columns[p], [&] {
        return "unexpected '" + std::string(code.substr(p, q - p)) +
               "': ignored (the rest of the block still runs)";
      });
      p = q;
    }
  }
}

} // namespace ncjoule::detail
