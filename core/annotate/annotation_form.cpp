#include "annotation_form.hpp"

#include <array>

namespace ncjoule::annotation {
namespace {

bool is_blank(char c) {
  return c == ' ' || c == '\t';
}

char upper(char c) {
  return c >= 'a' && c <= 'z' ? char(c - 'a' + 'A') : c;
}

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

std::size_t skip_blanks(std::string_view text, std::size_t i) {
  while (i < text.size() && is_blank(text[i]))
    ++i;
  return i;
}

// text[i..] begins with `word`, case aside.
bool starts_with(std::string_view text, std::size_t i, std::string_view word) {
  if (text.size() - std::min(i, text.size()) < word.size()) return false;
  for (std::size_t k = 0; k < word.size(); ++k)
    if (upper(text[i + k]) != word[k]) return false;
  return true;
}

enum class Value { Duration, Si, Number, Name, Seal, Check };

struct Key {
  std::string_view name;
  Value value;
};

// The fields of a block's comment, in the one order annotate() writes them.
constexpr std::array<Key, 11> kKeys{{{"T", Value::Duration},
                                     {"E", Value::Si},
                                     {"P", Value::Si},
                                     {"MRR", Value::Number},
                                     {"CUM", Value::Duration},
                                     {"LOAD_PCT", Value::Number},
                                     {"OP", Value::Name},
                                     {"OPT", Value::Duration},
                                     {"OPE", Value::Si},
                                     {"SEAL", Value::Seal},
                                     {"CK", Value::Check}}};

// The labels of the header's lines (SEAL and KEEP hold what strip needs; FILE is the key line of
// files written by earlier versions).
constexpr std::array<std::string_view, 14> kLabels{"SEAL",  "KEEP",    "TOTAL",  "TIME", "STOCK",
                                                   "SETUP", "GUESSED", "ENERGY", "OP",   "MACHINE",
                                                   "CONST", "KEYS",    "WARN",   "FILE"};

// The key of kKeys[first..] that begins at text[i] with its '=', or kKeys.size().
std::size_t key_at(std::string_view text, std::size_t i, std::size_t first) {
  for (std::size_t k = first; k < kKeys.size(); ++k) {
    const std::string_view name = kKeys[k].name;
    if (starts_with(text, i, name) && i + name.size() < text.size() && text[i + name.size()] == '=')
      return k;
  }
  return kKeys.size();
}

// -?DIGITS[.DIGITS]: its length, 0 if none.
std::size_t number_at(std::string_view text, std::size_t i, bool* decimal = nullptr) {
  std::size_t k = i;
  if (k < text.size() && text[k] == '-') ++k;
  const std::size_t digits = k;
  while (k < text.size() && is_digit(text[k]))
    ++k;
  if (k == digits) return 0;
  if (decimal) *decimal = false;
  if (k + 1 < text.size() && text[k] == '.' && is_digit(text[k + 1])) {
    ++k;
    while (k < text.size() && is_digit(text[k]))
      ++k;
    if (decimal) *decimal = true;
  }
  return k - i;
}

// Two digits at text[i].
bool two_digits(std::string_view text, std::size_t i) {
  return i + 1 < text.size() && is_digit(text[i]) && is_digit(text[i + 1]);
}

// A duration as format_duration() writes it: 1.23s, 1m05s, 1h02m03s, 1234567890h.
std::size_t duration_at(std::string_view text, std::size_t i) {
  bool decimal = false;
  const std::size_t n = number_at(text, i, &decimal);
  if (n == 0 || i + n >= text.size()) return 0;
  const std::size_t u = i + n;
  const char c = upper(text[u]);
  if (c == 'S') return n + 1;
  if (decimal) return c == 'H' ? n + 1 : 0;
  if (c == 'M' && two_digits(text, u + 1) && u + 3 < text.size() && upper(text[u + 3]) == 'S')
    return n + 4;
  if (c == 'H') {
    if (two_digits(text, u + 1) && u + 6 < text.size() && upper(text[u + 3]) == 'M' &&
        two_digits(text, u + 4) && upper(text[u + 6]) == 'S')
      return n + 7;
    return n + 1;
  }
  return 0;
}

// A number with an SI prefix and unit as format_si() writes it: 450J, 1.23kJ, 4.5MJ, 1.2kW.
std::size_t si_at(std::string_view text, std::size_t i) {
  const std::size_t n = number_at(text, i);
  if (n == 0) return 0;
  std::size_t k = i + n;
  if (k < text.size()) {
    const char c = upper(text[k]);
    if (c == 'K' || c == 'M' || c == 'G' || c == 'T') ++k;
  }
  if (k < text.size() && (upper(text[k]) == 'J' || upper(text[k]) == 'W')) return k + 1 - i;
  return 0;
}

bool is_name_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || is_digit(c) || c == '.' || c == ',' ||
         c == '-' || c == '_';
}

// An operation's name (safe_token()): up to the next blank, the comment's end, or a later key.
std::size_t name_at(std::string_view text, std::size_t i, std::size_t after_key) {
  std::size_t k = i;
  while (k < text.size() && is_name_char(text[k])) {
    if (k > i && key_at(text, k, after_key) < kKeys.size()) break;
    ++k;
  }
  return k - i;
}

std::size_t seal_at(std::string_view text, std::size_t i) {
  std::size_t k = i;
  while (k < text.size() &&
         (is_digit(text[k]) || (upper(text[k]) >= 'A' && upper(text[k]) <= 'Z') || text[k] == '-' ||
          text[k] == '.'))
    ++k;
  return k - i;
}

std::size_t check_at(std::string_view text, std::size_t i) {
  constexpr std::string_view kAlphabet = "0123456789ABCDEFGHJKMNPQRSTVWXYZ";
  for (std::size_t k = 0; k < 6; ++k)
    if (i + k >= text.size() || kAlphabet.find(upper(text[i + k])) == std::string_view::npos)
      return 0;
  return 6;
}

std::size_t value_at(std::string_view text, std::size_t i, std::size_t key) {
  switch (kKeys[key].value) {
  case Value::Duration:
    return duration_at(text, i);
  case Value::Si:
    return si_at(text, i);
  case Value::Number:
    return number_at(text, i);
  case Value::Name:
    return name_at(text, i, key + 1);
  case Value::Seal:
    return seal_at(text, i);
  case Value::Check:
    return check_at(text, i);
  }
  return 0;
}

// The block comment whose OPEN is at line[open]: one past its last byte, or 0 when what is
// there is not of the form. `found` gets its normal text and SEAL value.
std::size_t parse_block(std::string_view line, std::size_t open, FoundComment& found) {
  const bool paren = line[open] == '(';
  std::size_t i = open + 1;
  if (!starts_with(line, i, "NCJ")) return 0;
  i = skip_blanks(line, i + 3);
  std::string normal = "NCJ";
  std::size_t next_key = 0, fields = 0, last_end = 0;
  for (;;) {
    const std::size_t key = key_at(line, i, next_key);
    if (key == kKeys.size()) break;
    const std::size_t value = i + kKeys[key].name.size() + 1;
    const std::size_t length = value_at(line, value, key);
    if (length == 0) return 0;
    if (kKeys[key].value == Value::Seal)
      found.seal = std::string(line.substr(value, length));
    else
      for (char c : line.substr(i, value + length - i))
        normal += upper(c);
    ++fields;
    next_key = key + 1;
    last_end = value + length;
    // Blanks, or (blanks removed) the next key right away.
    i = skip_blanks(line, last_end);
  }
  if (fields == 0) return 0;
  const std::size_t after = skip_blanks(line, last_end);
  if (paren) {
    if (after >= line.size() || line[after] != ')') return 0;
    found.normal = std::move(normal);
    return after + 1;
  }
  // A ';' comment runs to the end of the line, or to a user's own ';' comment after it.
  if (after < line.size() && line[after] != ';') return 0;
  found.normal = std::move(normal);
  return last_end;
}

} // namespace

std::vector<FoundComment> block_comments(std::string_view line) {
  std::vector<FoundComment> found;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] != '(' && line[i] != ';') continue;
    if (i + 3 >= line.size() || upper(line[i + 1]) != 'N') continue; // most comments end here
    FoundComment c;
    const std::size_t end = parse_block(line, i, c);
    if (end == 0) continue;
    c.begin = i > 0 && is_blank(line[i - 1]) ? i - 1 : i;
    c.end = end;
    c.whole_line = skip_blanks(line, 0) == i && skip_blanks(line, end) == line.size();
    if (c.whole_line) c.begin = 0, c.end = line.size();
    found.push_back(std::move(c));
    i = end - 1;
  }
  return found;
}

bool is_header_line(std::string_view line) {
  if (line.empty() || (line[0] != '(' && line[0] != ';')) return false;
  const bool paren = line[0] == '(';
  std::size_t i = 1;
  if (!starts_with(line, i, "NCJ")) return false;
  i = skip_blanks(line, i + 3);
  bool labelled = false;
  for (std::string_view label : kLabels) {
    if (!starts_with(line, i, label)) continue;
    const std::size_t after = i + label.size();
    // "(NCJ OP N=1 ...)" is a header line; "(NCJ OP=ROUGH ...)" a block's comment.
    if (after < line.size() && line[after] == '=') continue;
    labelled = true;
    break;
  }
  if (!labelled) return false;
  if (!paren) return line.find(';', 1) == std::string_view::npos;
  const std::size_t close = line.find(')');
  return close == line.size() - 1 && line.find('(', 1) == std::string_view::npos;
}

std::string normal_text(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text)
    if (!is_blank(c)) out += upper(c);
  return out;
}

} // namespace ncjoule::annotation
