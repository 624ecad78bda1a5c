// The lexer keeps every byte of a line and cuts its code into words.
#include <doctest/doctest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "block.hpp"

using namespace ncjoule;
using ncjoule::detail::Block;
using ncjoule::detail::lex_line;

namespace {
Block lex(std::string_view line, const char* dialect = "linuxcnc") {
  Block b;
  lex_line(line, *find_dialect(dialect), b);
  return b;
}
} // namespace

TEST_CASE("source lines keep their exact bytes and line endings") {
  const std::string text = "G0 X1\r\n/G1 Y2 \t\n(comment)\rM2";
  SourceFile f = make_source("t.nc", text);
  REQUIRE(f.lines.size() == 4);
  CHECK(f.line_text(0) == "G0 X1");
  CHECK(f.lines[0].eol_length == 2);
  CHECK(f.line_text(1) == "/G1 Y2 \t");
  CHECK(f.lines[1].eol_length == 1);
  CHECK(f.line_text(2) == "(comment)");
  CHECK(f.lines[2].eol_length == 1);
  CHECK(f.line_text(3) == "M2");
  CHECK(f.lines[3].eol_length == 0);
  // Re-assembling the lines gives the file back byte for byte.
  std::string back;
  for (const LineSpan& l : f.lines)
    back += text.substr(l.begin, l.length + l.eol_length);
  CHECK(back == text);
}

TEST_CASE("source lines of random texts, with and without CR, are the line endings' spans") {
  // LF, CRLF or a lone CR ends a line (the text without any CR takes a faster way): every
  // line's span as a plain reading of the text gives it, and the lines put back are the text.
  std::mt19937 rng(13);
  const std::string alphabet = "G1 X2.5\n\n;()";
  int lines_seen = 0;
  for (int n = 0; n < 3000; ++n) {
    std::string text;
    const bool with_cr = n % 2 == 0;
    const int length = int(rng() % 40);
    for (int k = 0; k < length; ++k)
      text += with_cr && rng() % 6 == 0 ? '\r' : alphabet[rng() % alphabet.size()];
    std::vector<LineSpan> expected;
    for (std::size_t begin = 0; begin < text.size();) {
      std::size_t i = begin;
      while (i < text.size() && text[i] != '\n' && text[i] != '\r')
        ++i;
      std::uint8_t eol = 0;
      if (i < text.size())
        eol = text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n' ? 2 : 1;
      expected.push_back({begin, i - begin, eol});
      begin = i + eol;
    }
    const SourceFile f = make_source("t.nc", text);
    REQUIRE(f.lines.size() == expected.size());
    // count_lines: one more than the line ends, which make_source's last line may lack.
    const bool ends_line = text.empty() || text.back() == '\n' || text.back() == '\r';
    CHECK(count_lines(text) == expected.size() + (ends_line ? 1 : 0));
    std::string back;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      CHECK(f.lines[i].begin == expected[i].begin);
      CHECK(f.lines[i].length == expected[i].length);
      CHECK(f.lines[i].eol_length == expected[i].eol_length);
      back += text.substr(f.lines[i].begin, f.lines[i].length + f.lines[i].eol_length);
    }
    CHECK(back == text);
    lines_seen += int(f.lines.size());
  }
  CHECK(lines_seen > 10000);
}

TEST_CASE("words, lower case, blanks inside numbers and comments") {
  Block b = lex("n10 g1 x1 0.5 Y-.25 (move (fast) ; z9");
  REQUIRE(b.errors.size() == 0);
  REQUIRE(b.words.size() == 3);
  CHECK(b.words[0].letter == 'g');
  CHECK(b.words[1].value == "10.5"); // LinuxCNC ignores blanks anywhere in code
  CHECK(b.words[2].letter == 'y');
  CHECK(b.words[2].value == "-.25");
  CHECK(b.words[2].column == 15); // the Y, counting from 1
  REQUIRE(b.comments.size() == 2);
  CHECK(b.comments[0].text == "move (fast");
  CHECK(b.comments[1].text == " z9");
}

TEST_CASE("block delete, percent lines and grbl settings") {
  CHECK(lex("/G0 X1").block_delete);
  CHECK(lex("  %  ").percent);
  CHECK(lex("  %  ").percent_bare);
  for (const char* line : {"% vfd enable", "%(start)", "N10 %", "%%", "%prog1"}) {
    CAPTURE(line);
    const Block b = lex(line);
    CHECK(b.percent);
    CHECK_FALSE(b.percent_bare);
  }
  CHECK(lex("N10 %").percent_column == 5);
  CHECK(lex("$110=500", "grbl").dollar);
  CHECK_FALSE(lex("$110=500").warnings.empty()); // not in LinuxCNC: warned about, skipped
}

TEST_CASE("expressions, parameters and assignments") {
  Block b = lex("G1 X[#1 + 2] Y#<depth> Z-sin[30] #5=[#5+1] #<_n> = 3");
  REQUIRE(b.errors.empty());
  REQUIRE(b.words.size() == 4);
  CHECK(b.words[1].value == "[#1+2]");
  CHECK(b.words[2].value == "#<depth>");
  CHECK(b.words[3].value == "-sin[30]");
  REQUIRE(b.assignments.size() == 2);
  CHECK(b.assignments[0].target == "5");
  CHECK(b.assignments[0].value == "[#5+1]");
  CHECK(b.assignments[1].target == "<_n>");
}

TEST_CASE("O-words and Fanuc program numbers") {
  Block sub = lex("o<Pocket> sub");
  CHECK(sub.has_o);
  CHECK(sub.o_label == "<pocket>");
  CHECK(sub.o_keyword == "sub");
  Block call = lex("O0100 call [1] [2.5]");
  CHECK(call.o_label == "100");
  CHECK(call.o_keyword == "call");
  CHECK(call.o_args == "[1][2.5]");
  Block header = lex("O1234 (PART)", "fanuc");
  CHECK(header.has_o);
  CHECK(header.o_keyword.empty());
}

TEST_CASE("lexical problems carry the column, and those the control refuses are errors") {
  Block b = lex("G1 X1 Y");
  REQUIRE(b.errors.size() == 1); // a word with no value: rs274 refuses the block
  CHECK(b.errors[0].column == 7);
  Block broken = lex("G1 X1 Y[1");
  CHECK(broken.errors.empty()); // an expression not closed costs only its word
  REQUIRE_FALSE(broken.warnings.empty());
  CHECK(broken.warnings[0].column == 7);
  CHECK(broken.words.size() == 2);
  Block c = lex("G1 X1 (open");
  REQUIRE(c.warnings.size() == 1);
  CHECK(c.warnings[0].column == 7);
  Block d = lex("G1 X1 @");
  REQUIRE(d.warnings.size() == 1);
  CHECK(d.warnings[0].message.find('@') != std::string::npos);
}

TEST_CASE("an O inside a number, two decimal points and a bare letter are errors, not words") {
  const Block o = lex("G1 Z-0.03 F1O8.", "haas");
  REQUIRE(o.errors.size() == 1);
  CHECK(o.errors[0].column == 13);
  CHECK(o.errors[0].message.find("inside the number 'F1O8.'") != std::string::npos);
  // An O word of its own is not a typo in a number: nccad's controller sets an output so.
  CHECK(lex("M10 O6.0").errors.empty());
  CHECK(lex("G1 F1 O8").errors.empty());
  const Block points = lex("G1 X0..2");
  REQUIRE(points.errors.size() == 1);
  CHECK(points.errors[0].message.find("two decimal points in 'X0..2'") != std::string::npos);
  CHECK(lex("G0 X1 Y-").errors.size() == 1);
  // At the start of a block an O is a program number or an O-word, as before.
  CHECK(lex("N10 O100", "fanuc").has_o);
  CHECK(lex("N10 O100", "fanuc").errors.empty());
  // Marlin's parser reads a letter alone as a flag and skips what follows a number.
  CHECK(lex("G28 X Y", "reprap").errors.empty());
  CHECK(lex("G1 X0..2 F1O8.", "reprap").errors.empty());
}

TEST_CASE("words of several letters, Sinumerik argument lists and X=value") {
  Block b = lex("N10 MCALL CYCLE81(10, 0, 2, -5, ) ; drill", "siemens");
  CHECK(b.errors.empty());
  CHECK(b.warnings.empty());
  REQUIRE(b.keywords.size() == 2);
  CHECK(b.keywords[0].name == "mcall");
  CHECK(b.keywords[0].column == 5);
  CHECK(b.keywords[1].name == "cycle81");
  CHECK(b.keywords[1].has_parens);
  CHECK(b.keywords[1].args == "10,0,2,-5,");
  REQUIRE(b.comments.size() == 1);
  Block r = lex("ROT RPL=45 G0 X=10.5", "siemens");
  REQUIRE(r.keywords.size() == 2);
  CHECK(r.keywords[1].name == "rpl");
  CHECK(r.keywords[1].args == "45");
  REQUIRE(r.words.size() == 2);
  CHECK(r.words[1].value == "10.5");
  // Elsewhere a '(' after a name is still a comment, and functions stay values.
  Block l = lex("G0 X1 TOOL(x)");
  REQUIRE(l.keywords.size() == 1);
  CHECK(l.keywords[0].name == "tool");
  CHECK(l.comments.size() == 1);
  Block f = lex("G0 Xsin[30] Ycos[0]");
  CHECK(f.keywords.empty());
  CHECK(f.words.size() == 3);
}

TEST_CASE("Fanuc dialect: a semicolon is not a comment, parentheses are") {
  Block b = lex("G1 X1 (A;B)", "fanuc");
  CHECK(b.errors.empty());
  CHECK(b.comments[0].text == "A;B");
}

TEST_CASE("brackets are matched as the scan of each word would match them") {
  const Block b = lex("G1 X[1+[2]] Y[3 Z[4] A[[5]]");
  // X's value ends at its own ']'; Y's '[' is never closed (Z's is), so Y has no value.
  REQUIRE(b.words.size() == 4);
  CHECK(b.words[1].value == "[1+[2]]");
  CHECK(b.words[2].letter == 'z');
  CHECK(b.words[2].value == "[4]");
  CHECK(b.words[3].value == "[[5]]");
  CHECK(b.warnings.size() == 2); // Y without a value, the '[3' after it
  CHECK(ncjoule::detail::value_length("--#-#[1]]", 0) == 8);
  CHECK(ncjoule::detail::value_length("+#<a>b", 0) == 5);
  CHECK(ncjoule::detail::value_length("###", 0) == 0);
}

TEST_CASE("a line of a hundred thousand stray words keeps a hundred warnings and says so") {
  std::string line = "G1 ";
  for (int i = 0; i < 100000; ++i)
    line += "x[";
  const Block b = lex(line);
  REQUIRE(b.warnings.size() == 101);
  CHECK(b.warnings.back().message.find("not listed") != std::string::npos);
}
