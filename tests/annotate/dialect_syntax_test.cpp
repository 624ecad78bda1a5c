// Each dialect gets its annotations in its controller's comment syntax, never inside a call, an
// expression or a string, and within its controller's line length: Sinumerik and Marlin read
// ';' comments, grbl's senders stream lines of at most 125 bytes; and the annotated program runs
// exactly as the original, block for block.
#include <doctest/doctest.h>

#include <string>

#include "annotate_helpers.hpp"

using namespace ncjoule;
using namespace annotate_test;

namespace {

AnnotateOptions no_header() {
  AnnotateOptions o;
  o.header = false;
  return o;
}

// The line of `text` that starts with `code`.
std::string line_starting(const std::string& text, const std::string& code) {
  for (const std::string& line : lines_of(text))
    if (line.rfind(code, 0) == 0) return line;
  return {};
}

const char* const kSinumerik = "%_N_PART_MPF\n"
                               ";$PATH=/_N_WKS_DIR/_N_PART_WPD\n"
                               ";PART TITLE\n"
                               "G0 X0 Y0 Z5\n"
                               "CYCLE81(10,0,2,-5)\n"
                               "G1 X10 Y=COS (0) F100\n"
                               "G0 X1 MSG(\"a;b(c)\")\n"
                               "G1 X5 ;note\n"
                               "M30\n";

} // namespace

TEST_CASE("Sinumerik: semicolon annotations after calls, expressions and strings, never inside") {
  const Dialect siemens = *find_dialect("siemens");
  const std::string original = kSinumerik;
  const std::string once = annotated(original, siemens, no_header());
  CHECK(strip(once) == original);
  CHECK(annotated(once, siemens, no_header()) == once);
  CHECK(once.find("(NCJ") == std::string::npos);
  // The whole call, expression or string first, then the comment.
  CHECK(line_starting(once, "CYCLE81(10,0,2,-5) ;NCJ T=").size() > 0);
  CHECK(line_starting(once, "G1 X10 Y=COS (0) F100 ;NCJ T=").size() > 0);
  CHECK(line_starting(once, "G0 X1 MSG(\"a;b(c)\") ;NCJ T=").size() > 0);
  // Before the user's own ';' comment.
  const std::string note = line_starting(once, "G1 X5 ;NCJ T=");
  CHECK(note.substr(note.size() - 6) == " ;note");
  // The program runs as it did.
  CHECK(canon_of(once, siemens, original) == canon_of(original, siemens, original));
}

TEST_CASE("Sinumerik: the header is semicolon comments after %_N_, the $PATH line and the title "
          "comment") {
  const Dialect siemens = *find_dialect("siemens");
  const std::string original = kSinumerik;
  const std::string once = annotated(original, siemens);
  CHECK(strip(once) == original);
  CHECK(annotated(once, siemens) == once);
  const auto after = lines_of(once);
  REQUIRE(after.size() > 12);
  CHECK(after[0] == "%_N_PART_MPF");
  CHECK(after[1] == ";$PATH=/_N_WKS_DIR/_N_PART_WPD");
  CHECK(after[2] == ";PART TITLE");
  CHECK(after[3].rfind(";NCJ SEAL ", 0) == 0);
  CHECK(after[4].rfind(";NCJ TOTAL T=", 0) == 0);
  CHECK(once.find("(NCJ") == std::string::npos);
  CHECK(canon_of(once, siemens, original) == canon_of(original, siemens, original));
}

TEST_CASE("a string's semicolon and parentheses are no comment to the scanner annotate reads") {
  const Dialect siemens = *find_dialect("siemens");
  // ')' inside the string first: a count of parentheses alone would end the call there and take
  // ";c" for a comment inside the string.
  const std::string original = "G0 X0 Y0 Z5\nG0 X1 MSG(\"x)y;z\")\nG1 X2 F100 ; end\nM30\n";
  const std::string once = annotated(original, siemens, no_header());
  CHECK(strip(once) == original);
  CHECK(line_starting(once, "G0 X1 MSG(\"x)y;z\") ;NCJ T=").size() > 0);
  CHECK(canon_of(once, siemens, original) == canon_of(original, siemens, original));
}

TEST_CASE("a line ending inside a string or an argument list gets its comment on a line before") {
  // Found by fuzzing: at the end of 'MSG("a;b(' the comment was inside the string, and the
  // message said it.
  const Dialect siemens = *find_dialect("siemens");
  for (const char* open : {"G0 X1 MSG(\"a;b(", "G0 X1 MSG(\"a;b", "G0 X2 CYCLE81(10,0,2"}) {
    CAPTURE(open);
    const std::string original = std::string("G0 X0 Y0 Z5\n") + open + "\nG1 X5 F100\nM30\n";
    for (const AnnotateOptions& options : {AnnotateOptions{}, no_header()}) {
      const std::string once = annotated(original, siemens, options);
      CHECK(strip(once) == original);
      CHECK(annotated(once, siemens, options) == once);
      CHECK(once.find(std::string("\n") + open + "\n") != std::string::npos); // as it was
      CHECK(canon_of(once, siemens, original) == canon_of(original, siemens, original));
    }
  }
}

TEST_CASE("semicolon annotations never go at the end of a '( )' comment that does not close") {
  // Found by fuzzing: "G0 X(msg,note" took the comment into its message.
  for (const char* name : {"siemens", "reprap"}) { // Heidenhain reads '(' as code
    CAPTURE(name);
    const Dialect dialect = *find_dialect(name);
    const std::string original = "G0 X0 Y0 Z5\nG0 X1 (msg,note Y2\nG1 X5 F100\nM30\n";
    const std::string once = annotated(original, dialect);
    CHECK(strip(once) == original);
    CHECK(once.find("\nG0 X1 (msg,note Y2\n") != std::string::npos);
    CHECK(canon_of(once, dialect, original) == canon_of(original, dialect, original));
  }
}

TEST_CASE(
    "Marlin and RepRapFirmware: semicolon annotations, no parentheses Marlin would read as code") {
  const Dialect reprap = *find_dialect("reprap");
  const std::string original = "G21\nG90\nG0 X0 Y0 Z5\nG1 X20 F600 ; perimeter\nG4 P500\nM84\n";
  for (const AnnotateOptions& options : {AnnotateOptions{}, no_header()}) {
    const std::string once = annotated(original, reprap, options);
    CAPTURE(once);
    CHECK(strip(once) == original);
    CHECK(annotated(once, reprap, options) == once);
    CHECK(once.find('(') == std::string::npos);
    CHECK(line_starting(once, "G1 X20 F600 ;NCJ T=").size() > 0);
    for (const std::string& line : lines_of(once))
      CHECK(line.size() <= 95); // MAX_CMD_SIZE 96 with its terminating zero
    CHECK(canon_of(once, reprap, original) == canon_of(original, reprap, original));
  }
}

TEST_CASE("grbl: no annotated line longer than a sender streams, no room means a line of its own") {
  const Dialect grbl = *find_dialect("grbl");
  REQUIRE(grbl.max_line_length == 125);
  const std::string long_comment = "G1 X10 Y20 F300 (" + std::string(95, 'a') + ")";
  // 96 bytes: room for " (NCJ T=... CK=......)" and little more.
  const std::string some_room = "G1 X20.123456 Y30.123456 Z-1.123456 F300 (a post's comment, "
                                "thirty-odd characters)";
  const std::string original =
      "G21 G90\nG0 X0 Y0 Z5\n" + long_comment + "\n" + some_room + "\nM2\n";
  for (const AnnotateOptions& options : {AnnotateOptions{}, no_header()}) {
    const std::string once = annotated(original, grbl, options);
    CAPTURE(once);
    CHECK(strip(once) == original);
    CHECK(annotated(once, grbl, options) == once);
    const auto after = lines_of(once);
    for (const std::string& line : after)
      CHECK(line.size() <= 125);
    // The block with no room keeps its line as it was; its comment is the line before it.
    std::size_t at = 0;
    while (at < after.size() && after[at] != long_comment)
      ++at;
    REQUIRE(at < after.size());
    REQUIRE(at > 0);
    CHECK(after[at - 1].rfind("(NCJ T=", 0) == 0);
    // A line with some room gets the fields that fit, T first.
    CHECK(line_starting(once, "G1 X20.123456").find(" (NCJ T=") != std::string::npos);
    CHECK(canon_of(once, grbl, original) == canon_of(original, grbl, original));
  }
}

TEST_CASE("a block's own comment line is removed with its line ending, CR LF or none after") {
  const Dialect grbl = *find_dialect("grbl");
  const std::string full = "G1 X1 F100 (" + std::string(120, 'c') + ")";
  for (const char* eol : {"\n", "\r\n", "\r"}) {
    CAPTURE(eol);
    const std::string original =
        std::string("G21 G90") + eol + "G0 X0 Y0 Z1" + eol + full + eol + full; // no final eol
    for (const AnnotateOptions& options : {AnnotateOptions{}, no_header()}) {
      const std::string once = annotated(original, grbl, options);
      CHECK(strip(once) == original);
      CHECK(count(once, "(NCJ T=") >= 2);
      CHECK(annotated(once, grbl, options) == once);
    }
  }
}

TEST_CASE("Heidenhain ISO: semicolon after the block's '*', and no comment lines between blocks") {
  const Dialect tnc = *find_dialect("heidenhain");
  const std::string original = "%PART G71 *\nN10 G00 X+0 Y+0 Z+5 *\nN20 G01 X+10 F100 *\n"
                               "N99999999 %PART G71 *\n";
  const std::string once = annotated(original, tnc, no_header());
  CHECK(strip(once) == original);
  CHECK(line_starting(once, "N10 G00 X+0 Y+0 Z+5 * ;NCJ T=").size() > 0);
  CHECK(lines_of(once).size() == lines_of(original).size());
  CHECK(canon_of(once, tnc, original) == canon_of(original, tnc, original));
  // A block with no room for its time gets nothing: a line without its number and '*' is no
  // block a TNC reads.
  AnnotateOptions tight = no_header();
  tight.max_line_length = 24;
  CHECK(annotated(original, tnc, tight).find("N20 G01 X+10 F100 *\n") != std::string::npos);
  CHECK(lines_of(annotated(original, tnc, tight)).size() == lines_of(original).size());
}
