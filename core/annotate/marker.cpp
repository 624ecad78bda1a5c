#include "marker.hpp"

#include <array>
#include <cstdint>

namespace ncjoule::annotation {
namespace {

constexpr std::string_view kMarker = "NCJ";
constexpr std::string_view kSumKey = " CK=";
constexpr std::string_view kKeyPrefix = "NCJ FILE KEY=";
constexpr std::size_t kSumLength = 6;
constexpr std::size_t kKeyLength = 6;
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

bool is_alphabet_char(char c) {
  return kSumAlphabet.find(upper(c)) != std::string_view::npos;
}

// murmur3's finaliser: the low 30 bits used below depend on every input bit.
std::uint32_t finalise(std::uint32_t h) {
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return h;
}

// FNV-1a, then the finaliser.
class Hash {
public:
  explicit Hash(std::uint32_t basis) : h_(basis) {}
  void add(unsigned char c) {
    h_ ^= c;
    h_ *= 16777619u;
  }
  void add_folded(std::string_view text) {
    for (char c : text)
      add(static_cast<unsigned char>(upper(c)));
  }
  std::uint32_t finish() const { return finalise(h_); }

private:
  std::uint32_t h_;
};

// One basis per kind: a comment of one kind never verifies as another.
std::uint32_t basis(MarkKind kind) {
  switch (kind) {
  case MarkKind::Key:
    return 0x7f4a7c15u;
  case MarkKind::Header:
    return 0x9e3779b9u;
  case MarkKind::Inline:
    return 2166136261u;
  case MarkKind::Line:
    return 0x85ebca77u;
  }
  return 0;
}

std::string base32(std::uint32_t h, std::size_t length) {
  std::string out(length, '0');
  for (std::size_t i = 0; i < length; ++i) {
    out[length - 1 - i] = kSumAlphabet[h & 31u];
    h >>= 5;
  }
  return out;
}

// The marked comment opening at text[pos]: for each place its checksum could be, `verifies`
// is asked with the comment's content ("NCJ ..."), its sum and where it ends (one past its last
// byte); the length of the first that verifies is returned, 0 if none does.
template <class Verify> std::size_t match(std::string_view text, std::size_t pos, Verify verifies) {
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
    const std::size_t comment_end = sum_end + (paren ? 1 : 0);
    if (verifies(text.substr(begin, k - begin), text.substr(k + kSumKey.size(), kSumLength),
                 comment_end))
      return comment_end - pos;
  }
  return 0;
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

void FileKey::add(std::string_view text) {
  for (char c : text) {
    h_ ^= static_cast<unsigned char>(c);
    h_ *= 16777619u;
  }
}

std::string FileKey::value() const {
  return base32(finalise(h_), kKeyLength);
}

std::string key_seed(std::string_view key) {
  std::string seed = "K";
  seed += key;
  return seed;
}

std::string line_seed(std::string_view line) {
  std::string seed = "L";
  seed.reserve(line.size() + 1);
  for (char c : line)
    if (c != ' ' && c != '\t') seed += upper(c);
  return seed;
}

std::string checksum(std::string_view content, MarkKind kind, std::string_view seed) {
  Hash h(basis(kind));
  h.add_folded(seed);
  h.add(0x1f); // the seed ends: "K1" + "2 ..." is not "K12" + " ..."
  h.add_folded(content);
  return base32(h.finish(), kSumLength);
}

std::string marked_comment(std::string_view content, MarkKind kind, const CommentStyle& style,
                           std::string_view seed) {
  // Only safe characters, whatever a field holds: one that is not would end the comment for
  // match(), and strip() would leave it in the program. Written in place, in one allocation:
  // every annotated line has one.
  std::string out;
  out.reserve(style.open.size() + content.size() + kSumKey.size() + kSumLength +
              style.close.size());
  out += style.open;
  const std::size_t begin = out.size();
  for (char c : content) {
    if (!is_safe_char(c)) c = '_';
    out += style.upper_case ? upper(c) : c;
  }
  const std::string sum = checksum(std::string_view(out).substr(begin), kind, seed);
  out += kSumKey;
  out += sum;
  out += style.close;
  return out;
}

std::string plain_comment(std::string_view content, const CommentStyle& style) {
  std::string out;
  out.reserve(style.open.size() + content.size() + style.close.size());
  out += style.open;
  for (char c : content) {
    if (!is_safe_char(c)) c = '_';
    out += style.upper_case ? upper(c) : c;
  }
  out += style.close;
  return out;
}

std::size_t match_marked_comment(std::string_view text, std::size_t pos, MarkKind kind,
                                 std::string_view seed) {
  return match(text, pos, [&](std::string_view content, std::string_view sum, std::size_t) {
    return equal_no_case(sum, checksum(content, kind, seed));
  });
}

std::size_t match_line_bound_comment(std::string_view line, std::size_t space) {
  if (space >= line.size() || line[space] != ' ') return 0;
  const std::size_t length =
      match(line, space + 1, [&](std::string_view content, std::string_view sum, std::size_t end) {
        std::string rest(line.substr(0, space));
        rest += line.substr(end);
        return equal_no_case(sum, checksum(content, MarkKind::Inline, line_seed(rest)));
      });
  return length;
}

std::string key_content(std::string_view key) {
  std::string content(kKeyPrefix);
  content += key;
  return content;
}

std::optional<std::string> key_of_line(std::string_view line) {
  std::string key;
  const std::size_t length =
      match(line, 0, [&](std::string_view content, std::string_view sum, std::size_t) {
        if (content.size() != kKeyPrefix.size() + kKeyLength ||
            !equal_no_case(content.substr(0, kKeyPrefix.size()), kKeyPrefix))
          return false;
        const std::string_view value = content.substr(kKeyPrefix.size());
        for (char c : value)
          if (!is_alphabet_char(c)) return false;
        if (!equal_no_case(sum, checksum(content, MarkKind::Key, ""))) return false;
        key.clear();
        for (char c : value)
          key += upper(c);
        return true;
      });
  if (length == 0 || length != line.size()) return std::nullopt;
  return key;
}

} // namespace ncjoule::annotation
