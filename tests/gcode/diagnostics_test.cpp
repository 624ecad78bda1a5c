// What the interpreter says about programs it cannot fully honour, how dwell times are read in
// each dialect, and how the dialect is guessed.
#include <doctest/doctest.h>

#include "program_runner.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("unknown G and M codes warn with file, line and column, the motion still counts") {
  const Toolpath p = run("G21 G0 X0 Y0\n  G1 G300 X5 F100\nM200\nM2\n");
  CHECK(errors(p) == 0);
  const auto w = with_severity(p, Severity::Warning);
  REQUIRE(w.size() == 2);
  CHECK(w[0].file == "test.ngc");
  CHECK(w[0].line == 2);
  CHECK(w[0].column == 6);
  CHECK(w[0].message.find("G300") != std::string::npos);
  CHECK(format_diagnostic(w[0]).rfind("test.ngc:2:6: warning: ", 0) == 0);
  CHECK(w[1].line == 3);
  CHECK(w[1].message.find("M200") != std::string::npos);
  CHECK(moves(p).back() == "STRAIGHT_FEED(5.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  CHECK(p.result.completed);
}

TEST_CASE("bad G numbers and bare words are errors and skip the block: stray characters warn") {
  const Toolpath p = run("G21\nG0 X1 Y\nG0 X2 (open comment\nG0 X3 &\nG1.55 X4\nG0 X5\nM2\n");
  const auto e = with_severity(p, Severity::Error);
  REQUIRE(e.size() == 2);
  CHECK(e[0].line == 2); // "Y" with no value: rs274 refuses the block too
  CHECK(e[0].column == 7);
  CHECK(e[1].line == 5);
  CHECK(e[1].column == 1);
  const auto w = with_severity(p, Severity::Warning);
  REQUIRE(w.size() == 2);
  CHECK(w[0].line == 3);
  CHECK(w[0].column == 7);
  CHECK(w[0].message.find("')'") != std::string::npos);
  CHECK(w[1].line == 4);
  CHECK(w[1].column == 7);
  CHECK(moves(p) == std::vector<std::string>{
                        "STRAIGHT_TRAVERSE(2.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
                        "STRAIGHT_TRAVERSE(3.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
                        "STRAIGHT_TRAVERSE(5.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)"});
}

TEST_CASE("typos every control refuses are errors with line and column in every dialect") {
  // The letter O for a zero (F1O8. read as F1 turned a 38 s program into 32 minutes), two
  // decimal points, a word with no value: rs274 refuses each ("Bad character 'o' used", "bad
  // number format", "No characters found in reading real value"), Fanuc and Haas alarm.
  struct Case {
    const char* line;
    int column;
    const char* quoted;
  };
  for (const char* dialect : {"linuxcnc", "fanuc", "haas", "grbl", "mach3", "siemens"}) {
    for (const Case c :
         {Case{"G1 Z-0.03 F1O8.", 13, "'F1O8.'"}, Case{"G1 X0..2 F100", 4, "'X0..2'"},
          Case{"G1 X1.2.3 F100", 4, "'X1.2.3'"}, Case{"G1 X F100", 4, "'X'"}}) {
      CAPTURE(dialect);
      CAPTURE(c.line);
      const Toolpath p =
          run(std::string("G21 G90 G0 X0 Y0 Z1 F100\n") + c.line + "\nM2\n", dialect);
      const auto e = with_severity(p, Severity::Error);
      REQUIRE(e.size() == 1);
      CHECK(e[0].line == 2);
      CHECK(e[0].column == c.column);
      CHECK(e[0].message.find(c.quoted) != std::string::npos);
      CHECK(moves(p).size() == 1); // the block is not run: no move at F1, to X0 or to X0.2
    }
  }
  // With no dialect named or recognised, a letter alone and two points are warnings (the
  // program may be Marlin's: MPCNC posts write "G28 Z" and "M0 Turn ON spindle"); an O inside a
  // number is a typo whatever the control.
  const Toolpath unnamed =
      run("G21\nG28 Z\nM0 Turn ON spindle\nG1 X0..2 F100\nG1 X5 F1O8.\nM2\n", "");
  const auto unnamed_errors = with_severity(unnamed, Severity::Error);
  REQUIRE(unnamed_errors.size() == 1);
  CHECK(unnamed_errors[0].line == 5);
  CHECK_FALSE(with_severity(unnamed, Severity::Warning).empty());
  // Marlin reads them (a letter alone is a flag: "G28 X Y"; the rest of a number is skipped).
  const Toolpath marlin = run("G21\nG28 X Y\nG1 X5 F1O8.\nM2\n", "reprap");
  CHECK(errors(marlin) == 0);
  CHECK(moves(marlin).size() >= 1);
}

TEST_CASE("a program without M2/M30 warns at its last line") {
  const Toolpath p = run("G21\nG0 X1\n");
  const auto w = with_severity(p, Severity::Warning);
  REQUIRE(w.size() == 1);
  CHECK(w[0].line == 2);
  CHECK(p.result.completed);
}

TEST_CASE("a loop gives each of its blocks' diagnostics once, whatever the passes") {
  const Toolpath p = run("G21\n#1=0\no100 while [#1 LT 5]\nG0 G300 X#1\nM200\n#1=[#1+1]\n"
                         "o100 endwhile\nM2\n");
  const auto w = with_severity(p, Severity::Warning);
  REQUIRE(w.size() == 2);
  CHECK(w[0].line == 4);
  CHECK(w[0].message.find("G300") != std::string::npos);
  CHECK(w[1].line == 5);
  CHECK(moves(p).size() == 5);
}

TEST_CASE("a pass that keeps no diagnostics gives the same commands and the same ending") {
  for (const std::string text :
       {std::string("G21\nG0 G300 X1\nG1 X2 F100\nM2\n"),
        std::string("G21\nG0 X1\nG1.55 X4\nG0 X5\n"), std::string("G21\nG0 X1\n")}) {
    const SourceFile source = make_source("test.ngc", text);
    InterpreterOptions options;
    options.dialect = find_dialect("linuxcnc");
    const Toolpath kept = interpret(source, options);
    options.keep_diagnostics = false;
    const Toolpath quiet = interpret(source, options);
    CAPTURE(text);
    CHECK_FALSE(kept.result.diagnostics.empty());
    CHECK(quiet.result.diagnostics.empty());
    CHECK(canon(quiet) == canon(kept));
    CHECK(quiet.result.completed == kept.result.completed);
  }
}

TEST_CASE("dwell units per dialect") {
  auto dwell = [](const std::string& text, const std::string& dialect) {
    const auto d = of_kind(run(text, dialect), CanonKind::Dwell);
    return d.empty() ? -1.0 : d[0].value;
  };
  // LinuxCNC: P in seconds.
  CHECK(dwell("G4 P1.5\nM2\n", "linuxcnc") == doctest::Approx(1.5));
  CHECK(dwell("G4 P2\nM2\n", "linuxcnc") == doctest::Approx(2.0));
  // Fanuc: P in milliseconds, X in seconds.
  CHECK(dwell("G4 P1500\nM30\n", "fanuc") == doctest::Approx(1.5));
  CHECK(dwell("G4 X2.5\nM30\n", "fanuc") == doctest::Approx(2.5));
  // Haas: an integer P is milliseconds, a P with a decimal point seconds.
  CHECK(dwell("G4 P1000\nM30\n", "haas") == doctest::Approx(1.0));
  CHECK(dwell("G4 P1.5\nM30\n", "haas") == doctest::Approx(1.5));
  CHECK(dwell("G4 P2.\nM30\n", "haas") == doctest::Approx(2.0));
  // G82's P follows the same rule as G4's in Fanuc.
  const auto d =
      of_kind(run("G21 G0 Z5\nG98 G82 X1 Z-1 R1 P500 F100\nM30\n", "fanuc"), CanonKind::Dwell);
  REQUIRE(d.size() == 1);
  CHECK(d[0].value == doctest::Approx(0.5));
  CHECK(format_canon(d[0]) == "DWELL(0.5000)");
  // A dwell without its time is an error.
  CHECK(errors(run("G4\nM2\n")) == 1);
}

TEST_CASE("a family's own M codes are read without a warning in its dialect") {
  // A Haas program's chip auger, through-spindle coolant and air blast; a Fanuc 4th axis's
  // clamp; Marlin's motors-off and finish-moves.
  const std::string haas = "G20\nM31\nM88\nG0 X1\nM89\nM83\nM84\nM33\nM10\nM11\nM30\n";
  CHECK(warnings(run(haas, "haas")) == 0);
  CHECK(warnings(run(haas, "linuxcnc")) == 8); // a LinuxCNC control knows none of them
  CHECK(warnings(run(haas, "fanuc")) == 6);    // a Fanuc knows the clamp only
  // Marlin streams a program with no end code: that is a note there, a warning elsewhere.
  const std::string marlin = "G21\nM17\nG0 X1\nM400\nM84\n";
  CHECK(warnings(run(marlin, "reprap")) == 0);
  CHECK(notes(run(marlin, "reprap")) >= 1);
  CHECK(warnings(run(marlin, "linuxcnc")) == 4);
  // A code outside the family's list is still unknown.
  const Toolpath odd = run("G20\nM31\nM87\nM30\n", "haas");
  REQUIRE(warnings(odd) == 1);
  CHECK(with_severity(odd, Severity::Warning)[0].message.find("M87") != std::string::npos);
}

TEST_CASE("dialect detection") {
  auto detect = [](const std::string& text) {
    return detect_dialect(make_source("x.nc", text)).name;
  };
  CHECK(detect("G21\nG0 X1\nM2\n") == "linuxcnc");
  CHECK(detect("o<pocket> sub\nG0 X1\no<pocket> endsub\nM2\n") == "linuxcnc");
  CHECK(detect("%\nO1234 (PART)\nG21\nM98 P2000\nM30\n%\n") == "fanuc");
  CHECK(detect("%\nO1234 (HAAS VF2)\nG187 P1\nM30\n%\n") == "haas");
  CHECK(detect("$110=500\nG21 G0 X1\n") == "grbl");
  CHECK(detect("(Mach3 post)\nG21\n") == "mach3");
  // Haas's own chip-auger and through-spindle-coolant codes tell a Haas post (Fusion's Haas
  // posts write neither "HAAS" nor G187); M310 or a word ending in "m31" do not.
  CHECK(detect("%\nO1234 (PART)\nG20\nM31\nM30\n%\n") == "haas");
  CHECK(detect("%\nO1234 (PART)\nG20\nM88\nM30\n%\n") == "haas");
  CHECK(detect("%\nO1234 (PART)\nG20\nM310\nM30\n%\n") == "fanuc");
  CHECK(detect("%\nO1234 (PROGRAM31)\nG20\nM30\n%\n") == "fanuc");
  CHECK(describe_dialect_choice(choose_dialect(make_source("x.nc", "O1\nM88\nM30\n"))) ==
        "haas (detected: Haas code M88 at line 2)");
  // The detected dialect is the one used when none is given.
  const Toolpath p = run("O0001\nG4 P2000\nM30\n", "");
  CHECK(p.result.dialect.name == "fanuc");
  CHECK(of_kind(p, CanonKind::Dwell)[0].value == doctest::Approx(2.0));
  CHECK(find_dialect("Sinumerik")->name == "siemens");
  CHECK(find_dialect("heidenhain")->name == "heidenhain");
  CHECK(find_dialect("Marlin")->name == "reprap");
  CHECK_FALSE(find_dialect("okuma").has_value());
  CHECK(detect("; Sinumerik 840D\nG17 G90\nMCALL CYCLE81(10,0,2,-5)\n") == "siemens");
  CHECK(detect("%PART G71 *\nN10 G00 X+0 *\n") == "heidenhain");
  // ncjoule's own annotations name a dialect: they do not count.
  CHECK(detect("(NCJ MACHINE DIALECT=fanuc CK=ABCDEF)\nG21\nG0 X1 (NCJ T=1s CK=ABCDEF)\n") ==
        "linuxcnc");
  // Free text in comments names no dialect: a customer's, a part's or a machine's name is not
  // the post's signature. A LinuxCNC program with a Haas note keeps G4 P in seconds.
  std::string linuxcnc = "G21 G90\n";
  for (int i = 0; i < 300; ++i)
    linuxcnc += "G1 X" + std::to_string(i % 10) + " F300\n";
  linuxcnc += "(OP 7: HOLES FOR THE HAAS TRUNNION ADAPTER)\nG4 P5\nM2\n";
  CHECK(detect(linuxcnc) == "linuxcnc");
  CHECK(of_kind(run(linuxcnc, ""), CanonKind::Dwell)[0].value == doctest::Approx(5.0));
  // A Fusion Haas program with a customer's name in its header: Haas, by the post's machine
  // block, never Sinumerik.
  const std::string fusion_haas = "%\nO1023\n(CUSTOMER: SIEMENS AG - BRACKET)\n(Machine)\n"
                                  "(  vendor: HAAS)\n(  model: VF-2)\nG90 G94 G17\nG20\n"
                                  "G0 X1. Y1.\nM30\n%\n";
  CHECK(describe_dialect_choice(choose_dialect(make_source("x.nc", fusion_haas))) ==
        "haas (detected: 'haas' in the post's machine block at line 5)");
  CHECK(detect("%\nO1023\n(CUSTOMER: SIEMENS AG - BRACKET)\nG20\nG0 X1.\nM30\n%\n") == "fanuc");
  CHECK(detect("%\nO1234\n(MARLIN BRACKET REV B)\nG21\nG0 X1.\nM30\n%\n") == "fanuc");
  // The post's own signature does name it, in the header only.
  CHECK(detect("(Post Processor: HAAS VF series)\nG20\nG0 X1.\nM30\n") == "haas");
  CHECK(detect("G20\nG0 X1.\n(Post Processor: HAAS VF series)\nM30\n") == "linuxcnc");
  // Sinumerik's own words, without a name anywhere.
  CHECK(detect("; warm-up\nEXTERN WARMUP(REAL)\nG70 G90\nG0 SUPA Z0\nM2\n") == "siemens");
  // Why: the first clue, with its line.
  const DialectChoice c = choose_dialect(make_source("x.nc", "%\nO1001 (PART)\nG21\nM30\n"));
  CHECK(c.origin == DialectOrigin::Detected);
  CHECK(describe_dialect_choice(c) == "fanuc (detected: O-number program header at line 2)");
  CHECK(choose_dialect(make_source("x.nc", "G21\nG0 X1\n")).origin == DialectOrigin::Default);
  // A machine's own control takes over where nothing names a dialect, never over a clue.
  InterpreterOptions haas;
  haas.fallback_dialect = find_dialect("haas");
  CHECK(interpret(make_source("x.nc", "G21\nG4 P1000\nM30\n"), haas).result.dialect.name == "haas");
  CHECK(interpret(make_source("x.nc", "o<a> sub\no<a> endsub\nM2\n"), haas).result.dialect.name ==
        "linuxcnc");
  CHECK(detect("(Post Processor: PathScripts.post.marlin_post.py)\nG21\n") == "reprap");
  CHECK(detect("(POST PROCESSOR: PATHSCRIPTS.POST.FANUC_POST)\nG21\n") == "fanuc");
}

TEST_CASE(
    "comment syntax is dialect data: the semicolon ends the block on Fanuc, comments on LinuxCNC") {
  CHECK(errors(run("G21 G0 X1 ; move\nM2\n", "linuxcnc")) == 0);
  // Fanuc: ';' is the end of block; text after it is warned about and not run.
  const Toolpath f = run("G21 G0 X1 ; move\nG0 X2;\nM30\n", "fanuc");
  CHECK(errors(f) == 0);
  CHECK(with_severity(f, Severity::Warning).size() == 1);
  CHECK(moves(f).size() == 2);
  const Toolpath msg = run("(MSG, tool change next)\nM2\n");
  const auto m = of_kind(msg, CanonKind::Message);
  REQUIRE(m.size() == 1);
  CHECK(format_canon(m[0]) == "MESSAGE(\" tool change next\")");
}

TEST_CASE("block delete is honoured only when asked for") {
  const SourceFile s = make_source("bd.ngc", "G21\n/G0 X1\nG0 Y1\nM2\n");
  InterpreterOptions o;
  CHECK(moves(interpret(s, o)).size() == 2);
  o.block_delete = true;
  CHECK(moves(interpret(s, o)).size() == 1);
}

TEST_CASE("a number with an exponent is an E word: an error as rs274 has it, else a warning") {
  // rs274: "E word with no G70, G76, M66, M67 or M68 to use it".
  const Toolpath strict = run("G21 G0 X0 Y0\nG1 X1e3 F100\nM2\n", "linuxcnc");
  const auto e = with_severity(strict, Severity::Error);
  REQUIRE(e.size() == 1);
  CHECK(e[0].line == 2);
  CHECK(e[0].column == 6);
  CHECK(e[0].message.find("no exponent") != std::string::npos);

  const Toolpath fanuc = run("G21 G0 X0 Y0\nG1 X1e3 F100\nM30\n", "fanuc");
  CHECK(errors(fanuc) == 0);
  const auto w = with_severity(fanuc, Severity::Warning);
  REQUIRE(w.size() == 1);
  CHECK(w[0].message.find("E word ignored") != std::string::npos);
  CHECK(moves(fanuc).back() == "STRAIGHT_FEED(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");

  // Where E has a use, nothing is said.
  CHECK(with_severity(run("G21\nM66 P0 E0 L0\nM2\n", "linuxcnc"), Severity::Warning).empty());
}
