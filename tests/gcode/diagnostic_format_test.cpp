// What a diagnostic prints: nothing that can drive a terminal or reorder the text it is read in,
// and never a whole 10 MB word.
#include <doctest/doctest.h>

#include <string>

#include "ncjoule/diagnostic.hpp"

using namespace ncjoule;

namespace {

std::string printed(std::string file, std::string message) {
  return format_diagnostic({Severity::Warning, std::move(file), 3, 7, std::move(message)});
}

} // namespace

TEST_CASE("control bytes, C1 controls and bidirectional overrides are printed escaped") {
  using namespace std::string_literals;
  CHECK(printed("p.ngc", "unknown word 'A\x1b[31mB'") ==
        "p.ngc:3:7: warning: unknown word 'A\\x1b[31mB'");
  CHECK(printed("p.ngc", "a \0 b"s) == "p.ngc:3:7: warning: a \\x00 b");
  // U+202E (right-to-left override) would show "gn.txe" as "exe.ng": escaped by its number.
  CHECK(printed("p.ngc", "word '\xe2\x80\xae"
                         "cgn.exe'") == "p.ngc:3:7: warning: word '\\u{202e}cgn.exe'");
  CHECK(printed("p.ngc", "isolate \xe2\x81\xa6x\xe2\x81\xa9") ==
        "p.ngc:3:7: warning: isolate \\u{2066}x\\u{2069}");
  CHECK(printed("p.ngc", "c1 \xc2\x9b"
                         "31m") == "p.ngc:3:7: warning: c1 \\u{9b}31m"); // CSI
  // Bytes that are not UTF-8 (a Latin-1 accent) are escaped; real UTF-8 letters are kept.
  CHECK(printed("p.ngc", "caf\xe9 Fr\xc3\xa4se") == "p.ngc:3:7: warning: caf\\xe9 Fr\xc3\xa4se");
  // The file name is printed the same way: it comes from the user too.
  CHECK(printed("\xe2\x80\xae"
                "evil\x1b.ngc",
                "m") == "\\u{202e}evil\\x1b.ngc:3:7: warning: m");
}

TEST_CASE("a very long word in a message is cut, with the number of bytes left out") {
  const std::string word(10'000'000, 'X');
  const std::string out = printed("p.ngc", "unknown word '" + word + "': ignored (the rest runs)");
  CHECK(out.size() < 300);
  CHECK(out.find("more bytes)") != std::string::npos);
  CHECK(out.find("ignored (the rest runs)") != std::string::npos); // what follows is kept
  // A run of 200 is printed whole; the cut keeps 160 and counts the rest.
  const std::string run(200, 'Y');
  CHECK(printed("p.ngc", run) == "p.ngc:3:7: warning: " + run);
  const std::string cut = printed("p.ngc", std::string(300, 'Z'));
  CHECK(cut == "p.ngc:3:7: warning: " + std::string(160, 'Z') + "...(140 more bytes)");
  // A file name is never cut: editors jump to file:line.
  const std::string path = "/" + std::string(300, 'd') + "/p.ngc";
  CHECK(printed(path, "m") == path + ":3:7: warning: m");
  CHECK(printable("a\x1b\xe2\x80\xae"
                  "b") == "a\\x1b\\u{202e}b");
}
