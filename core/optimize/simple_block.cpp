#include "simple_block.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>

namespace ncjoule::optimize_detail {
namespace {

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

// The plain number at line[pos] ([+-]digits[.digits] or [+-].digits): its length, 0 if none.
std::size_t number_length(std::string_view line, std::size_t pos) {
  std::size_t i = pos;
  if (i < line.size() && (line[i] == '+' || line[i] == '-')) ++i;
  std::size_t digits = 0;
  while (i < line.size() && is_digit(line[i]))
    ++i, ++digits;
  if (i < line.size() && line[i] == '.') {
    ++i;
    while (i < line.size() && is_digit(line[i]))
      ++i, ++digits;
  }
  return digits ? i - pos : 0;
}

// Reads plain words and comments; calls `word` for each word. False at anything else.
template <class OnWord>
bool scan_words(std::string_view line, const Dialect& dialect, OnWord&& word) {
  if (dialect.star_block_end || dialect.sinumerik_words) return false;
  std::size_t i = 0;
  while (i < line.size()) {
    const char c = line[i];
    if (c == ' ' || c == '\t') {
      ++i;
    } else if (c == '(' && dialect.paren_comments) {
      const std::size_t close = line.find(')', i + 1);
      if (close == std::string_view::npos) return false;
      if (dialect.nested_paren_comments &&
          line.substr(i + 1, close - i - 1).find('(') != std::string_view::npos)
        return false;
      i = close + 1;
    } else if (c == ';' && dialect.semicolon_comments) {
      return true;
    } else if (std::isalpha(static_cast<unsigned char>(c))) {
      const std::size_t n = number_length(line, i + 1);
      if (n == 0) return false;
      if (!word(char(std::toupper(static_cast<unsigned char>(c))), i, i + 1, i + 1 + n))
        return false;
      i += 1 + n;
    } else {
      return false;
    }
  }
  return true;
}

} // namespace

const Word* SimpleBlock::find(char letter) const {
  for (const Word& w : words)
    if (w.letter == letter) return &w;
  return nullptr;
}

std::optional<SimpleBlock> read_simple_block(std::string_view line, const Dialect& dialect) {
  SimpleBlock block;
  const bool ok = scan_words(
      line, dialect, [&](char letter, std::size_t begin, std::size_t number, std::size_t end) {
        const std::string text(line.substr(number, end - number));
        const double value = std::strtod(text.c_str(), nullptr);
        switch (letter) {
        case 'N':
        case 'X':
        case 'Y':
        case 'Z':
        case 'F':
          break;
        case 'G':
          // G0, G1, G00, G01 as written: digits only, no sign, no decimals.
          if (text.find_first_not_of("0123456789") != std::string::npos ||
              (value != 0 && value != 1))
            return false;
          break;
        default:
          return false;
        }
        if (block.has(letter)) return false;
        if (letter == 'F' && !(value > 0)) return false;
        block.words.push_back({letter, begin, end, number, value});
        block.code_end = end;
        return true;
      });
  if (!ok || block.words.empty()) return std::nullopt;
  return block;
}

bool writes_motion_word(std::string_view line, const Dialect& dialect) {
  bool motion = false;
  const bool ok =
      scan_words(line, dialect, [&](char letter, std::size_t, std::size_t number, std::size_t end) {
        if (letter != 'G') return true;
        const std::string_view text = line.substr(number, end - number);
        if (text.find_first_not_of("0123456789") != std::string_view::npos) return true;
        const int value = std::atoi(std::string(text).c_str());
        if (value >= 0 && value <= 3) motion = true;
        return true;
      });
  return ok && motion;
}

} // namespace ncjoule::optimize_detail
