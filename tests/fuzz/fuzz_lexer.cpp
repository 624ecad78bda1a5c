// libFuzzer target: the lexer alone, line by line, in every dialect, and the evaluation of every
// word's value text (with an empty parameter table: reads of unset names are errors, not crashes).
#include <cstddef>
#include <cstdint>
#include <string>

#include "block.hpp"
#include "expression.hpp"
#include "parameters.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const ncjoule::SourceFile source =
      ncjoule::make_source("fuzz.ngc", std::string(reinterpret_cast<const char*>(data), size));
  ncjoule::detail::Block block;
  ncjoule::detail::Parameters params;
  for (const std::string& name : ncjoule::dialect_names()) {
    const ncjoule::Dialect dialect = *ncjoule::find_dialect(name);
    for (std::size_t i = 0; i < source.lines.size(); ++i) {
      ncjoule::detail::lex_line(source.line_text(i), dialect, block);
      for (const ncjoule::detail::Word& word : block.words) {
        double value;
        std::string error;
        std::size_t offset = 0;
        (void)ncjoule::detail::evaluate(word.value, params, value, error, offset);
      }
    }
  }
  return 0;
}
