// strip(annotate(x)) == x byte for byte, and annotate(annotate(x)) == annotate(x), on files that
// exercise what an annotator could get wrong: line endings, blanks, case, block delete, tape
// marks, comments of both kinds, a missing final newline, lines at the length limit.
#include <doctest/doctest.h>

#include "annotate_helpers.hpp"

using namespace ncjoule;
using namespace annotate_test;

namespace {

// Every way a file can be written that must survive untouched.
const char* const kTrickyPrograms[] = {
    // CRLF, tabs, trailing blanks, lower case, block delete, both comment kinds, MSG, blank lines,
    // % at both ends and no newline after the last one.
    "%\r\n(Tricky program)\r\ng21 g90 g17\r\n\tG0 X0 Y0 Z5  \t\r\nT1 M6\r\nS1000 M3\r\n"
    "/G1 Z-1 F100\r\ng1 x10 y0 (lower case)  \r\nG1 X20 (MSG, halfway)\r\n"
    "G1 X30 ; semicolon note\r\nG1 X40(no space)(MSG, two comments)\r\n\r\n   \r\n"
    "G0 Z5\r\nM5\r\nM2\r\n%",
    // LF, a motion block as the last line without a newline.
    "G21 G90\nG0 X1 Y1 Z1\nG1 X2 F100\nG1 X3",
    // Old Mac line endings and a mixture.
    "G21 G90\rG0 X1\rG1 X5 F200\r\nG1 Y5\nM2\r",
    // Only a tape mark, no newline: nothing to put a header before.
    "%",
    // Empty file.
    "",
    // Comments only.
    "(nothing but words)\n; and more\n",
    // A comment that looks like ncjoule's, written by a user: kept as it is.
    "G21\nG0 X1 (NCJ T=1s CK=ABCDEF)\nG1 X2 F100 (NCJ user note)\nM2\n",
    // Tabs before comments, several blanks, a line of blanks with a tab.
    "G21 G90\n\t\t\nG0\tX1\t\t(tabbed)\t\nG1  X2  F300    ;  spaced  \nM2\n",
};

void check_round_trip(const std::string& original) {
  const std::string once = annotated(original);
  CHECK(strip(once) == original);
  // Re-annotating the annotated file, as the command line does (strip, then estimate).
  CHECK(annotated(strip(once)) == once);
  // annotate() given an annotated file and its estimate replaces the old annotations itself.
  CHECK(annotated(once) == once);
}

} // namespace

TEST_CASE("tricky files round-trip byte for byte and annotate is idempotent") {
  for (const char* program : kTrickyPrograms) {
    CAPTURE(program);
    check_round_trip(program);
  }
}

TEST_CASE("the tricky CRLF file gets annotations, and only comments are added") {
  const std::string original = kTrickyPrograms[0];
  const std::string once = annotated(original);
  CHECK(once != original);
  const auto before = lines_of(original);
  const auto after = lines_of(once);
  // Header lines are the only new lines, after the % line and the program's title comment;
  // every other line starts with the original line's code.
  const std::size_t header = after.size() - before.size();
  CHECK(header >= 3);
  CHECK(after[0] == "%");
  CHECK(after[1] == "(Tricky program)");
  CHECK(after[2].rfind("(NCJ SEAL ", 0) == 0);
  for (std::size_t i = 2; i < 2 + header; ++i)
    CHECK(after[i].rfind("(NCJ ", 0) == 0);
  for (std::size_t i = 2; i < before.size(); ++i) {
    CAPTURE(before[i]);
    const std::string& a = after[i + header];
    CHECK(count(a, "(NCJ ") <= 1);
    CHECK(a.size() >= before[i].size());
  }
  // Every line ending is CRLF, header lines too, and the last line still has none.
  CHECK(count(once, "\r\n") == count(original, "\r\n") + header);
  CHECK(count(once, "\n") == count(once, "\r\n"));
  CHECK(once.back() == '%');
}

TEST_CASE("blocks that move or take time get exactly one comment, others none") {
  const std::string original = "G21 G90\nG0 X1 Y1\nF100\nG1 X5\nG4 P0.5\nM2\n";
  AnnotateOptions options;
  options.header = false;
  const auto after = lines_of(annotated(original, std::nullopt, options));
  REQUIRE(after.size() == 6);
  CHECK(after[0] == "G21 G90");
  CHECK(count(after[1], "(NCJ ") == 1);
  CHECK(after[2] == "F100");
  CHECK(count(after[3], "(NCJ ") == 1);
  CHECK(count(after[4], "(NCJ ") == 1); // a dwell takes time
  CHECK(after[4].find("T=0.5s") != std::string::npos);
  CHECK(after[5] == "M2");
}

TEST_CASE("a line at the maximum length is left as it is, its comment the line before it") {
  AnnotateOptions options;
  options.max_line_length = 60;
  std::string full = "G1 X3 F100 (";
  full += std::string(60 - full.size() - 1, 'p') + ")";
  REQUIRE(full.size() == 60);
  const std::string original = "G21 G90\nG0 X1\n" + full + "\nG1 X4\nM2\n";
  const std::string once = annotated(original, std::nullopt, options);
  CHECK(strip(once) == original);
  for (const std::string& line : lines_of(once)) {
    CAPTURE(line);
    CHECK(line.size() <= 60);
  }
  CHECK(once.find("\n" + full + "\n") != std::string::npos);
  CHECK(count(once, "G0 X1 (NCJ T=") == 1);
  CHECK(count(once, "\n(NCJ T=") == 1);
  CHECK(once.find(")\n" + full + "\n") != std::string::npos);
}

TEST_CASE("a Fanuc line at the dialect's 128 characters is left alone, its comment before it") {
  const Dialect fanuc = *find_dialect("fanuc");
  REQUIRE(fanuc.max_line_length == 128);
  std::string full = "G01 X3. F100. (";
  full += std::string(128 - full.size() - 1, 'P') + ")";
  REQUIRE(full.size() == 128);
  const std::string original = "%\nO0001\nG21 G90\nG00 X1.\n" + full + "\nM30\n%\n";
  const std::string once = annotated(original, fanuc);
  CHECK(strip(once) == original);
  CHECK(once.find("\n" + full + "\n") != std::string::npos);
  CHECK(once.find("\n(NCJ T=") != std::string::npos);
  for (const std::string& line : lines_of(once))
    CHECK(line.size() <= 128);
}
