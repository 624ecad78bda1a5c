// What annotate writes is safe for controllers: only letters, digits, space and . , = _ - inside
// the comment, no nested parentheses, no bytes >= 0x80, upper case for the Fanuc family, and the
// line length kept by dropping fields in a fixed order.
#include <doctest/doctest.h>

#include <string>

#include "annotate_helpers.hpp"
#include "line_alignment.hpp"
#include "marker.hpp"

using namespace ncjoule;
using namespace annotate_test;

namespace {

// The text of every comment annotate inserted: whole lines (the header, a block's comment on a
// line of its own) and the comments inserted into lines, found by matching the annotated lines
// with the original's.
std::vector<std::string> inserted_comments(const std::string& original, const std::string& once) {
  std::vector<std::string> out;
  const auto after = lines_of(once);
  const auto before = lines_of(original);
  const std::vector<int> from = original_lines(after, before);
  REQUIRE(from.size() == after.size());
  for (std::size_t j = 0; j < after.size(); ++j) {
    if (from[j] < 0) {
      out.push_back(after[j]);
      continue;
    }
    const std::string& was = before[static_cast<std::size_t>(from[j])];
    if (after[j] == was) continue;
    // The inserted part starts at the first byte that differs, less the repeats around it, and
    // is as long as the line grew: take it from the first " (NCJ" or " ;NCJ" at or before.
    const std::size_t grew = after[j].size() - was.size();
    std::size_t at = 0;
    while (at < was.size() && after[j][at] == was[at])
      ++at;
    while (at > 0 && !(after[j][at] == ' ' && starts_with_marker(after[j].substr(at + 1))))
      --at;
    out.push_back(after[j].substr(at, grew));
  }
  return out;
}

const char* const kProgramWithUnsafeNames = "%\n"
                                            "O0010 (ÜBER-PART; rev 2)\n"
                                            "(Face (rough) – 50% stepover #1)\n"
                                            "T1 M6\n"
                                            "S1500 M3\n"
                                            "G0 X0 Y0 Z5\n"
                                            "G1 Z-1 F200\n"
                                            "G1 X40 Y10\n"
                                            "G1 X40 Y10 Z5 (bye)\n"
                                            "M5\n"
                                            "M30\n"
                                            "%\n";

} // namespace

TEST_CASE("inserted comments hold only safe characters, for every dialect") {
  for (const std::string& name : dialect_names()) {
    CAPTURE(name);
    const Dialect dialect = *find_dialect(name);
    const bool semicolon = dialect.comment_open == ";";
    const std::string original = kProgramWithUnsafeNames;
    const std::string once = annotated(original, dialect);
    CHECK(strip(once) == original);
    const auto comments = inserted_comments(original, once);
    CHECK(comments.size() >= 8); // header lines and the moving blocks
    for (const std::string& c : comments) {
      CAPTURE(c);
      const std::string body = c.front() == ' ' ? c.substr(1) : c;
      REQUIRE(body.size() > 2);
      CHECK(body.rfind(semicolon ? ";NCJ " : "(NCJ ", 0) == 0);
      if (!semicolon) CHECK(body.back() == ')');
      for (char ch : body.substr(1, body.size() - (semicolon ? 1 : 2))) {
        CHECK(static_cast<unsigned char>(ch) < 0x80);
        CHECK(annotation::is_safe_char(ch));
      }
      if (dialect.upper_case_comments)
        for (char ch : body)
          CHECK_FALSE((ch >= 'a' && ch <= 'z'));
    }
  }
}

TEST_CASE("Fanuc-family annotations are in upper case, others keep readable units") {
  const std::string original = "%\nO0001\nG21 G90\nG00 X10. Y5.\nG01 X20. F300.\nM30\n%\n";
  const std::string fanuc = annotated(original, *find_dialect("fanuc"));
  CHECK(fanuc.find("G00 X10. Y5. (NCJ T=") != std::string::npos);
  CHECK(fanuc.find("KJ") != std::string::npos);
  CHECK(fanuc.find("NAME=GENERIC_3-AXIS_VMC") != std::string::npos);
  const std::string linuxcnc = annotated("%\nG21 G90\nG0 X10 Y5\nG1 X20 F300\nM2\n%\n");
  CHECK(linuxcnc.find("s E=") != std::string::npos);
  CHECK(linuxcnc.find("NAME=Generic_3-axis_VMC") != std::string::npos);
}

TEST_CASE("a line too short for every field drops them in a fixed order, then goes on a line "
          "of its own") {
  const std::string original = "G21 G90\nT1 M6\nG0 X1\nG1 X123.456 Y78.9 F300\nM2\n";
  // From plenty of room down to none: fields go CUM, MRR, P, then OPE, OPT, OP, then E; T stays
  // while it fits after the code, and then the comment is the line before the block, with the
  // fields that fit there.
  const char* const kDropOrder[] = {"CUM=", "MRR=", "P=", "OPE=", "OPT=", "OP=", "E="};
  for (std::size_t limit = 160; limit >= 24; limit -= 2) {
    AnnotateOptions options;
    options.header = false;
    options.max_line_length = limit;
    const std::string once = annotated(original, std::nullopt, options);
    CAPTURE(limit);
    CAPTURE(once);
    CHECK(strip(once) == original);
    const auto after = lines_of(once);
    const std::vector<int> from = original_lines(after, lines_of(original));
    REQUIRE(from.size() == after.size());
    for (const std::string& line : after)
      CHECK(line.size() <= limit);
    // The tool change's comment: after its code, else the line before it.
    std::size_t at = 0;
    while (at < after.size() && from[at] != 1)
      ++at;
    REQUIRE(at < after.size());
    const bool inline_comment = after[at].find("(NCJ") != std::string::npos;
    const std::string tool_change = inline_comment ? after[at] : after[at - 1];
    CHECK(tool_change.find("(NCJ T=") != std::string::npos);
    if (!inline_comment) {
      CHECK(from[at - 1] == -1);
      CHECK(limit < std::string("T1 M6 (NCJ T=6s)").size());
    }
    // A field that is present implies every field dropped after it is present too.
    for (std::size_t i = 0; i + 1 < std::size(kDropOrder); ++i)
      if (tool_change.find(std::string(" ") + kDropOrder[i]) != std::string::npos)
        CHECK(tool_change.find(std::string(" ") + kDropOrder[i + 1]) != std::string::npos);
  }
  AnnotateOptions tight;
  tight.header = false;
  tight.max_line_length = 9; // "(NCJ T=6s)" is 10: no room even on a line of its own
  CHECK(annotated(original, std::nullopt, tight) == original);
}

TEST_CASE("header lines respect the line length too") {
  AnnotateOptions options;
  options.max_line_length = 64; // the seal line's longest, "(NCJ SEAL LINES=9999 ...)", is 61
  const std::string original = "%\nG21 G90\nG0 X1\nG1 X2 F100\nM2\n%\n";
  const std::string once = annotated(original, std::nullopt, options);
  CHECK(strip(once) == original);
  std::size_t header_lines = 0;
  for (const std::string& line : lines_of(once)) {
    CHECK(line.size() <= 64);
    if (line.rfind("(NCJ ", 0) == 0) ++header_lines;
  }
  CHECK(header_lines > 5);
}
