// strip() removes exactly what annotate() inserted, and nothing a user wrote, even when it looks
// alike: comments are recognised by their checksum, not by their look.
#include <doctest/doctest.h>

#include <string>

#include "annotate_helpers.hpp"
#include "marker.hpp"

using namespace ncjoule;
using namespace annotate_test;

TEST_CASE("user comments that merely look like annotations are kept") {
  const std::string user = "G21\n"
                           "G0 X1 (NCJ T=1s CK=ABCDEF)\n"     // wrong checksum
                           "G0 X2 (NCJ T=1s)\n"               // no checksum
                           "(NCJ TOTAL T=1s CK=000000)\n"     // a header-like line
                           "G0 X3 (NCJ is our shop's code)\n" // just text
                           "G0 X4 (ncj)\n"
                           "G0 X5 ;NCJ T=1s CK=ZZZZZZ\n";
  CHECK(strip(user) == user);
  CHECK_FALSE(has_annotations(user));
}

TEST_CASE("an annotation with one character changed is no longer ncjoule's") {
  const std::string original = "G21 G90\nG0 X10\nG1 X20 F100\nM2\n";
  const std::string once = annotated(original);
  REQUIRE(has_annotations(once));
  const std::size_t at = once.find("G0 X10 (NCJ T=");
  REQUIRE(at != std::string::npos);
  std::string edited = once;
  const std::size_t digit = edited.find_first_of("0123456789", at + 14);
  edited[digit] = edited[digit] == '9' ? '8' : '9';
  const std::string stripped = strip(edited);
  // The edited comment stays (it is now the user's), every other annotation goes.
  CHECK(stripped.find("G0 X10 (NCJ T=") != std::string::npos);
  CHECK(stripped.find("G1 X20 F100\n") != std::string::npos);
  CHECK(count(stripped, "(NCJ") == 1);
}

TEST_CASE("a file turned to upper case by an editor still strips") {
  const std::string original = "G21 G90\nG0 X10\nG1 X20 F100\nM2\n";
  std::string once = annotated(original);
  for (char& c : once)
    if (c >= 'a' && c <= 'z') c = char(c - 'a' + 'A');
  CHECK(strip(once) == original);
}

TEST_CASE("strip takes the space annotate inserted and keeps the user's own blanks") {
  const std::string original = "G21\nG0 X1  \t\nG1 X2 F100\t(c)\nG1 X3(c)\nM2\n";
  const std::string once = annotated(original);
  CHECK(once.find("G0 X1 (NCJ ") != std::string::npos);
  CHECK(once.find(")  \t\n") != std::string::npos);
  CHECK(once.find("G1 X3 (NCJ ") != std::string::npos);
  CHECK(once.find(")(c)") != std::string::npos);
  CHECK(strip(once) == original);
}

TEST_CASE("each kind of annotation has a checksum of its own, sealed with the file's key") {
  using annotation::MarkKind;
  const annotation::CommentStyle paren;
  const std::string key =
      annotation::marked_comment(annotation::key_content("ABCDEF"), MarkKind::Key, paren, "");
  const std::string seed = annotation::key_seed("ABCDEF");
  auto mark = [&](MarkKind kind) {
    return annotation::marked_comment("NCJ T=1s", kind, paren, seed);
  };
  CHECK(mark(MarkKind::Inline) != mark(MarkKind::Header));
  CHECK(mark(MarkKind::Inline) != mark(MarkKind::Line));
  CHECK(mark(MarkKind::Header) != mark(MarkKind::Line));
  CHECK(annotation::marked_comment("NCJ T=1s", MarkKind::Inline, paren,
                                   annotation::key_seed("ABCDEG")) != mark(MarkKind::Inline));
  // A header comment at the end of a code line is not an inline annotation, and an inline one on
  // a line of its own is not a header line: only the key line goes.
  const std::string mixed =
      "G0 X1 " + mark(MarkKind::Header) + "\n" + mark(MarkKind::Inline) + "\nG0 X2\n";
  CHECK(strip(key + "\n" + mixed) == mixed);
  CHECK(strip(key + "\nG0 X1 " + mark(MarkKind::Inline) + "\n" + mark(MarkKind::Header) + "\n" +
              mark(MarkKind::Line) + "\nG0 X2\n") == "G0 X1\nG0 X2\n");
  // Without the key line, none of them is an annotation.
  const std::string keyless = "G0 X1 " + mark(MarkKind::Inline) + "\n" + mark(MarkKind::Header) +
                              "\n" + mark(MarkKind::Line) + "\nG0 X2\n";
  CHECK(strip(keyless) == keyless);
  // A key line after the first line with code is no key.
  CHECK(strip("G0 X0\n" + key + "\nG0 X1 " + mark(MarkKind::Inline) + "\n") ==
        "G0 X0\n" + key + "\nG0 X1 " + mark(MarkKind::Inline) + "\n");
}
