// What alignment needs of a program, read from its text: each line's N number and tool change,
// its title and where it ends. A light reading (comments out, words in), enough to follow a
// control's line or N-number log; the program's timing comes from the estimate.
#include <cctype>
#include <cstdlib>

#include "ncjoule/logs.hpp"

namespace ncjoule {
namespace {

// The line without its comments, in upper case: "( ... )" and "; ..." both go, as every
// dialect that logs over MTConnect writes them.
std::string code_of(std::string_view line) {
  std::string out;
  int depth = 0;
  for (char c : line) {
    if (c == ';' && depth == 0) break;
    if (c == '(')
      ++depth;
    else if (c == ')' && depth > 0)
      --depth;
    else if (depth == 0)
      out += char(std::toupper(static_cast<unsigned char>(c)));
  }
  return out;
}

// The words of a line: letter and number, blanks allowed between (N 10, G 0).
std::vector<std::pair<char, double>> words_of(const std::string& code) {
  std::vector<std::pair<char, double>> words;
  for (std::size_t i = 0; i < code.size(); ++i) {
    const char c = code[i];
    if (c < 'A' || c > 'Z') continue;
    std::size_t j = i + 1;
    while (j < code.size() && code[j] == ' ')
      ++j;
    const char* begin = code.c_str() + j;
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin) continue; // a letter without a number: a keyword, not a word
    words.emplace_back(c, v);
    i = std::size_t(end - code.c_str()) - 1;
  }
  return words;
}

} // namespace

ProgramOutline outline_program(const SourceFile& source) {
  ProgramOutline p;
  p.path = source.path;
  const std::size_t slash = source.path.find_last_of("/\\");
  p.name = slash == std::string::npos ? source.path : source.path.substr(slash + 1);
  p.lines = int(source.lines.size());
  p.n_word.assign(source.lines.size() + 1, -1);
  p.tool_at.assign(source.lines.size() + 1, 0);
  p.code.assign(source.lines.size() + 1, 0);
  int selected = -1;
  for (std::size_t i = 0; i < source.lines.size(); ++i) {
    const std::string_view raw = source.line_text(i);
    const std::size_t line = i + 1;
    if (p.title.empty() && line <= 5) {
      std::size_t k = 0;
      while (k < raw.size() && std::isspace(static_cast<unsigned char>(raw[k])))
        ++k;
      if (k < raw.size() && (raw[k] == 'O' || raw[k] == 'o' || raw[k] == '(' || raw[k] == ':'))
        p.title = std::string(raw.substr(k));
    }
    const std::string code = code_of(raw);
    const auto words = words_of(code);
    if (words.empty()) continue;
    p.code[line] = 1;
    bool change = false, end = false;
    for (const auto& [letter, value] : words) {
      if (letter == 'T') selected = int(value);
      if (letter == 'M' && (value == 6)) change = true;
      if (letter == 'M' && (value == 2 || value == 30)) end = true;
    }
    if (words.front().first == 'N') p.n_word[line] = long(words.front().second);
    if (change) p.tool_at[line] = selected > 0 ? selected : -1;
    if (end && p.end_line == 0) p.end_line = int(line);
  }
  return p;
}

} // namespace ncjoule
