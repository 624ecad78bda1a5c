#include "json_writer.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace ncjoule::report_detail {

JsonWriter::JsonWriter(std::ostream& out, int indent) : out_(out), indent_(indent) {
  buffer_.reserve(1 << 16);
}

JsonWriter::~JsonWriter() {
  out_.write(buffer_.data(), std::streamsize(buffer_.size()));
}

void JsonWriter::flush_if_full() {
  if (buffer_.size() < (1 << 16)) return;
  out_.write(buffer_.data(), std::streamsize(buffer_.size()));
  buffer_.clear();
}

void JsonWriter::newline() {
  if (indent_ <= 0 || one_line_levels_ > 0) return;
  put('\n');
  buffer_.append(levels_.size() * std::size_t(indent_), ' ');
}

void JsonWriter::before_value() {
  flush_if_full();
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (levels_.empty()) return;
  Level& level = levels_.back();
  if (!level.empty) put(',');
  level.empty = false;
  newline();
}

JsonWriter& JsonWriter::key(std::string_view name) {
  before_value();
  // Keys are names the code chose (plain ASCII): written as they are, not scanned for escapes.
  put('"');
  put(name);
  put('"');
  put(':');
  if (indent_ > 0 && one_line_levels_ == 0) put(' ');
  after_key_ = true;
  return *this;
}

void JsonWriter::begin_object() {
  before_value();
  put('{');
  levels_.push_back({false, true});
}

void JsonWriter::begin_object_on_one_line() {
  before_value();
  put('{');
  levels_.push_back({false, true, true});
  ++one_line_levels_;
}

void JsonWriter::begin_array() {
  before_value();
  put('[');
  levels_.push_back({true, true});
}

void JsonWriter::end_object() {
  const bool empty = levels_.back().empty;
  const bool one_line = levels_.back().one_line;
  levels_.pop_back();
  if (one_line)
    --one_line_levels_;
  else if (!empty)
    newline();
  put('}');
}

void JsonWriter::end_array() {
  const bool empty = levels_.back().empty;
  levels_.pop_back();
  if (!empty) newline();
  put(']');
}

void JsonWriter::value(double number) {
  if (!std::isfinite(number)) return null();
  before_value();
  char text[32];
  const auto r = std::to_chars(text, text + sizeof text, number);
  put(std::string_view(text, std::size_t(r.ptr - text)));
}

void JsonWriter::value(float number) {
  if (!std::isfinite(number)) return null();
  before_value();
  char text[32];
  const auto r = std::to_chars(text, text + sizeof text, number);
  put(std::string_view(text, std::size_t(r.ptr - text)));
}

void JsonWriter::value(std::int64_t number) {
  before_value();
  char text[32];
  const auto r = std::to_chars(text, text + sizeof text, number);
  put(std::string_view(text, std::size_t(r.ptr - text)));
}

void JsonWriter::value(std::string_view text) {
  before_value();
  write_string(text);
}

void JsonWriter::value(bool flag) {
  before_value();
  put(flag ? "true" : "false");
}

void JsonWriter::null() {
  before_value();
  put("null");
}

namespace {

// A byte that stands for itself inside a JSON string.
bool is_plain(char c) {
  const auto u = static_cast<unsigned char>(c);
  return u >= 0x20 && u < 0x7f && c != '"' && c != '\\';
}

// Length of the valid UTF-8 sequence at text[i], or 0 when the bytes there are not one.
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const unsigned char c = static_cast<unsigned char>(text[i]);
  std::size_t n = 0;
  if (c >= 0xc2 && c <= 0xdf)
    n = 2;
  else if (c >= 0xe0 && c <= 0xef)
    n = 3;
  else if (c >= 0xf0 && c <= 0xf4)
    n = 4;
  else
    return 0;
  if (i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(text[i + k]) & 0xc0) != 0x80) return 0;
  return n;
}

} // namespace

void JsonWriter::write_string(std::string_view text) {
  put('"');
  for (std::size_t i = 0; i < text.size(); ++i) {
    // Runs of printable ASCII, which is nearly all of it, go in one append.
    std::size_t plain = i;
    while (plain < text.size() && is_plain(text[plain]))
      ++plain;
    if (plain > i) {
      put(text.substr(i, plain - i));
      i = plain;
      if (i == text.size()) break;
    }
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x80) {
      // Programs are often not UTF-8 (Latin-1 comments): such bytes become U+FFFD, so that the
      // document stays valid JSON.
      const std::size_t n = utf8_length(text, i);
      if (n == 0) {
        put("\ufffd");
      } else {
        put(text.substr(i, n));
        i += n - 1;
      }
      continue;
    }
    switch (c) {
    case '"':
      put("\\\"");
      break;
    case '\\':
      put("\\\\");
      break;
    case '\n':
      put("\\n");
      break;
    case '\r':
      put("\\r");
      break;
    case '\t':
      put("\\t");
      break;
    default:
      if (c < 0x20 || c == 0x7f) {
        char esc[8];
        std::snprintf(esc, sizeof esc, "\\u%04x", c);
        put(esc);
      } else {
        put(char(c));
      }
    }
  }
  put('"');
}

} // namespace ncjoule::report_detail
