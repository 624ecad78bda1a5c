// Small text helpers every stage uses: white space trimmed, ASCII case, a number read whole.
// Programs are not always UTF-8 (Latin-1 comments are common), so case changes touch ASCII
// letters only and never depend on the locale.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace ncjoule {

// Without the spaces, tabs, carriage returns and line feeds at either end.
std::string_view trim(std::string_view text);

// ASCII letters in lower / upper case; every other byte unchanged.
std::string to_lower(std::string_view text);
std::string to_upper(std::string_view text);

// The whole text as a finite number ("6", "-0.5", "+1e3", ".5", "6."), white space around it
// allowed; std::nullopt for anything else (an empty text, "6mm", "nan", "1e999").
std::optional<double> parse_number(std::string_view text);

} // namespace ncjoule
