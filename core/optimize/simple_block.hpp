// Internal: the blocks optimize may change, read word by word. A simple block holds only N, G0 or
// G1, X, Y, Z and F words (each once, plain numbers) and comments; anything else (an expression,
// a parameter, another code, a block delete) makes it not simple, and it is never changed.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::optimize_detail {

struct Word {
  char letter = 0;        // upper case
  std::size_t begin = 0;  // of the letter
  std::size_t end = 0;    // one past the number
  std::size_t number = 0; // where the number starts
  double value = 0;
};

struct SimpleBlock {
  std::vector<Word> words;
  std::size_t code_end = 0; // one past the last word: where a mark goes
  const Word* find(char letter) const;
  bool has(char letter) const { return find(letter) != nullptr; }
};

// The block on `line` when it is simple in `dialect`'s comment syntax; std::nullopt otherwise
// (a line without words is not one either).
std::optional<SimpleBlock> read_simple_block(std::string_view line, const Dialect& dialect);

// Whether the line writes a motion word of group 1 (G0..G3, G00..G03) among plain words; false
// when it cannot tell (an expression, a parameter).
bool writes_motion_word(std::string_view line, const Dialect& dialect);

} // namespace ncjoule::optimize_detail
