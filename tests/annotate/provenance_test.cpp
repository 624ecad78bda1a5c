// An annotation is ncjoule's only in the file it was written for: a user's look-alike is never
// taken for one, and a genuine annotation copied from another annotated file into a program (a
// note after a block, a header line) is the user's text there, kept byte for byte by annotate
// and strip. The seal (the header's first line, or without a header a SEAL field of the first
// block comment) counts the file's own comments and lists the user's of the same form.
#include <doctest/doctest.h>

#include <string>

#include "annotate_helpers.hpp"
#include "marker.hpp"
#include "seal.hpp"

using namespace ncjoule;
using namespace annotate_test;

namespace {

AnnotateOptions no_header() {
  AnnotateOptions o;
  o.header = false;
  return o;
}

const char* const kOther = "G21 G90\nG0 X0 Y0 Z5\nG1 X40 F500\nG1 Y40\nM2\n";
const char* const kProgram = "G21 G90\nG0 X10 Y10 Z5\nG1 X80 F300\nG1 Y60\nG0 Z20\nM2\n";

// The first line of `text` that starts with `prefix`.
std::string first_line(const std::string& text, const std::string& prefix) {
  for (const std::string& line : lines_of(text))
    if (line.rfind(prefix, 0) == 0) return line;
  FAIL("no line starts with " << prefix);
  return {};
}

// The inline annotation on the line of `text` that starts with `code`: " (NCJ ...)".
std::string inline_annotation(const std::string& text, const std::string& code) {
  const std::string line = first_line(text, code);
  const std::size_t at = line.find(" (NCJ ");
  REQUIRE(at != std::string::npos);
  return line.substr(at, line.find(')', at) + 1 - at);
}

// annotate, strip and annotate again leave `program` as it is, whatever it holds.
void check_kept(const std::string& program, const AnnotateOptions& options = {}) {
  CAPTURE(program);
  CHECK_FALSE(has_annotations(program));
  CHECK(strip(program) == program);
  const std::string once = annotated(program, std::nullopt, options);
  CHECK(strip(once) == program);
  CHECK(annotated(once, std::nullopt, options) == once);
}

} // namespace

TEST_CASE("a user's NCJ comment, even of the annotation's form, is never taken for one") {
  const std::string key =
      annotation::marked_comment("NCJ FILE KEY=ABCDEF", annotation::MarkKind::Key, {}, "");
  std::string bad_key = key;
  bad_key[bad_key.size() - 2] = bad_key[bad_key.size() - 2] == '0' ? '1' : '0';
  const std::string user = "(NCJ FILE KEY=ABCDEF CK=000000)\n" + bad_key +
                           "\n(NCJ TOTAL T=1s CK=000000)\nG21 G90\n"
                           "G0 X1 (NCJ T=1s CK=ABCDEF)\nG0 X2 (NCJ T=1s)\n"
                           "G0 X3 (NCJ is our shop's code)\nG1 X5 F100 ;NCJ T=1s CK=ZZZZZZ\nM2\n";
  check_kept(user);
  check_kept(user, no_header());
}

TEST_CASE("an annotation pasted from another file after a block is kept by annotate and strip") {
  for (const AnnotateOptions& options : {AnnotateOptions{}, no_header()}) {
    const std::string other = annotated(kOther, std::nullopt, options);
    const std::string note = inline_annotation(other, "G1 X40 F500");
    // Pasted after a block of this program, on a line of the same code and on another one.
    std::string program = kProgram;
    program.replace(program.find("G1 X80 F300\n"), 12, "G1 X80 F300" + note + "\n");
    program.replace(program.find("G0 Z20\n"), 7, "G0 Z20 (see" + note + ")\n");
    check_kept(program);
    check_kept(program, no_header());
    const std::string same_code = "G21 G90\nG0 X0 Y0 Z5\nG1 X40 F500 (was" + note + ")\nM2\n";
    check_kept(same_code);
  }
}

TEST_CASE("a header line pasted from another annotated file is kept as the user's") {
  const std::string other = annotated(kOther);
  for (const char* label : {"(NCJ TOTAL ", "(NCJ OP ", "(NCJ MACHINE ", "(NCJ SEAL "}) {
    CAPTURE(label);
    const std::string pasted = first_line(other, label);
    // After the first block: a seal line without its header lines is no seal.
    std::string program = kProgram;
    program.insert(program.find("G0 X10"), pasted + "\n");
    check_kept(program);
    check_kept(program, no_header());
    // And among the program's own leading comments.
    check_kept("(my part)\n" + pasted + "\n" + kProgram);
  }
}

TEST_CASE("the seal is the first header line, and only the file's own annotations go with it") {
  const std::string once = annotated(kProgram);
  const auto after = lines_of(once);
  REQUIRE(after.size() > 3);
  const std::optional<annotation::Seal> seal = annotation::seal_of_line(after[0]);
  REQUIRE(seal);
  CHECK(seal->blocks == 4);
  CHECK(seal->keep.empty());
  // The same program, the same file; the seal of another program does not cover this one.
  CHECK(annotated(kProgram) == once);
  CHECK(annotation::seal_of_line(lines_of(annotated(kOther))[0])->sum != seal->sum);
  CHECK(strip(once) == kProgram);
  // No block carries a checksum: the seal line alone has one.
  CHECK(count(once, "CK=") == 1);
}

TEST_CASE("with a header, a block whose numbers a user edited still has its annotation stripped") {
  const std::string once = annotated(kProgram);
  std::string edited = once;
  const std::size_t at = edited.find("G1 X80 F300 (NCJ");
  REQUIRE(at != std::string::npos);
  edited.replace(at, 11, "G1 X85.5 F250");
  std::string expected = kProgram;
  expected.replace(expected.find("G1 X80 F300"), 11, "G1 X85.5 F250");
  CHECK(strip(edited) == expected);
}

TEST_CASE("without a header, the seal is a field of the first comment: upper case still strips") {
  const std::string once = annotated(kProgram, std::nullopt, no_header());
  CHECK(strip(once) == kProgram);
  CHECK(count(once, " SEAL=") == 1);
  CHECK(count(once, "CK=") == 0);
  std::string upper = once;
  for (char& c : upper)
    if (c >= 'a' && c <= 'z') c = char(c - 'a' + 'A');
  std::string program_upper = kProgram; // already upper case: the annotations' units are not
  CHECK(strip(upper) == program_upper);
  // A program whose only comments of that form are the user's (no SEAL field covers them) keeps
  // them, whatever their number.
  const std::string note = inline_annotation(once, "G1 X80 F300");
  std::string moved = kProgram;
  moved.replace(moved.find("G1 Y60\n"), 7, "G1 Y60" + note + "\n");
  CHECK(strip(moved) == moved);
}

TEST_CASE("a file mixing annotations of several runs: annotate takes out what strip takes out") {
  const std::string with_header = annotated(kProgram);
  const std::string without = annotated(kOther, std::nullopt, no_header());
  // The seal line twice (a line duplicated in an editor), then the comments of a file annotated
  // without a header after the program's end: the seal no longer covers them all, and every
  // comment of the form goes.
  const std::string mixed = first_line(with_header, "(NCJ SEAL ") + "\n" + with_header + without;
  CHECK(strip(mixed) == std::string(kProgram) + kOther);
  EstimateOptions estimate_options;
  estimate_options.simulate_removal = false;
  for (const AnnotateOptions& options : {AnnotateOptions{}, no_header()}) {
    const AnnotatedProgram once =
        annotate_program("mixed.ngc", mixed, machine(), estimate_options, options);
    CHECK(strip(once.text) == strip(mixed));
    CHECK(annotate_program("mixed.ngc", once.text, machine(), estimate_options, options).text ==
          once.text);
  }
}

TEST_CASE("a program of many thousand lines (written in chunks on several threads) seals and "
          "strips as a short one") {
  // annotate() writes lines in chunks of a few thousand and joins them in order: the seal's sum,
  // the places of the user's comments it keeps, the SEAL field's spot and the output lines the
  // header's warnings name must be those of the whole file. Pasted annotations (to keep) and
  // lines too long for their comment (which get a line of their own) in the first chunk and in
  // later ones; a block with F0 (warned) near the end.
  const std::string pasted = inline_annotation(annotated(kOther), "G1 X40 F500");
  const std::string long_code = "G1 X1 Y1 F400 (" + std::string(240, 'a') + ")";
  std::string program = "G21 G90\nG0 X0 Y0 Z5\n";
  for (int k = 0; k < 10'000; ++k) {
    program += "G1 X" + std::to_string(k % 50) + " Y" + std::to_string(k % 7) + " F300";
    if (k == 3 || k == 5'000 || k == 9'990) program += " (was" + pasted + ")";
    program += '\n';
    if (k == 10 || k == 4'200 || k == 8'500) program += long_code + '\n';
  }
  program += "G1 X10 F0\nM2\n";
  for (const AnnotateOptions& options : {AnnotateOptions{}, no_header()}) {
    const std::string once = annotated(program, std::nullopt, options);
    const StripResult back = strip_checked(once);
    CHECK_FALSE(back.by_form); // the seal covers exactly the file's own comments
    CHECK(back.text == program);
    CHECK(count(once, "(was" + pasted + ")") == 3);
    CHECK(annotated(once, std::nullopt, options) == once);
    if (!options.header) continue;
    const std::vector<std::string> lines = lines_of(once);
    int warned = 0; // the F0 block's error and warning
    for (const std::string& line : lines) {
      const std::size_t at = line.find(" L", line.find("NCJ WARN"));
      if (line.find("NCJ WARN") == std::string::npos || line.find("feed rate") == std::string::npos)
        continue;
      REQUIRE(at != std::string::npos);
      const int named = std::stoi(line.substr(at + 2));
      REQUIRE(named >= 1);
      REQUIRE(std::size_t(named) <= lines.size());
      CHECK(lines[std::size_t(named) - 1].rfind("G1 X10 F0", 0) == 0);
      ++warned;
    }
    CHECK(warned == 2);
  }
}
