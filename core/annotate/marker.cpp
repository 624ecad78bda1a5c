#include "marker.hpp"

#include <array>
#include <cstdint>

namespace ncjoule::annotation {
namespace {

constexpr std::string_view kMarker = "NCJ";
constexpr std::string_view kSumKey = " CK=";
constexpr std::size_t kSumLength = 6;
// Crockford's base 32: no I, L, O, U, so that a sum never reads as a word or as 0/1.
constexpr std::string_view kSumAlphabet = "0123456789ABCDEFGHJKMNPQRSTVWXYZ";

// Byte tables: every annotated line's bytes pass through these (to write, check and strip it),
// and a table look-up is one load where the comparisons are a branch each.
using ByteTable = std::array<unsigned char, 256>;

constexpr ByteTable make_upper_table() {
  ByteTable t{};
  for (int c = 0; c < 256; ++c)
    t[c] = static_cast<unsigned char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
  return t;
}
constexpr ByteTable kUpper = make_upper_table();

constexpr ByteTable make_safe_table() {
  ByteTable t{};
  for (int c = 0; c < 256; ++c)
    t[c] = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == ' ' ||
           c == '.' || c == ',' || c == '=' || c == '_' || c == '-';
  return t;
}
constexpr ByteTable kSafe = make_safe_table();

char upper(char c) {
  return static_cast<char>(kUpper[static_cast<unsigned char>(c)]);
}

bool equal_no_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (upper(a[i]) != upper(b[i])) return false;
  return true;
}

std::uint32_t hash(std::string_view content, MarkKind kind) {
  // FNV-1a over the upper-cased bytes, a different basis per kind, then murmur3's finaliser so
  // that the low 30 bits used below depend on every input bit.
  std::uint32_t h = kind == MarkKind::Header ? 0x9e3779b9u : 2166136261u;
  for (char c : content) {
    h ^= static_cast<unsigned char>(upper(c));
    h *= 16777619u;
  }
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return h;
}

} // namespace

CommentStyle comment_style(const Dialect& dialect) {
  if (dialect.comment_open == ";" && dialect.comment_close.empty())
    return {";", "", dialect.upper_case_comments};
  return {"(", ")", dialect.upper_case_comments};
}

bool is_safe_char(char c) {
  return kSafe[static_cast<unsigned char>(c)] != 0;
}

std::string checksum(std::string_view content, MarkKind kind) {
  std::uint32_t h = hash(content, kind);
  std::string sum(kSumLength, '0');
  for (std::size_t i = 0; i < kSumLength; ++i) {
    sum[kSumLength - 1 - i] = kSumAlphabet[h & 31u];
    h >>= 5;
  }
  return sum;
}

std::string marked_comment(std::string_view content, MarkKind kind, const CommentStyle& style) {
  // Only safe characters, whatever a field holds: one that is not would end the comment for
  // match_marked_comment, and strip() would leave it in the program. Written in place, in one
  // allocation: every annotated line has one.
  std::string out;
  out.reserve(style.open.size() + content.size() + kSumKey.size() + kSumLength +
              style.close.size());
  out += style.open;
  const std::size_t begin = out.size();
  for (char c : content) {
    if (!is_safe_char(c)) c = '_';
    out += style.upper_case ? upper(c) : c;
  }
  const std::string sum = checksum(std::string_view(out).substr(begin), kind);
  out += kSumKey;
  out += sum;
  out += style.close;
  return out;
}

std::size_t match_marked_comment(std::string_view text, std::size_t pos, MarkKind kind) {
  if (pos >= text.size() || (text[pos] != '(' && text[pos] != ';')) return 0;
  const bool paren = text[pos] == '(';
  const std::size_t begin = pos + 1;
  if (!equal_no_case(text.substr(begin, kMarker.size()), kMarker)) return 0;
  // The comment's text is a run of safe characters; a parenthesis comment ends at ')', a ';'
  // comment right after its checksum.
  std::size_t end = begin + kMarker.size();
  if (end >= text.size() || text[end] != ' ') return 0;
  while (end < text.size() && is_safe_char(text[end]))
    ++end;
  const std::size_t sum_size = kSumKey.size() + kSumLength;
  // A parenthesis comment's sum ends where its safe run does: one place to look. A ';' comment's
  // may be followed by more text: look at every " CK=" in the run.
  std::size_t k = begin + kMarker.size();
  if (paren && end >= k + sum_size) k = end - sum_size;
  for (; k + sum_size <= end; ++k) {
    if (text[k] != ' ' || !equal_no_case(text.substr(k, kSumKey.size()), kSumKey)) continue;
    const std::size_t sum_end = k + kSumKey.size() + kSumLength;
    if (paren && (sum_end != end || end >= text.size() || text[end] != ')')) continue;
    if (!paren && sum_end < text.size() && is_safe_char(text[sum_end]) && text[sum_end] != ' ')
      continue;
    const std::string_view content = text.substr(begin, k - begin);
    if (!equal_no_case(text.substr(k + kSumKey.size(), kSumLength), checksum(content, kind)))
      continue;
    return sum_end + (paren ? 1 : 0) - pos;
  }
  return 0;
}

} // namespace ncjoule::annotation
