// strip() removes exactly what annotate() inserted, and nothing a user wrote, even when it looks
// alike: the seal in the header says which comments are ncjoule's. A file edited after it was
// annotated (its header deleted, a line added above it, blanks removed) still loses every
// annotation, and annotate does not add a second set.
#include <doctest/doctest.h>

#include <string>

#include "annotate_helpers.hpp"
#include "annotation_form.hpp"
#include "marker.hpp"
#include "strip_line.hpp"

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

TEST_CASE("a file whose annotations a user edited loses them all, by their form") {
  const std::string original = "G21 G90\nG0 X10\nG1 X20 F100\nM2\n";
  const std::string once = annotated(original);
  REQUIRE(has_annotations(once));
  const std::size_t at = once.find("G0 X10 (NCJ T=");
  REQUIRE(at != std::string::npos);
  std::string edited = once;
  const std::size_t digit = edited.find_first_of("0123456789", at + 14);
  edited[digit] = edited[digit] == '9' ? '8' : '9';
  // The seal no longer matches: every comment of the annotation's form goes, the edited one too.
  CHECK(strip(edited) == original);
  const std::vector<LineSpan> spans = annotation::split_lines(edited);
  CHECK(annotation::Annotations(edited, spans).by_form());
  CHECK_FALSE(annotation::Annotations(once, annotation::split_lines(once)).by_form());
}

TEST_CASE(
    "what users and DNC senders do to an annotated file: strip still finds every annotation") {
  const std::string original = "%\nO1001 (PART)\nG21 G90\nG0 X10 Y5\nG1 X20 F100\nG1 Y20\n"
                               "G1 X10\nG0 Z20\nM30\n%\n";
  const std::string once = annotated(original);
  REQUIRE(strip(once) == original);
  auto without_lines = [](const std::string& text, auto drop) {
    std::string out;
    for (const std::string& l : lines_of(text))
      if (!drop(l)) out += l + "\n";
    return out;
  };
  // A line of code added above the header (the seal moves down with it).
  std::string added = once;
  added.insert(added.find("(NCJ SEAL"), "G17 (ADDED BY JS)\n");
  std::string original_added = original;
  original_added.insert(original_added.find("G21 G90"), "G17 (ADDED BY JS)\n");
  CHECK(strip(added) == original_added);
  // The header deleted: the block comments go by their form (on most blocks).
  const std::string headless =
      without_lines(once, [](const std::string& l) { return annotation::is_header_line(l); });
  CHECK(headless.find("(NCJ SEAL") == std::string::npos);
  CHECK(strip(headless) == original);
  // Blank lines removed, and then every blank, as DNC senders do.
  const std::string no_blank_lines =
      without_lines(once, [](const std::string& l) { return l.empty(); });
  CHECK(strip(no_blank_lines) == original);
  std::string no_blanks, original_no_blanks;
  for (char c : once)
    if (c != ' ') no_blanks += c;
  for (char c : original)
    if (c != ' ') original_no_blanks += c;
  CHECK(strip(no_blanks) == original_no_blanks);
  // And annotate never doubles them, whatever was done.
  for (const std::string& edited : {added, headless, no_blank_lines, no_blanks}) {
    const std::string again = annotated(edited);
    CHECK(count(again, "(NCJ SEAL") == 1);
    CHECK(count(again, "(NCJ T=") == count(once, "(NCJ T="));
  }
}

TEST_CASE("a file turned to upper case by an editor still strips") {
  const std::string original = "G21 G90\nG0 X10\nG1 X20 F100\nM2\n";
  std::string once = annotated(original);
  for (char& c : once)
    if (c >= 'a' && c <= 'z') c = char(c - 'a' + 'A');
  CHECK(strip(once) == original);
}

TEST_CASE(
    "a file turned to lower case still strips, one without 'ncj' in any case is left as it is") {
  // strip reads no line of a text that holds "NCJ" in no case (most programs): the check must be
  // as blind to case as the annotations' form is.
  const std::string original = "g21 g90\ng0 x10\ng1 x20 f100\nm2\n";
  std::string once = annotated(original);
  for (char& c : once)
    if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
  CHECK(has_annotations(once));
  CHECK(strip(once) == original);
  const std::string mixed = "G21\nG0 X1 (nCj T=1s)\nG1 X2 F100 (Ncj T=1s)\nG1 X3 (NCj T=1s)\nM2\n";
  CHECK(strip(mixed) == "G21\nG0 X1\nG1 X2 F100\nG1 X3\nM2\n"); // by their form
  const std::string none = "G21\nG0 X1 (NC JOB)\nG1 X2 F100 (N C J)\nM2\n";
  CHECK_FALSE(has_annotations(none));
  CHECK(strip_checked(none).text == none);
  CHECK_FALSE(strip_checked(none).by_form);
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

TEST_CASE("comments of earlier versions, sealed with CK= and the file's key, still strip") {
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
  // A header comment at the end of a code line is not an inline annotation, and an inline one on
  // a line of its own is not a header line: only the key line goes (the others, on as many lines
  // as there is code, are too few to be taken by their form).
  const std::string mixed =
      "G0 X1 " + mark(MarkKind::Header) + "\n" + mark(MarkKind::Inline) + "\nG0 X2\nG0 X3\nG0 X4\n";
  CHECK(strip(key + "\n" + mixed) == mixed);
  CHECK(strip(key + "\nG0 X1 " + mark(MarkKind::Inline) + "\n" + mark(MarkKind::Header) + "\n" +
              mark(MarkKind::Line) + "\nG0 X2\n") == "G0 X1\nG0 X2\n");
  // Without the key line, a few of them are the user's; on most blocks, an annotated file whose
  // header was deleted.
  const std::string few = "G0 X1 " + mark(MarkKind::Inline) + "\nG0 X2\nG0 X3\nG0 X4\n";
  CHECK(strip(few) == few);
  const std::string most = "G0 X1 " + mark(MarkKind::Inline) + "\nG0 X2 " + mark(MarkKind::Inline) +
                           "\nG0 X3 " + mark(MarkKind::Inline) + "\nG0 X4\n";
  CHECK(strip(most) == "G0 X1\nG0 X2\nG0 X3\nG0 X4\n");
  // A key line after the first line with code is no key.
  CHECK(strip("G0 X0\n" + key + "\nG0 X1 " + mark(MarkKind::Inline) + "\n") ==
        "G0 X0\n" + key + "\nG0 X1 " + mark(MarkKind::Inline) + "\n");
}

TEST_CASE("every value annotate writes reads back as the annotation's form") {
  for (const char* comment :
       {"(NCJ T=0.012s E=450J P=1.2kW MRR=62.1 CUM=1h02m03s)", "(NCJ T=1m05s E=-1.23kJ)",
        "(NCJ T=16700000000000000000000000h)", "(NCJ T=1.23S E=20.6KJ P=4.5MW)",
        "(NCJ T=6s LOAD_PCT=135 OP=Pocket_40_x_20,_r8 OPT=52.9s OPE=69.2kJ)",
        "(NCJT=1.23sE=20.6kJP=1.42kWMRR=62.1CUM=23.1s)", "(NCJ OP=XOPT OPT=1s OPE=1J)"}) {
    CAPTURE(comment);
    const auto found = annotation::block_comments(std::string("G1 X1 ") + comment);
    REQUIRE(found.size() == 1);
    CHECK(found[0].begin == 5);
  }
  for (const char* comment : {"(NCJ T=1s hello)", "(NCJ E=1 J)", "(NCJ is our code)", "(NCJ)",
                              "(NCJ T=1s E=)", "(NCJ P=1kW T=1s)"})
    CHECK_MESSAGE(annotation::block_comments(std::string("G1 X1 ") + comment).empty(), comment);
}

TEST_CASE("every group the header writes is a header line strip knows") {
  // A guessed stock's range group among them: a label strip did not know left the line in the
  // stripped file and broke the seal.
  for (const char* line :
       {"(NCJ TOTAL T=1s)", "(NCJ TIME CUT=1s)", "(NCJ STOCK BOX=0,0,0,1,1,1)", "(NCJ SETUP N=2)",
        "(NCJ GUESSED STOCK RANGE E=252kJ..277kJ VOL_MM3=0..10338)", "(NCJ ENERGY TARE=1kJ)",
        "(NCJ OP N=1 NAME=Facing)", "(NCJ MACHINE NAME=VMC)", "(NCJ CONST tare_w=325)",
        "(NCJ KEYS T=time of the block.)", "(NCJ WARN a sentence.)"}) {
    CAPTURE(line);
    CHECK(annotation::is_header_line(line));
  }
}
