#include "json_writer.hpp"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "ncjoule/in_order.hpp"

namespace ncjoule::report_detail {

JsonWriter::JsonWriter(std::ostream& out, int indent)
    : out_(&out), buffer_(new char[kBufferSize]), indent_(indent) {}

JsonWriter::JsonWriter(std::string& text, const JsonWriter& parent, bool array_empty)
    : text_(&text), buffer_(new char[kBufferSize]), indent_(parent.indent_),
      levels_(parent.levels_), one_line_levels_(parent.one_line_levels_) {
  levels_.back().empty = array_empty;
}

JsonWriter::~JsonWriter() {
  flush();
}

void JsonWriter::flush() {
  if (used_ == 0) return;
  if (out_)
    out_->write(buffer_.get(), std::streamsize(used_));
  else
    text_->append(buffer_.get(), used_);
  used_ = 0;
}

void JsonWriter::put(std::string_view text) {
  if (kBufferSize - used_ < text.size()) {
    flush();
    if (text.size() > kBufferSize) { // a long string value: written as it is
      if (out_)
        out_->write(text.data(), std::streamsize(text.size()));
      else
        text_->append(text);
      return;
    }
  }
  std::memcpy(buffer_.get() + used_, text.data(), text.size());
  used_ += text.size();
}

void JsonWriter::newline() {
  if (indent_ <= 0 || one_line_levels_ > 0) return;
  put('\n');
  for (std::size_t n = levels_.size() * std::size_t(indent_); n > 0; --n)
    put(' ');
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

void JsonWriter::begin_array_of_lines() {
  before_value();
  put('[');
  levels_.push_back({true, true, false, true});
}

void JsonWriter::end_array() {
  const bool empty = levels_.back().empty;
  const bool lines = levels_.back().lines;
  levels_.pop_back();
  if (!empty && lines && one_line_levels_ == 0 && indent_ <= 0)
    put('\n');
  else if (!empty)
    newline();
  put(']');
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

void JsonWriter::elements(std::size_t count,
                          const std::function<void(JsonWriter&, std::size_t)>& element) {
  // Pieces of a few hundred kB of text; at most a few per core in memory at a time.
  constexpr std::size_t kPiece = 512;
  const std::size_t pieces = (count + kPiece - 1) / kPiece;
  const bool was_empty = levels_.back().empty;
  flush(); // the pieces' text follows what is written so far
  // The longest piece made so far: the next piece's text takes that much room at once rather
  // than growing into it (a copy of all it holds at every doubling).
  std::atomic<std::size_t> longest{0};
  make_in_order<std::string>(
      pieces,
      [&](std::size_t piece) {
        std::string text;
        const std::size_t expected = longest.load(std::memory_order_relaxed);
        text.reserve(expected + expected / 8);
        JsonWriter w(text, *this, was_empty && piece == 0);
        const std::size_t end = std::min(count, (piece + 1) * kPiece);
        for (std::size_t i = piece * kPiece; i < end; ++i)
          element(w, i);
        w.flush();
        std::size_t seen = longest.load(std::memory_order_relaxed);
        while (text.size() > seen && !longest.compare_exchange_weak(seen, text.size()))
          ;
        return text;
      },
      [&](const std::string& text) { put(text); });
  if (count > 0) levels_.back().empty = false;
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
