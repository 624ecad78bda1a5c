// Internal: evaluation of G-code values and [ ] expressions (LinuxCNC and Fanuc macro syntax).
#pragma once

#include <limits>
#include <string>
#include <string_view>

namespace ncjoule::detail {

// Brackets an expression may nest (function brackets and #[...] included). LinuxCNC reads lines
// of at most 256 bytes, which cannot nest more than 127; the evaluator recurses once per level,
// so the limit also bounds the stack an expression takes, whatever its length.
constexpr int kMaxExpressionNesting = 128;

// Where an expression reads its parameters from.
class ParameterReader {
public:
  virtual ~ParameterReader() = default;
  // Returns false with `error` set when the parameter does not exist or cannot be read.
  virtual bool read(int index, double& value, std::string& error) = 0;
  virtual bool read(std::string_view name, double& value, std::string& error) = 0;
  virtual bool exists(std::string_view name) = 0;
};

// Evaluates `text` (lower case, no blanks), e.g. "-1.5", "[#1*2]", "#<depth>", "sin[30]".
// Returns false with a message on error; `offset` is then the position of the problem.
bool evaluate(std::string_view text, ParameterReader& params, double& value, std::string& error,
              std::size_t& offset);

// Evaluates an expression written without its brackets, as the right side of a Fanuc macro B
// assignment ("#1-#2*sin[30]"): the same as evaluate("[" + text + "]").
bool evaluate_bare(std::string_view text, ParameterReader& params, double& value,
                   std::string& error, std::size_t& offset);

// Converts a program value to an integer type, saturating at the type's range (NaN gives 0):
// casting an out-of-range double is undefined behaviour, and a program may well say G1e300.
template <class Int> Int saturate(double value) {
  if (!(value == value)) return 0;
  if (value <= double(std::numeric_limits<Int>::min())) return std::numeric_limits<Int>::min();
  if (value >= double(std::numeric_limits<Int>::max())) return std::numeric_limits<Int>::max();
  return Int(value);
}

// Fast path for plain numbers ("12", "-.5", "+3."); false when text is not one.
bool parse_plain_number(std::string_view text, double& value);

} // namespace ncjoule::detail
