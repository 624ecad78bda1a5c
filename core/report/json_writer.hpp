// Internal: a JSON document written to a stream as it is made, value by value: no tree of the
// document is built, so a million-block estimate is written in the memory of one block. Numbers
// are written in the shortest form that reads back to the same double (a float field in the
// shortest form that reads back to the same float); non-finite numbers are written as null.
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "shortest_number.hpp"

namespace ncjoule::report_detail {

class JsonWriter {
public:
  // `indent` spaces per level (0 or less: one line).
  JsonWriter(std::ostream& out, int indent);
  ~JsonWriter(); // writes out what is buffered
  JsonWriter(const JsonWriter&) = delete;
  JsonWriter& operator=(const JsonWriter&) = delete;

  void begin_object();
  // An object written on one line, whatever it holds: one per element keeps a long array (the
  // blocks of a million-line program) readable line by line and a third of the size.
  void begin_object_on_one_line();
  void end_object();
  void begin_array();
  // An array whose elements each start on a line of their own, indented or not (the rows of
  // the compact document: a client can read them line by line).
  void begin_array_of_lines();
  void end_array();
  // The key of the next value, inside an object: a name of plain ASCII, written unescaped.
  // This and the numbers are defined below, inline: a large document writes millions of them.
  JsonWriter& key(std::string_view name);
  void value(double number);
  void value(float number);
  void value(std::int64_t number);
  void value(int number) { value(std::int64_t(number)); }
  void value(std::size_t number) { value(std::int64_t(number)); }
  void value(std::uint32_t number) { value(std::int64_t(number)); }
  void value(std::string_view text);
  void value(const char* text) { value(std::string_view(text)); }
  void value(const std::string& text) { value(std::string_view(text)); }
  void value(bool flag);
  void null();

  // Ends the document, with a newline when `newline`. Written through the buffer, in order: a
  // newline put on the stream itself went out before the text still buffered (the start of a
  // small document, or inside a block of a large one).
  void end_document(bool newline) {
    if (newline) put('\n');
  }

  template <class T> void field(std::string_view name, const T& v) {
    key(name);
    value(v);
  }

  // A key and a number as key() and value() write them inside a one-line object that holds a
  // value already: `key_text` is the key as written there, with the comma before it
  // (",\"time_s\":"). The same bytes without the bookkeeping of a value that may come anywhere:
  // for the blocks of a large document, two dozen fields each.
  template <class Number> void raw_field(std::string_view key_text, Number number);
  // Text as it is, inside a one-line object (the brace closing what a raw key opened).
  void raw_text(std::string_view text) { put(text); }

  // Writes `count` elements of the array open now, element(writer, i) writing the i-th, the
  // same bytes as writing them one after another here: pieces of elements are made on all cores
  // (TBB) into text of their own and written in order, a few pieces in memory at a time. For the
  // blocks of a large program, where formatting numbers is most of the time.
  void elements(std::size_t count, const std::function<void(JsonWriter&, std::size_t)>& element);

private:
  struct Level {
    bool array = false;
    bool empty = true;
    bool one_line = false;
    bool lines = false; // each element on a line of its own (begin_array_of_lines)
  };
  // A writer into `text`, continuing `parent`'s document inside its open array.
  JsonWriter(std::string& text, const JsonWriter& parent, bool array_empty);

  void before_value();
  void newline();
  void write_string(std::string_view text);
  void put(char c) {
    if (used_ == kBufferSize) flush();
    buffer_[used_++] = c;
  }
  void put(std::string_view text);
  // Room for `n` more characters in the buffer (n <= kBufferSize), flushing it if needed.
  char* room(std::size_t n) {
    if (kBufferSize - used_ < n) flush();
    return buffer_.get() + used_;
  }
  void flush();

  static constexpr std::size_t kBufferSize = std::size_t(1) << 16;
  std::ostream* out_ = nullptr; // where the text goes: a stream,
  std::string* text_ = nullptr; // or a string (a piece of elements())
  // Written out in large pieces: a stream write per character is slow.
  std::unique_ptr<char[]> buffer_;
  std::size_t used_ = 0;
  int indent_;
  std::vector<Level> levels_;
  int one_line_levels_ = 0; // open levels written on one line (newlines off inside them)
  bool after_key_ = false;
};

// Below this, a whole number's shortest form is its digits (to_chars writes 100000 as "1e+05",
// shorter than its digits).
inline constexpr double kWholeDigitsBelow = 100000;

// Writes a whole number of magnitude below kWholeDigitsBelow as to_chars does ("-0" for
// negative zero) at p; returns the end. Most numbers of an estimate's blocks are 0 (no removal,
// no coolant, no tool change on most lines), and many are whole.
inline char* put_whole(char* p, double number) {
  if (std::signbit(number)) *p++ = '-';
  return std::to_chars(p, p + 8, std::int64_t(std::fabs(number))).ptr;
}

inline void JsonWriter::before_value() {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (levels_.empty()) return;
  Level& level = levels_.back();
  if (!level.empty) put(',');
  level.empty = false;
  if (level.lines && one_line_levels_ == 0 && indent_ <= 0)
    put('\n');
  else if (indent_ > 0 && one_line_levels_ == 0)
    newline();
}

inline JsonWriter& JsonWriter::key(std::string_view name) {
  before_value();
  // Keys are names the code chose (plain ASCII): written as they are, not scanned for escapes.
  char* p = room(name.size() + 4);
  *p++ = '"';
  std::memcpy(p, name.data(), name.size());
  p += name.size();
  *p++ = '"';
  *p++ = ':';
  if (indent_ > 0 && one_line_levels_ == 0) *p++ = ' ';
  used_ = std::size_t(p - buffer_.get());
  after_key_ = true;
  return *this;
}

// A finite number as value() writes it, at p (room for kShortestNumberRoom); returns the end.
inline char* put_number(char* p, double number) {
  if (std::fabs(number) < kWholeDigitsBelow && number == std::trunc(number))
    return put_whole(p, number);
  return write_shortest(p, number);
}
inline char* put_number(char* p, float number) {
  if (std::fabs(number) < float(kWholeDigitsBelow) && number == std::trunc(number))
    return put_whole(p, double(number));
  return write_shortest(p, number);
}
inline char* put_number(char* p, std::int64_t number) {
  return std::to_chars(p, p + 32, number).ptr;
}

inline void JsonWriter::value(double number) {
  if (!std::isfinite(number)) return null();
  before_value();
  used_ = std::size_t(put_number(room(kShortestNumberRoom), number) - buffer_.get());
}

inline void JsonWriter::value(float number) {
  if (!std::isfinite(number)) return null();
  before_value();
  used_ = std::size_t(put_number(room(kShortestNumberRoom), number) - buffer_.get());
}

inline void JsonWriter::value(std::int64_t number) {
  before_value();
  used_ = std::size_t(put_number(room(32), number) - buffer_.get());
}

template <class Number> void JsonWriter::raw_field(std::string_view key_text, Number number) {
  char* p = room(key_text.size() + kShortestNumberRoom);
  std::memcpy(p, key_text.data(), key_text.size());
  p += key_text.size();
  if constexpr (std::is_floating_point_v<Number>) {
    if (!std::isfinite(number)) {
      std::memcpy(p, "null", 4);
      used_ = std::size_t(p + 4 - buffer_.get());
      return;
    }
    p = put_number(p, number);
  } else {
    p = put_number(p, std::int64_t(number));
  }
  used_ = std::size_t(p - buffer_.get());
}

} // namespace ncjoule::report_detail
