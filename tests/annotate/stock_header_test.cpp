// The header says what stock each setup cut and where it came from: a guessed stock makes every
// volume a guess, so the programmer reads that before the numbers.
#include <doctest/doctest.h>

#include <string>

#include "annotate_helpers.hpp"

using namespace ncjoule;
using namespace annotate_test;

namespace {

// A 6 mm end mill in a 40 x 20 mm pocket, two levels; `head` goes first, `between` between two
// copies of it (a second setup when it says so).
std::string pocket_program(const std::string& head, const std::string& between = "") {
  std::string cut = "G0 Z5\nG0 X3 Y3\nG1 Z-1.5 F200\nG1 X37 F600\nG1 Y17\nG1 X3\nG1 Y3\n"
                    "G1 Z-3 F200\nG1 X37 F600\nG1 Y17\nG1 X3\nG1 Y3\nG0 Z5\n";
  std::string p =
      head + "G21 G90 G17\n(T1 D=6. CR=0. - FLAT END MILL)\nT1 M6\nS8000 M3\nG54\n" + cut;
  if (!between.empty()) p += between + "\n" + cut;
  return p + "M5\nM30\n";
}

std::string annotate_with_removal(const std::string& text, const EstimateOptions& options) {
  const SourceFile source = make_source("part.ngc", text);
  return annotate(source, estimate_program(source, machine(), options), machine(), {});
}

std::string stock_lines(const std::string& annotated_text) {
  std::string out;
  for (const std::string& line : lines_of(annotated_text))
    if (line.find("NCJ STOCK") != std::string::npos || line.find("NCJ SETUP") != std::string::npos)
      out += line + "\n";
  return out;
}

} // namespace

TEST_CASE("a stock guessed from the cuts is said to be, with its box") {
  const std::string lines = stock_lines(annotate_with_removal(pocket_program(""), {}));
  CAPTURE(lines);
  // The box: the extent of the passes (they go round an area 34 x 14 mm, 2.3 tool diameters
  // wide: an area, not a line), from the lower pass up to Z0 (every cut runs below it).
  CHECK(lines.find("BOX_MM=3,3,-3,37,17,0") != std::string::npos);
  CHECK(lines.find("GUESSED FROM CUTS") != std::string::npos);
  CHECK(lines.find("NCJ SETUP") == std::string::npos); // one setup: no setup lines
}

TEST_CASE("a given stock and a CAM comment's stock are said to be so") {
  EstimateOptions given;
  given.stock = parse_stock_spec("box:-5,-5,-10,45,25,0");
  const std::string a = stock_lines(annotate_with_removal(pocket_program(""), given));
  CAPTURE(a);
  CHECK(a.find("BOX_MM=-5,-5,-10,45,25,0 GIVEN") != std::string::npos);
  // Carbide Create's stock comments, in inches inside a mm program: their own unit holds.
  const std::string b = stock_lines(annotate_with_removal(
      pocket_program("(stockMin:-0.2in, -0.2in, -0.5in)\n(stockMax:1.8in, 1in, 0.00in)\n"), {}));
  CAPTURE(b);
  CHECK(b.find("BOX_MM=-5.08,-5.08,-12.7,45.72,25.4,0 FROM CAM COMMENTS") != std::string::npos);
  // A stock given wins over the comments.
  const std::string c = stock_lines(annotate_with_removal(
      pocket_program("(stockMin:-0.2in, -0.2in, -0.5in)\n(stockMax:1.8in, 1in, 0.00in)\n"), given));
  CHECK(c.find("GIVEN") != std::string::npos);
}

TEST_CASE("two setups: a stock line and a setup line for each") {
  const std::string lines =
      stock_lines(annotate_with_removal(pocket_program("", "M0 (FLIP PART)\nG55"), {}));
  CAPTURE(lines);
  CHECK(count(lines, "NCJ STOCK SETUP=") == 2);
  CHECK(lines.find("NCJ SETUP N=1 LINE=1 ") != std::string::npos);
  CHECK(lines.find("NCJ SETUP N=2 ") != std::string::npos);
  CHECK(lines.find("FROM=M0_at_line") != std::string::npos);
  // Each setup removed its own pocket level (the second is not air cutting in the first's hole).
  CHECK(count(lines, "VOL_MM3=0 ") == 0);
}

TEST_CASE("the TOTAL line says what its numbers rest on that nobody gave") {
  auto total_lines = [](const std::string& text) {
    std::string out;
    for (const std::string& line : lines_of(text))
      if (line.find("NCJ TOTAL") != std::string::npos) out += line + "\n";
    return out;
  };
  // A guessed stock: said; a given one: not.
  const std::string guessed = total_lines(annotate_with_removal(pocket_program(""), {}));
  CHECK((guessed.find("GUESSED=STOCK ") != std::string::npos ||
         guessed.find("GUESSED=STOCK)") != std::string::npos));
  EstimateOptions given;
  given.stock = parse_stock_spec("box:-5,-5,-10,45,25,0");
  CHECK(total_lines(annotate_with_removal(pocket_program(""), given)).find("GUESSED") ==
        std::string::npos);
  // A tool nothing describes (T2), and the generic machine standing in for an unnamed one.
  const std::string undescribed = "G21 G90\nT2 M6\nS8000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F200\n"
                                  "G1 X30 F600\nG0 Z5\nM30\n";
  MachineProfile unnamed = machine();
  unnamed.by_default = true;
  const SourceFile source = make_source("part.ngc", undescribed);
  const std::string both =
      total_lines(annotate(source, estimate_program(source, unnamed, given), unnamed, {}));
  CAPTURE(both);
  CHECK((both.find("GUESSED=TOOLS-MACHINE ") != std::string::npos ||
         both.find("GUESSED=TOOLS-MACHINE)") != std::string::npos));
}
