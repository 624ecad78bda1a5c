#include "json_writer.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace ncjoule::report_detail {

JsonWriter::JsonWriter(std::ostream& out, int indent) : out_(out), indent_(indent) {}

void JsonWriter::newline() {
  if (indent_ <= 0) return;
  out_.put('\n');
  for (std::size_t i = 0; i < levels_.size() * std::size_t(indent_); ++i)
    out_.put(' ');
}

void JsonWriter::before_value() {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (levels_.empty()) return;
  Level& level = levels_.back();
  if (!level.empty) out_.put(',');
  level.empty = false;
  newline();
}

JsonWriter& JsonWriter::key(std::string_view name) {
  before_value();
  write_string(name);
  out_.put(':');
  if (indent_ > 0) out_.put(' ');
  after_key_ = true;
  return *this;
}

void JsonWriter::begin_object() {
  before_value();
  out_.put('{');
  levels_.push_back({false, true});
}

void JsonWriter::begin_array() {
  before_value();
  out_.put('[');
  levels_.push_back({true, true});
}

void JsonWriter::end_object() {
  const bool empty = levels_.back().empty;
  levels_.pop_back();
  if (!empty) newline();
  out_.put('}');
}

void JsonWriter::end_array() {
  const bool empty = levels_.back().empty;
  levels_.pop_back();
  if (!empty) newline();
  out_.put(']');
}

void JsonWriter::value(double number) {
  if (!std::isfinite(number)) return null();
  before_value();
  char text[32];
  const auto r = std::to_chars(text, text + sizeof text, number);
  out_.write(text, r.ptr - text);
}

void JsonWriter::value(float number) {
  if (!std::isfinite(number)) return null();
  before_value();
  char text[32];
  const auto r = std::to_chars(text, text + sizeof text, number);
  out_.write(text, r.ptr - text);
}

void JsonWriter::value(std::int64_t number) {
  before_value();
  char text[32];
  const auto r = std::to_chars(text, text + sizeof text, number);
  out_.write(text, r.ptr - text);
}

void JsonWriter::value(std::string_view text) {
  before_value();
  write_string(text);
}

void JsonWriter::value(bool flag) {
  before_value();
  out_ << (flag ? "true" : "false");
}

void JsonWriter::null() {
  before_value();
  out_ << "null";
}

namespace {

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
  out_.put('"');
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x80) {
      // Programs are often not UTF-8 (Latin-1 comments): such bytes become U+FFFD, so that the
      // document stays valid JSON.
      const std::size_t n = utf8_length(text, i);
      if (n == 0) {
        out_ << "\ufffd";
      } else {
        out_.write(text.data() + i, std::streamsize(n));
        i += n - 1;
      }
      continue;
    }
    switch (c) {
    case '"':
      out_ << "\\\"";
      break;
    case '\\':
      out_ << "\\\\";
      break;
    case '\n':
      out_ << "\\n";
      break;
    case '\r':
      out_ << "\\r";
      break;
    case '\t':
      out_ << "\\t";
      break;
    default:
      if (c < 0x20 || c == 0x7f) {
        char esc[8];
        std::snprintf(esc, sizeof esc, "\\u%04x", c);
        out_ << esc;
      } else {
        out_.put(char(c));
      }
    }
  }
  out_.put('"');
}

} // namespace ncjoule::report_detail
