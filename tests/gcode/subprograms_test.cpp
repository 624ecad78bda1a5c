// Subprograms and control flow: LinuxCNC O-words, Fanuc M98/M99, Haas M97 and G65 macro calls.
// The LinuxCNC program's moves are those `rs274 -g` prints for it.
#include <doctest/doctest.h>

#include <cstdio>

#include "program_runner.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

TEST_CASE("o-word sub/call with arguments, nested calls, return value, loops and branches") {
  const std::string program = R"(G21
o<square> sub
  G1 X#1 F100
  o<inner> call [#1*2]
o<square> endsub [#1+10]
o<inner> sub
  G1 Y#1
o<inner> endsub
o<square> call [3]
#100 = #<_value>
G0 X#100
#1 = 0
o1 while [#1 LT 3]
  #1 = [#1 + 1]
  o2 if [#1 EQ 2]
    o1 continue
  o2 endif
  G0 Z#1
o1 endwhile
#2 = 0
o3 do
  #2 = [#2 + 1]
  o4 if [#2 GT 5]
    o3 break
  o4 elseif [#2 EQ 2]
    G0 Y20
  o4 else
    G0 Y[#2]
  o4 endif
o3 while [#2 LT 100]
o5 repeat [2]
  G0 X-1
o5 endrepeat
M2
)";
  const Toolpath p = run(program);
  CHECK(errors(p) == 0);
  CHECK(p.result.completed);
  const std::vector<std::string> expected = {
      F(3, 0, 0),  F(3, 6, 0),  // the call and the nested call with [#1*2]
      T(13, 6, 0),              // the return value [#1+10]
      T(13, 6, 1), T(13, 6, 3), // while, with #1 = 2 skipped by continue
      T(13, 1, 3), T(13, 20, 3), T(13, 3, 3), T(13, 4, 3), T(13, 5, 3), // do-while, if/elseif/else
      T(-1, 5, 3), T(-1, 5, 3)};                                        // repeat [2]
  CHECK(moves(p) == expected);
  // Moves made inside a call point at the call site in the main program.
  const auto m = move_commands(p);
  CHECK(m[1].line == 6);      // G1 Y#1 inside o<inner>
  CHECK(m[1].call_line == 8); // o<square> call [3]
  CHECK(m[2].call_line == 10);
}

TEST_CASE("subroutine locals: #1-#30 are restored after the call") {
  const Toolpath p = run("G21\no100 sub\n#1=7\n#<local>=1\no100 endsub\n#1=2\no100 call [5]\n"
                         "G0 X#1\nM2\n");
  CHECK(errors(p) == 0);
  CHECK(moves(p) == std::vector<std::string>{T(2, 0, 0)});
}

TEST_CASE("a call to a subroutine or macro not in the file is a warning, the run goes on") {
  // LinuxCNC reads o<missing> from its subroutine path, a Fanuc or Haas control holds O9810 and
  // O9100 in its memory: the controller runs these programs, so they are not refused.
  const Toolpath p = run("G21\n  o<missing> call\nG0 X1\nM2\n");
  CHECK(errors(p) == 0);
  const auto w = with_severity(p, Severity::Warning);
  REQUIRE(w.size() == 1);
  CHECK(w[0].line == 2);
  CHECK(w[0].column == 3);
  CHECK(w[0].message.find("not counted") != std::string::npos);
  CHECK(moves(p).size() == 1);
  for (const char* call : {"G65 P9810 X1. F100.", "M98 P9100"}) {
    CAPTURE(std::string(call));
    const Toolpath f =
        run(std::string("O0001\nG21 G90 G0 X0 Y0 Z5\n") + call + "\nG0 X2\nM30\n", "fanuc");
    CHECK(errors(f) == 0);
    CHECK(with_severity(f, Severity::Warning).size() == 1);
    CHECK(moves(f).size() == 2);
  }
  // Haas M97 jumps to an N block of this program: one missing is an alarm on the control.
  CHECK(errors(run("O0001\nG21 G0 X0\nM97 P500\nM30\n", "haas")) == 1);
}

TEST_CASE("Fanuc M98 P L calls an O-number subprogram that ends with M99") {
  const std::string program = "%\nO0001 (MAIN)\nG21 G90\nG0 X0 Y0 Z5\nM98 P1000 L3\nG0 Z10\n"
                              "M30\nO1000 (SUB)\nG91 G1 X10 F200\nG90\nM99\n%\n";
  const Toolpath p = run(program, "fanuc");
  CHECK(errors(p) == 0);
  const std::vector<std::string> expected = {T(0, 0, 5), F(10, 0, 5), F(20, 0, 5), F(30, 0, 5),
                                             T(30, 0, 10)};
  CHECK(moves(p) == expected);
  // P<repeats><program> form: M98 P21000 = twice O1000.
  const Toolpath packed =
      run("O0001\nG21 G0 X0 Y0 Z5\nM98 P21000\nM30\nO1000\nG91 G1 X1 F100\nG90\n"
          "M99\n",
          "fanuc");
  CHECK(moves(packed).size() == 3);
  CHECK(moves(packed).back() == F(2, 0, 5));
}

TEST_CASE("Haas M97 calls a local subprogram at an N number") {
  const std::string program = "O0001\nG21 G0 X0 Y0 Z1\nM97 P100\nM97 P100\nM30\nN100 G91 G1 Y5 "
                              "F100\nG90\nM99\n";
  const Toolpath p = run(program, "haas");
  CHECK(errors(p) == 0);
  const std::vector<std::string> expected = {T(0, 0, 1), F(0, 5, 1), F(0, 10, 1)};
  CHECK(moves(p) == expected);
  CHECK(errors(run("O1\nM97 P200\nM30\n", "haas")) == 1);
}

TEST_CASE("G65 passes letter arguments as #1 (A), #2 (B), #24 (X), #26 (Z)") {
  const std::string program = "O0001\nG21 G0 X0 Y0 Z5\nG65 P9000 A2 B3 X7 Z-1\nG0 Z5\nM30\n"
                              "O9000\nG1 X[#24+#1] Y#2 Z#26 F100\nM99\n";
  const Toolpath p = run(program, "fanuc");
  CHECK(errors(p) == 0);
  const std::vector<std::string> expected = {T(0, 0, 5), F(9, 3, -1), T(9, 3, 5)};
  CHECK(moves(p) == expected);
}

TEST_CASE("runaway loops and recursion stop with a diagnostic, not a hang") {
  SourceFile s = make_source("loop.ngc", "o1 while [1]\nG0 X1\no1 endwhile\nM2\n");
  InterpreterOptions o;
  o.max_loop_iterations = 50;
  const Toolpath loop = interpret(s, o);
  CHECK(errors(loop) == 1);
  CHECK(moves(loop).size() == 51);
  const Toolpath recursive = run("o<r> sub\nG0 X1\no<r> call\no<r> endsub\no<r> call\nM2\n");
  CHECK(errors(recursive) == 1);
  CHECK_FALSE(recursive.result.completed);
}

TEST_CASE("a program number too long for any number is no call target, and no crash") {
  // Found by fuzzing: O followed by 80 digits threw out of the interpreter.
  const Toolpath p =
      run("O" + std::string(80, '1') + " (PART)\nG21 G90\nG0 X1 Y2 Z3\nM30\n", "fanuc");
  CHECK(errors(p) == 0);
  CHECK(moves(p).size() == 1);
}

TEST_CASE("a block number too long for any number is no local subprogram, and no overflow") {
  // Found by fuzzing: N followed by 30 digits overflowed while M97 looked for its target.
  const Toolpath p =
      run("O0200\nN" + std::string(30, '3') + " X1.4\nG21 G90\nM97 P2\nG0 X1\nM30\nN2 G0 Y5\nM99\n",
          "haas");
  CHECK(errors(p) == 0);
  const auto m = move_commands(p);
  REQUIRE(m.size() == 3); // the long N line's X1.4, N2's Y5 (called), then X1
  CHECK(m[1].end.y == doctest::Approx(5));
  CHECK(m[2].end.x == doctest::Approx(1));
}

TEST_CASE("Fanuc macro B assignments take an expression without brackets") {
  // Fanuc Custom Macro B: "#i = <expression>" with operators by precedence, no brackets needed
  // around the whole right side (#610 = #597 - #601 in a probing macro).
  const std::string program = "O0001\nG21 G90 G0 X0 Y0 Z5\n#1 = 2 + 3 * 2\n#2 = #1 - 1\n"
                              "#3 = #1 / 4 + ABS[-1] * 2\n#4 = 7 MOD 4\n"
                              "G0 X#2 Y#3 Z#4\n#5 = 1 G0 X#5\nM30\n";
  const Toolpath p = run(program, "fanuc");
  CHECK(errors(p) == 0);
  CHECK(with_severity(p, Severity::Warning).empty());
  // #1 = 8, #2 = 7, #3 = 4, #4 = 3; "#5 = 1 G0 X#5" ends the value at "1" (the block's
  // assignments take effect after its words, so X reads the #5 from before: vacant, 0).
  const std::vector<std::string> expected = {T(0, 0, 5), T(7, 4, 3), T(0, 4, 3)};
  CHECK(moves(p) == expected);
  // LinuxCNC reads one value after '=': the operators after it are not part of it.
  CHECK(!with_severity(run("G21\n#1 = 2 + 3\nM2\n", "linuxcnc"), Severity::Warning).empty());
}

TEST_CASE("Fanuc macro B control flow: WHILE DO END, IF GOTO, IF THEN, GOTO") {
  // Fanuc Custom Macro B (Operator's Manual, "Branch and repetition"): the loop runs three times,
  // IF ... THEN assigns, IF ... GOTO and GOTO skip the blocks between.
  const std::string program = "O0001\nG21 G90 G0 X0 Y0 Z5\n#1 = 0\nWHILE [#1 LT 3] DO1\n"
                              "#1 = #1 + 1\nG1 X#1 F100\nEND1\nIF [#1 EQ 3] THEN #2 = 10\n"
                              "IF [#1 EQ 4] THEN #2 = 20\nG0 Y#2\nIF [#2 GT 5] GOTO 100\n"
                              "G0 Z50\nN100 G0 Z6\nGOTO200\nG0 Z60\nN200 M30\n";
  const Toolpath p = run(program, "fanuc");
  CHECK(errors(p) == 0);
  CHECK(with_severity(p, Severity::Warning).empty());
  const std::vector<std::string> expected = {T(0, 0, 5), F(1, 0, 5),  F(2, 0, 5),
                                             F(3, 0, 5), T(3, 10, 5), T(3, 10, 6)};
  CHECK(moves(p) == expected);
  // A GOTO searches the program being run: the subprogram's N10, not the main program's.
  const Toolpath sub = run("O0001\nG21 G0 X0 Y0 Z5\nM98 P2000\nN10 G0 X1\nM30\n"
                           "O2000\nGOTO 10\nG0 Y9\nN10 G0 Y2\nM99\n",
                           "fanuc");
  CHECK(errors(sub) == 0);
  const std::vector<std::string> sub_expected = {T(0, 0, 5), T(0, 2, 5), T(1, 2, 5)};
  CHECK(moves(sub) == sub_expected);
  // What the control alarms on: a GOTO to no block, a loop without its END, a bare IF.
  CHECK(errors(run("O1\nG21\nGOTO 99\nG0 X1\nM30\n", "fanuc")) == 1);
  CHECK(errors(run("O1\nG21\n#1=5\nWHILE [#1 LT 1] DO1\n#1=1\nM30\n", "fanuc")) == 1);
  CHECK(errors(run("O1\nG21\nIF [1 EQ 1] G0 X1\nM30\n", "fanuc")) == 1);
  // An endless DO loop stops at the loop guard, with an error, not a hang.
  CHECK(errors(run("O1\nG21\nDO1\nG0 X1\nEND1\nM30\n", "fanuc")) == 1);
}

TEST_CASE("programs the control holds run when the caller gives them") {
  // O9810 and o<probe> are in the control's memory, not in the file: given by the caller (a
  // folder, --macro-dir), they run as if in the file, and their commands count at the call line.
  std::vector<std::string> asked;
  InterpreterOptions options;
  options.dialect = find_dialect("fanuc");
  options.control_programs = [&](const std::string& name) -> std::optional<SourceFile> {
    asked.push_back(name);
    if (name == "9810") return make_source("O9810.NC", "O9810\nG1 X#24 Y#25 F#9\nBAD\nM99\n");
    return std::nullopt;
  };
  const SourceFile main = make_source(
      "main.nc", "O0001\nG21 G90 G0 X0 Y0 Z5\nG65 P9810 X10. Y5. F500.\nG65 P9810 X20. Y5. "
                 "F500.\nM98 P9999\nG0 Z20\nM30\n");
  const Toolpath p = interpret(main, options);
  const std::vector<std::string> expected = {T(0, 0, 5), F(10, 5, 5), F(20, 5, 5), T(20, 5, 20)};
  CHECK(moves(p) == expected);
  // Asked once for each program: O9999 is found nowhere and its call is skipped with a warning.
  CHECK(asked == std::vector<std::string>{"9810", "9999"});
  int feed_lines = 0;
  for (const CanonCommand& c : p.commands)
    if (c.kind == CanonKind::Feed) CHECK(c.line == (feed_lines++ == 0 ? 2 : 3));
  CHECK(feed_lines == 2);
  // What is wrong in the macro is said at its own file and line.
  bool found = false;
  for (const Diagnostic& d : p.result.diagnostics)
    if (d.file == "O9810.NC" && d.line == 3) found = true;
  CHECK(found);
  // A LinuxCNC subroutine file: o<probe> call reads probe.ngc.
  InterpreterOptions lcnc;
  lcnc.dialect = find_dialect("linuxcnc");
  lcnc.control_programs = [](const std::string& name) -> std::optional<SourceFile> {
    if (name != "probe") return std::nullopt;
    return make_source("probe.ngc", "o<probe> sub\nG1 Z#1 F100\no<probe> endsub\nM2\n");
  };
  const Toolpath l =
      interpret(make_source("m.ngc", "G21 G0 X0 Y0 Z5\no<probe> call [-2]\nG0 Z5\nM2\n"), lcnc);
  CHECK(errors(l) == 0);
  const std::vector<std::string> l_expected = {T(0, 0, 5), F(0, 0, -2), T(0, 0, 5)};
  CHECK(moves(l) == l_expected);
}
