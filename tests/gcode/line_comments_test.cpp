// line_comments() answers lines that hold no comment character without the scanner: its answer
// must be the scanner's for every line, in every dialect.
#include <doctest/doctest.h>

#include <random>
#include <string>

#include "comment_syntax.hpp"

using namespace ncjoule;

namespace {

bool same(const LineComments& a, const LineComments& b) {
  if (a.has_code != b.has_code || a.comments.size() != b.comments.size()) return false;
  for (std::size_t i = 0; i < a.comments.size(); ++i)
    if (a.comments[i].text != b.comments[i].text || a.comments[i].column != b.comments[i].column)
      return false;
  return true;
}

} // namespace

TEST_CASE("line_comments gives the scanner's comments and code on every line, in every dialect") {
  // Blanks, '%', code and every character the scanner treats apart, with plain lines (none of
  // them) as likely as the rest.
  const std::string plain = " \t\r%%GXYZ019.-N";
  const std::string apart = "()\"*;";
  std::mt19937 rng(5);
  int shortcut = 0, scanned = 0, with_code = 0, blank = 0, differ = 0;
  for (const std::string& name : dialect_names()) {
    CAPTURE(name);
    const Dialect& dialect = *find_dialect(name);
    for (int n = 0; n < 4000; ++n) {
      std::string line;
      const bool only_plain = rng() % 2 == 0;
      const int length = int(rng() % 12);
      for (int k = 0; k < length; ++k)
        line += !only_plain && rng() % 4 == 0 ? apart[rng() % apart.size()]
                                              : plain[rng() % (rng() % 3 == 0 ? 5 : plain.size())];
      const LineComments fast = line_comments(line, dialect);
      const LineComments full = detail::scanned_line_comments(line, dialect);
      differ += !same(fast, full);
      (line.find_first_of(apart) == std::string::npos ? shortcut : scanned)++;
      (full.has_code ? with_code : blank)++;
    }
  }
  CHECK(differ == 0);
  // Both ways of answering, and lines with and without code, were tried many times.
  CHECK(shortcut > 10000);
  CHECK(scanned > 10000);
  CHECK(with_code > 10000);
  CHECK(blank > 2000);
}

TEST_CASE("line_comments reads a comment after plain code, and code of blanks as none") {
  const Dialect& linuxcnc = *find_dialect("linuxcnc");
  const LineComments blanks = line_comments(" \t%\r", linuxcnc);
  CHECK_FALSE(blanks.has_code);
  CHECK(blanks.comments.empty());
  const LineComments code = line_comments("G1 X1", linuxcnc);
  CHECK(code.has_code);
  CHECK(code.comments.empty());
  const LineComments both = line_comments("G1 X1 (cut)", linuxcnc);
  CHECK(both.has_code);
  REQUIRE(both.comments.size() == 1);
  CHECK(both.comments[0].text == "cut");
  CHECK(both.comments[0].column == 7);
}
