#include "seal.hpp"

#include "annotation_form.hpp"

namespace ncjoule::annotation {
namespace {

constexpr std::string_view kAlphabet = "0123456789ABCDEFGHJKMNPQRSTVWXYZ"; // Crockford
constexpr std::size_t kSumLength = 8;
constexpr std::size_t kKeepHashLength = 4;

void add(std::uint64_t& h, std::string_view text) {
  for (char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ull;
  }
  h ^= 0x1f; // the end of one item: "AB" + "C" is not "A" + "BC"
  h *= 0x100000001b3ull;
}

std::uint64_t finalise(std::uint64_t h) {
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ull;
  h ^= h >> 33;
  return h;
}

std::string base32(std::uint64_t h, std::size_t length) {
  std::string out(length, '0');
  for (std::size_t i = 0; i < length; ++i) {
    out[length - 1 - i] = kAlphabet[h & 31u];
    h >>= 5;
  }
  return out;
}

bool is_base32(std::string_view text) {
  for (char c : text)
    if (kAlphabet.find(c) == std::string_view::npos) return false;
  return true;
}

// Reads "KEY=" and a run of digits at text[i]; npos when they are not there.
std::size_t read_count(std::string_view text, std::size_t& i, std::string_view key) {
  if (text.substr(i, key.size()) != key) return std::string_view::npos;
  i += key.size();
  const std::size_t begin = i;
  std::size_t value = 0;
  while (i < text.size() && text[i] >= '0' && text[i] <= '9' && i - begin < 12)
    value = value * 10 + std::size_t(text[i++] - '0');
  return i == begin ? std::string_view::npos : value;
}

// "ORDINAL.HASH" entries one after another (with separators `separator`, if any, between them).
bool read_kept(std::string_view text, char separator, std::vector<KeptComment>& keep) {
  std::size_t i = 0;
  while (i < text.size()) {
    if (separator && i > 0) {
      if (text[i] != separator) return false;
      ++i;
    }
    KeptComment k;
    const std::size_t begin = i;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9' && i - begin < 12)
      k.ordinal = k.ordinal * 10 + std::size_t(text[i++] - '0');
    if (i == begin || i >= text.size() || text[i] != '.') return false;
    ++i;
    k.hash = std::string(text.substr(i, kKeepHashLength));
    if (k.hash.size() != kKeepHashLength || !is_base32(k.hash)) return false;
    i += kKeepHashLength;
    keep.push_back(std::move(k));
  }
  return true;
}

std::string kept_text(const KeptComment& k) {
  return std::to_string(k.ordinal) + "." + k.hash;
}

// The inside of a whole-line comment ("(...)" or ";..."), or nothing.
std::optional<std::string_view> inside(std::string_view line) {
  if (line.size() >= 2 && line.front() == '(' && line.back() == ')')
    return line.substr(1, line.size() - 2);
  if (!line.empty() && line.front() == ';') return line.substr(1);
  return std::nullopt;
}

std::string comment(std::string_view content, const CommentStyle& style) {
  std::string out = style.open;
  for (char c : content)
    out += style.upper_case && c >= 'a' && c <= 'z' ? char(c - 'a' + 'A') : c;
  out += style.close;
  return out;
}

// The seal line's own checksum, of its normal text: blanks a DNC sender took out, or a change of
// case, leave it valid.
std::string seal_check(std::string_view normal) {
  return checksum(normal, MarkKind::Key, "SEAL");
}

} // namespace

void SealSum::add_header(std::string_view normal) {
  add(header_, normal);
}

void SealSum::add_block(std::string_view normal) {
  add(blocks_, normal);
}

std::string SealSum::value(std::size_t lines, std::size_t blocks) const {
  std::uint64_t h = header_ ^ (blocks_ * 0x9e3779b97f4a7c15ull);
  add(h, std::to_string(lines) + "/" + std::to_string(blocks));
  return base32(finalise(h), kSumLength);
}

std::string keep_hash(std::string_view normal) {
  std::uint64_t h = 0x6c62272e07bb0142ull;
  add(h, normal);
  return base32(finalise(h), kKeepHashLength);
}

std::string seal_line(const Seal& seal, const CommentStyle& style) {
  const std::string content = "NCJ SEAL LINES=" + std::to_string(seal.lines) +
                              " BLOCKS=" + std::to_string(seal.blocks) + " SUM=" + seal.sum;
  return comment(content + " CK=" + seal_check(normal_text(content)), style);
}

std::optional<Seal> seal_of_line(std::string_view line) {
  const auto text = inside(line);
  if (!text) return std::nullopt;
  const std::string normal = normal_text(*text);
  constexpr std::string_view kStart = "NCJSEAL";
  if (normal.compare(0, kStart.size(), kStart) != 0) return std::nullopt;
  Seal seal;
  std::size_t i = kStart.size();
  seal.lines = read_count(normal, i, "LINES=");
  if (seal.lines == std::string_view::npos) return std::nullopt;
  seal.blocks = read_count(normal, i, "BLOCKS=");
  if (seal.blocks == std::string_view::npos) return std::nullopt;
  if (normal.compare(i, 4, "SUM=") != 0) return std::nullopt;
  seal.sum = normal.substr(i + 4, kSumLength);
  i += 4 + kSumLength;
  if (seal.sum.size() != kSumLength || !is_base32(seal.sum)) return std::nullopt;
  if (normal.compare(i, 3, "CK=") != 0 || normal.size() != i + 3 + 6) return std::nullopt;
  if (normal.substr(i + 3) != seal_check(normal.substr(0, i))) return std::nullopt;
  return seal;
}

std::vector<std::string> keep_lines(const std::vector<KeptComment>& keep, const CommentStyle& style,
                                    std::size_t max_length) {
  std::vector<std::string> lines;
  const std::string start = "NCJ KEEP";
  std::string content = start;
  auto flush = [&] {
    if (content.size() > start.size()) lines.push_back(comment(content, style));
    content = start;
  };
  for (const KeptComment& k : keep) {
    const std::string entry = " " + kept_text(k);
    if (style.open.size() + content.size() + entry.size() + style.close.size() > max_length)
      flush();
    content += entry;
  }
  flush();
  return lines;
}

bool read_keep_line(std::string_view line, std::vector<KeptComment>& keep) {
  const auto text = inside(line);
  if (!text) return false;
  const std::string normal = normal_text(*text);
  constexpr std::string_view kStart = "NCJKEEP";
  if (normal.compare(0, kStart.size(), kStart) != 0) return false;
  std::vector<KeptComment> read;
  if (!read_kept(std::string_view(normal).substr(kStart.size()), 0, read)) return false;
  keep.insert(keep.end(), read.begin(), read.end());
  return true;
}

std::string seal_field(const Seal& seal) {
  std::string out = std::to_string(seal.blocks) + "-" + seal.sum;
  for (const KeptComment& k : seal.keep)
    out += "-" + kept_text(k);
  return out;
}

std::optional<Seal> seal_of_field(std::string_view value) {
  Seal seal;
  std::string upper;
  for (char c : value)
    upper += c >= 'a' && c <= 'z' ? char(c - 'a' + 'A') : c;
  std::size_t i = 0;
  while (i < upper.size() && upper[i] >= '0' && upper[i] <= '9' && i < 12)
    seal.blocks = seal.blocks * 10 + std::size_t(upper[i++] - '0');
  if (i == 0 || i >= upper.size() || upper[i] != '-') return std::nullopt;
  seal.sum = upper.substr(i + 1, kSumLength);
  if (seal.sum.size() != kSumLength || !is_base32(seal.sum)) return std::nullopt;
  i += 1 + kSumLength;
  if (i < upper.size()) {
    if (upper[i] != '-') return std::nullopt;
    if (!read_kept(std::string_view(upper).substr(i + 1), '-', seal.keep)) return std::nullopt;
  }
  return seal;
}

} // namespace ncjoule::annotation
