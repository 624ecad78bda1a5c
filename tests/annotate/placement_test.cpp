// Where annotations go: before a line's comments (so LinuxCNC's MSG stays the last comment),
// the header after % and O-number lines, subtotals on tool-change lines.
#include <doctest/doctest.h>

#include <cstdlib>
#include <string>

#include "annotate_helpers.hpp"
#include "header.hpp"
#include "line_layout.hpp"

using namespace ncjoule;
using namespace annotate_test;

namespace {

AnnotateOptions no_header() {
  AnnotateOptions o;
  o.header = false;
  return o;
}

// The value of `key=` in an annotation, as a number in the unit the suffix names (s, J).
double field_value(const std::string& line, const std::string& key) {
  const std::size_t at = line.find(" " + key + "=");
  REQUIRE(at != std::string::npos);
  const char* p = line.c_str() + at + key.size() + 2;
  char* end = nullptr;
  double v = std::strtod(p, &end);
  if (*end == 'm' && end[1] != 'J' && key != "MRR") { // 1m05s
    v = v * 60 + std::strtod(end + 1, &end);
  } else if (*end == 'k') {
    v *= 1000;
  } else if (*end == 'M') {
    v *= 1e6;
  }
  return v;
}

} // namespace

TEST_CASE("the annotation goes before existing comments: MSG stays the last comment") {
  const std::string original =
      "G21 G90\nG0 X1 (MSG, hello there)\nG1 X2 F100 (first)(DEBUG, x=#<_x>)\nG1 X3 ;note\nM2\n";
  const auto after = lines_of(annotated(original, std::nullopt, no_header()));
  REQUIRE(after.size() == 5);
  CHECK(after[1].rfind("G0 X1 (NCJ T=", 0) == 0);
  CHECK(after[1].size() > std::string("(MSG, hello there)").size());
  CHECK(after[1].substr(after[1].size() - 18) == "(MSG, hello there)");
  CHECK(after[1].find(") (MSG, hello there)") != std::string::npos);
  CHECK(after[2].rfind("G1 X2 F100 (NCJ T=", 0) == 0);
  CHECK(after[2].find(") (first)(DEBUG, x=#<_x>)") == after[2].size() - 25);
  CHECK(after[3].rfind("G1 X3 (NCJ T=", 0) == 0);
  CHECK(after[3].substr(after[3].size() - 6) == " ;note");
}

TEST_CASE(
    "with semicolon comments the annotation goes at the end of the code, after ( ) comments") {
  Dialect semicolon = *find_dialect("linuxcnc");
  semicolon.comment_open = ";";
  semicolon.comment_close = "";
  const std::string original = "G21 G90\nG0 X1 (MSG, hi)\nG1 X2 F100 ; user note\nG1 X3\nM2\n";
  const std::string once = annotated(original, semicolon, no_header());
  CHECK(strip(once) == original);
  CHECK(annotated(once, semicolon, no_header()) == once);
  const auto after = lines_of(once);
  REQUIRE(after.size() == 5);
  CHECK(after[1].rfind("G0 X1 (MSG, hi) ;NCJ T=", 0) == 0); // the MSG keeps working
  CHECK(after[2].rfind("G1 X2 F100 ;NCJ T=", 0) == 0);
  CHECK(after[2].substr(after[2].size() - 12) == " ; user note");
  CHECK(after[3].rfind("G1 X3 ;NCJ T=", 0) == 0);
  CHECK(after[3].find('(') == std::string::npos);
}

TEST_CASE("the header goes after a leading % line and an O-number line, never before") {
  const Dialect fanuc = *find_dialect("fanuc");
  // The key first, then the totals.
  const auto with_both = lines_of(annotated("%\nO1234 (PART)\nG21 G90\nG00 X1.\nM30\n%\n", fanuc));
  CHECK(with_both[0] == "%");
  CHECK(with_both[1] == "O1234 (PART)");
  CHECK(with_both[2].rfind("(NCJ SEAL ", 0) == 0);
  CHECK(with_both[3].rfind("(NCJ TOTAL T=", 0) == 0);

  const auto o_only = lines_of(annotated("O0002\nG21 G90\nG00 X1.\nM30\n", fanuc));
  CHECK(o_only[0] == "O0002");
  CHECK(o_only[1].rfind("(NCJ SEAL ", 0) == 0);

  const auto percent_only = lines_of(annotated("%\nG21 G90\nG0 X1\nM2\n%\n"));
  CHECK(percent_only[0] == "%");
  CHECK(percent_only[1].rfind("(NCJ SEAL ", 0) == 0);

  const auto neither = lines_of(annotated("G21 G90\nG0 X1\nM2\n"));
  CHECK(neither[0].rfind("(NCJ SEAL ", 0) == 0);

  // LinuxCNC's "o100 sub" is a control word, not a program number.
  CHECK_FALSE(annotation::is_program_number_line("o100 sub"));
  CHECK(annotation::is_program_number_line("O0100 (NAME)"));
  CHECK(annotation::is_program_number_line(":1234"));
}

TEST_CASE("the program's title comment after % and the O-number stays first, the header follows") {
  const Dialect fanuc = *find_dialect("fanuc");
  // A title on a line of its own: controls and DNC lists show the first comment as the name.
  const auto titled = lines_of(annotated("%\nO1234\n(BRACKET REV B)\n(T1 D=6.)\nG21 G90\n"
                                         "G00 X1.\nM30\n%\n",
                                         fanuc));
  CHECK(titled[1] == "O1234");
  CHECK(titled[2] == "(BRACKET REV B)");
  CHECK(titled[3].rfind("(NCJ SEAL ", 0) == 0);
  // With the name on the O-number line, the next comment is the post's, not a title.
  const auto named = lines_of(annotated("%\nO1234 (BRACKET)\n(T1 D=6.)\nG21 G90\nG00 X1.\n"
                                        "M30\n%\n",
                                        fanuc));
  CHECK(named[2].rfind("(NCJ SEAL ", 0) == 0);
  // A Mach3 post's "%" then "(1001)" then "(PART)": the first comment after '%' is the title.
  const auto mach = lines_of(annotated("%\n(1001)\n(PART)\nG21 G90\nG0 X1\nM30\n%\n"));
  CHECK(mach[1] == "(1001)");
  CHECK(mach[2].rfind("(NCJ SEAL ", 0) == 0);
  // Without a % or O-number line, no title: the header is first.
  const auto plain = lines_of(annotated("(PART)\nG21 G90\nG0 X1\nM2\n"));
  CHECK(plain[0].rfind("(NCJ SEAL ", 0) == 0);
}

TEST_CASE("the header names the totals, the components, the machine and the per-axis constants") {
  const std::string once = annotated("G21 G90\nS1000 M3\nG0 X10 Y10\nG1 X50 F300\nM5\nM2\n");
  for (const char* key :
       {"(NCJ TOTAL T=", " E=", " E_KWH=", " TARE=", " SPINDLE=", " AXIS_X=", " CUTTING=",
        " NAME=Generic_3-axis_VMC", " MODEL=combined", " x.move_ka_w=", " y.move_kb_w_per_mm_s=",
        " z.move_ka_w=", " zhou.c3=", " zhou.c4=", "(NCJ KEYS"}) {
    CAPTURE(key);
    CHECK(once.find(key) != std::string::npos);
  }
  // The profile's value, written with 4 significant digits.
  const double kb = machine().power.pavanaskar.move_kb_w_per_mm_s[0];
  const std::size_t at = once.find(" x.move_kb_w_per_mm_s=");
  REQUIRE(at != std::string::npos);
  CHECK(std::strtod(once.c_str() + at + 22, nullptr) == doctest::Approx(kb).epsilon(1e-3));
}

TEST_CASE("tool changes carry their operation's subtotal, named after the CAM comment") {
  const std::string original = "G21 G90\n"
                               "(Facing)\n"
                               "T1 M6\n"
                               "S2000 M3\n"
                               "G0 X0 Y0 Z5\n"
                               "G1 Z-1 F200\n"
                               "G1 X80\n"
                               "G0 Z5\n"
                               "M5\n"
                               "(2D Pocket1)\n"
                               "M9\n"
                               "T2 M6\n"
                               "S3000 M3\n"
                               "G0 X20 Y20\n"
                               "G1 Z-2 F100\n"
                               "G2 X20 Y20 I5 J0 F400\n"
                               "G0 Z10\n"
                               "T3 M6 (Drill 5mm)\n"
                               "G0 X1\n"
                               "M2\n";
  const SourceFile source = make_source("ops.ngc", original);
  const Estimate e = estimate(source);
  const std::string once = annotate(source, e, machine(), no_header());
  const auto after = lines_of(once);
  REQUIRE(after.size() == 20);
  CHECK(after[2].find(" OP=Facing ") != std::string::npos);
  CHECK(after[11].find(" OP=2D_Pocket1 ") != std::string::npos);
  CHECK(after[17].find(" OP=Drill_5mm ") != std::string::npos);
  CHECK(after[17].find("(Drill 5mm)") != std::string::npos);
  // The subtotal is the sum of the blocks from this tool change up to the next one, checked
  // against the estimate's own per-line results.
  double facing_s = 0, facing_j = 0;
  for (const LineSummary& s : e.lines)
    if (s.line >= 2 && s.line < 11) {
      facing_s += s.time_s;
      facing_j += s.energy_j;
    }
  CHECK(facing_s > 6); // the tool change itself takes 6 s on this machine
  CHECK(field_value(after[2], "OPT") == doctest::Approx(facing_s).epsilon(0.006));
  CHECK(field_value(after[2], "OPE") == doctest::Approx(facing_j).epsilon(0.006));
  // Only tool-change lines carry OP.
  CHECK(count(once, " OP=") == 3);
}

TEST_CASE("a block's numbers are the estimate's, and CUM is the time when it ends") {
  const std::string original = "G21 G90\nG0 X10 Y10 Z5\nG1 Z-1 F60\nG1 X100 F1200\nM2\n";
  const SourceFile source = make_source("t.ngc", original);
  const Estimate e = estimate(source);
  const auto after = lines_of(annotate(source, e, machine(), no_header()));
  double cumulative = 0;
  for (const LineSummary& s : e.lines) {
    if (!s.has_move) continue;
    cumulative += s.time_s;
    const std::string& line = after[static_cast<std::size_t>(s.line)];
    CAPTURE(line);
    CHECK(field_value(line, "T") == doctest::Approx(s.time_s).epsilon(0.006));
    CHECK(field_value(line, "E") == doctest::Approx(s.energy_j).epsilon(0.006));
    CHECK(field_value(line, "P") == doctest::Approx(s.energy_j / s.time_s).epsilon(0.006));
    CHECK(field_value(line, "CUM") == doctest::Approx(cumulative).epsilon(0.006));
  }
  // G1 Z-1 F60 over 6 mm at 1 mm/s, less the 0.51 mm the blend arc into G1 X100 takes from its
  // end (LinuxCNC's rule, which the generic profile uses, charges that arc to the next line).
  CHECK(field_value(after[2], "T") >= 5.45);
  CHECK(field_value(after[2], "T") <= 6.0);
}

TEST_CASE("the header splits the time and has one line per operation, inch programs in inches") {
  const std::string two_ops = "G21 G90\n(Facing)\nT1 M6\nS2000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F200\n"
                              "G1 X80\nG0 Z5\n(2D Pocket1)\nT2 M6\nS3000 M3\nG0 X20 Y20\n"
                              "G1 Z-2 F100\nG4 P2\nG0 Z10\nM2\n";
  const std::string once = annotated(two_ops);
  for (const char* key :
       {"(NCJ TIME RAPID=", " CUT=", " AIR=unknown", " TOOL_CHANGE=", " DWELL=2s", " MRR_MM3_S="}) {
    CAPTURE(key);
    CHECK(once.find(key) != std::string::npos);
  }
  CHECK(once.find("VOL_IN3") == std::string::npos); // a metric program
  std::vector<std::string> ops;
  for (const std::string& line : lines_of(once))
    if (line.rfind("(NCJ OP ", 0) == 0) ops.push_back(line);
  REQUIRE(ops.size() == 2);
  CHECK(ops[0].find("N=1 NAME=Facing TOOL=T1 T=") != std::string::npos);
  CHECK(ops[1].find("N=2 NAME=2D_Pocket1 TOOL=T2 T=") != std::string::npos);
  CHECK(ops[1].find("SHARE_PCT=") != std::string::npos);
  CHECK(once.find('%') == std::string::npos); // '%' ends a Fanuc tape, even in a comment

  const std::string inch = annotated("G20 G90\nT1 M6\nS2000 M3\nG0 X0 Y0 Z0.2\nG1 Z-0.04 F8\n"
                                     "G1 X3\nG0 Z0.2\nM2\n");
  CHECK(inch.find(" VOL_IN3=") != std::string::npos);
  CHECK(inch.find(" MRR_IN3_MIN=") != std::string::npos);
}

TEST_CASE("a header warning names its block's line in the annotated file, past the header") {
  const std::string out = annotated("%\nG21 G90\nG0 X0 Y0 Z5\nG1 X10 F0\nG1 Y10 F0\nM2\n%\n");
  const std::vector<std::string> lines = lines_of(out);
  int warned = 0;
  for (const std::string& line : lines) {
    const std::size_t at = line.find("NCJ WARN L");
    if (at == std::string::npos) continue;
    const int named = std::stoi(line.substr(at + 10));
    CAPTURE(line);
    REQUIRE(named >= 1);
    REQUIRE(static_cast<std::size_t>(named) <= lines.size());
    // The named line of the output is the first block the warning concerns: "G1 X10 F0".
    CHECK(lines[named - 1].rfind("G1 X10 F0", 0) == 0);
    ++warned;
  }
  CHECK(warned == 1);
  CHECK(lines[0] == "%");
  CHECK(lines[1].rfind("(NCJ SEAL ", 0) == 0); // the header: between the % line and the program
}

TEST_CASE("a header warning reads in words: a model's formula by its name, units with 'per'") {
  const annotation::WriteStyle style{annotation::comment_style(*find_dialect("linuxcnc")), 200};
  const std::vector<std::string> lines = annotation::warning_lines(
      {{"", 0,
        "the cutting term c3*n^c4*MRR was fitted on MRR 3-48 mm^3/s; this program removes up to "
        "362 mm^3/s (7.5x the highest): its cutting power is extrapolated",
        1},
       {"", 0, "the idle spindle line c1 + c2*n was fitted at 500-2100 rpm", 1}},
      style, [](int line) { return line; });
  REQUIRE(lines.size() == 2);
  CAPTURE(lines[0]);
  CHECK(lines[0].find("cutting term was fitted on MRR 3-48 mm3 per s") != std::string::npos);
  CHECK(lines[0].find("c3 nc4") == std::string::npos);
  CHECK(lines[0].find("mm3-s") == std::string::npos);
  CHECK(lines[1].find("the idle spindle line was fitted at 500-2100 rpm") != std::string::npos);
}
