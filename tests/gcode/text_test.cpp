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
