// Internal: a JSON document written to a stream as it is made, value by value: no tree of the
// document is built, so a million-block estimate is written in the memory of one block. Numbers
// are written in the shortest form that reads back to the same double (a float field in the
// shortest form that reads back to the same float); non-finite numbers are written as null.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

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
  void end_array();
  // The key of the next value, inside an object: a name of plain ASCII, written unescaped.
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

  template <class T> void field(std::string_view name, const T& v) {
    key(name);
    value(v);
  }

private:
  void before_value();
  void newline();
  void write_string(std::string_view text);
  void put(char c) { buffer_.push_back(c); }
  void put(std::string_view text) { buffer_.append(text); }
  void flush_if_full();

  std::ostream& out_;
  std::string buffer_; // written to out_ in large pieces: a stream write per character is slow
  int indent_;
  struct Level {
    bool array = false;
    bool empty = true;
    bool one_line = false;
  };
  std::vector<Level> levels_;
  int one_line_levels_ = 0; // open levels written on one line (newlines off inside them)
  bool after_key_ = false;
};

} // namespace ncjoule::report_detail
