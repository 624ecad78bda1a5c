// The shared text helpers: trimming, ASCII case, whole-text numbers, reading a user's file.
#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "ncjoule/text.hpp"
#include "ncjoule/text_file.hpp"

using namespace ncjoule;

TEST_CASE("trim takes blanks and line ends off both ends only") {
  CHECK(trim("  a b\t\r\n") == "a b");
  CHECK(trim(" \t\r\n").empty());
  CHECK(trim("x") == "x");
}

TEST_CASE("case changes touch ASCII letters only") {
  CHECK(to_upper("g1 x\xe9") == "G1 X\xe9"); // a Latin-1 byte stays as it is
  CHECK(to_lower("Box:1,2") == "box:1,2");
}

TEST_CASE("a number is the whole text, finite") {
  CHECK(parse_number(" 6 ") == 6.0);
  CHECK(parse_number("+1e3") == 1000.0);
  CHECK(parse_number(".5") == 0.5);
  CHECK(parse_number("6.") == 6.0);
  CHECK(parse_number("-0.25") == -0.25);
  for (const char* bad : {"", " ", "6mm", "nan", "inf", "1e999", "--1", "+"}) {
    CAPTURE(bad);
    CHECK_FALSE(parse_number(bad));
  }
}

TEST_CASE("a user's file is read whole, or refused with a diagnostic on it") {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("ncjoule-text-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "part.nc").string();
  std::ofstream(file, std::ios::binary) << "G0 X1\r\nM2"; // the CR is kept
  std::vector<Diagnostic> problems;
  const auto text = read_text_file(file, "an NC file", problems);
  REQUIRE(text);
  CHECK(*text == std::string("G0 X1\r\nM2", 9));
  CHECK(problems.empty());

  CHECK_FALSE(read_text_file(dir.string(), "an NC file", problems));
  REQUIRE(problems.size() == 1);
  CHECK(format_diagnostic(problems[0]) == dir.string() + ": error: is a directory, not an NC file");
  CHECK_FALSE(read_text_file((dir / "missing.nc").string(), "an NC file", problems));
  REQUIRE(problems.size() == 2);
  CHECK(problems[1].file == (dir / "missing.nc").string());
  CHECK(problems[1].severity == Severity::Error);
  std::filesystem::remove_all(dir);
}

TEST_CASE("read_text_file stops at its size limit, also on a device that never ends") {
  const auto dir =
      std::filesystem::temp_directory_path() / ("ncjoule-text-limit-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "big.nc").string();
  std::ofstream(file, std::ios::binary) << std::string(5000, 'G');
  std::vector<Diagnostic> problems;
  CHECK(read_text_file(file, "an NC file", problems, 5000));
  CHECK_FALSE(read_text_file(file, "an NC file", problems, 4999));
  REQUIRE(problems.size() == 1);
  CHECK(problems[0].message.find("larger than 4999 bytes") != std::string::npos);
  // /dev/zero has no size: read until past the limit, then refused.
  CHECK_FALSE(read_text_file("/dev/zero", "an NC file", problems, 1 << 20));
  REQUIRE(problems.size() == 2);
  CHECK(problems[1].message.find("larger than 1 MiB") != std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("non_text_encoding tells wide text and binary data from text") {
  using namespace std::string_literals;
  const std::string program = "G21 G90\nG0 X0 Y0 Z5\nG1 X10 F100\nM2\n";
  auto widen = [&](int width, bool big_endian) {
    std::string out;
    for (char c : program) {
      std::string unit(std::size_t(width), '\0');
      unit[big_endian ? width - 1 : 0] = c;
      out += unit;
    }
    return out;
  };
  CHECK(non_text_encoding(program).empty());
  CHECK(non_text_encoding("").empty());
  // UTF-8 letters, a one-byte code page's accent, a stray ESC and NUL: still text.
  CHECK(non_text_encoding("(Fräse \xc3\xb8 6 mm)\nG0 X0 \x1b Y0 \0 Z0\n(caf\xe9)\nM2\n"s).empty());
  CHECK(non_text_encoding("\xef\xbb\xbf" + program).empty()); // UTF-8 with its mark
  CHECK(non_text_encoding("\xff\xfe"s + widen(2, false)) == "UTF-16 (little-endian) text");
  CHECK(non_text_encoding("\xfe\xff"s + widen(2, true)) == "UTF-16 (big-endian) text");
  CHECK(non_text_encoding(widen(2, false)) == "UTF-16 (little-endian) text");
  CHECK(non_text_encoding(widen(2, true)) == "UTF-16 (big-endian) text");
  CHECK(non_text_encoding("\xff\xfe\0\0"s + widen(4, false)) == "UTF-32 (little-endian) text");
  CHECK(non_text_encoding(widen(4, true)) == "UTF-32 (big-endian) text");
  std::string binary;
  for (int k = 0; k < 4096; ++k)
    binary += char((k * 7919 + 13) & 0xff); // every byte value, spread
  CHECK(non_text_encoding(binary) == "binary data");
  // A mostly ASCII file with NULs scattered through it (an executable's strings) is binary too.
  std::string padded;
  for (int k = 0; k < 200; ++k)
    padded += "G1 X1\n"s + '\0';
  CHECK(non_text_encoding(padded) == "binary data");
}
