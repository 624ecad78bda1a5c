// Controller features real posts emit, each checked against what the controller's manual says
// the control does with it.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

#include "program_runner.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {
std::vector<CanonCommand> feeds_and_rapids(const Toolpath& p) {
  std::vector<CanonCommand> out;
  for (const CanonCommand& c : p.commands)
    if (c.kind == CanonKind::Feed || c.kind == CanonKind::Traverse) out.push_back(c);
  return out;
}
} // namespace

TEST_CASE("Haas G187 and G103, Fanuc G05.1 are planner hints with their values") {
  // Haas Mill Operator's Manual, "G187 Accuracy Control" (P1 rough, P2 medium, P3 finish,
  // E corner tolerance) and "G103 Limit Block Lookahead" (P = blocks, P0 = no limit).
  const Toolpath p = run("G21 G90\nG187 P3 E0.01\nG103 P5\nG1 X10 F500\nG187\nM30\n", "haas");
  const auto hints = of_kind(p, CanonKind::PlannerHint);
  REQUIRE(hints.size() == 3);
  CHECK(hints[0].text == "G187 P3 E0.01");
  CHECK(hints[0].value == doctest::Approx(187));
  CHECK(hints[1].text == "G103 P5");
  CHECK(hints[2].text == "G187");
  CHECK(with_severity(p, Severity::Warning).empty());
  // The move is unchanged by the hints.
  CHECK(moves(p).back() == "STRAIGHT_FEED(10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  // Fanuc Operator's Manual, "AI contour control (G05.1)": Q1 on, Q0 off.
  const Toolpath f = run("G21\nG05.1 Q1\nG1 X5 F100\nG05.1 Q0\nM30\n", "fanuc");
  const auto fh = of_kind(f, CanonKind::PlannerHint);
  REQUIRE(fh.size() == 2);
  CHECK(fh[0].text == "G5.1 Q1");
  CHECK(fh[1].text == "G5.1 Q0");
}

TEST_CASE("Fanuc G84 taps: feed in, spindle reverses, feed out: G74 is left-handed: M29 rigid") {
  // Fanuc Operator's Manual, "Tapping cycle (G84)" / "Rigid tapping": the tool feeds to Z at F,
  // the spindle reverses at the bottom after the dwell P (ms), and the tool feeds back to R;
  // G98 then rapids to the initial level.
  const Toolpath p = run("G21 G90 G0 Z20\nS500 M3\nM29 S500\n"
                         "G98 G84 X10 Y5 Z-10 R2 P300 F625\nG80\nM30\n",
                         "fanuc");
  CHECK(errors(p) == 0);
  auto m = feeds_and_rapids(p);
  REQUIRE(m.size() == 6);
  m.erase(m.begin());                      // the G0 Z20 of the first line
  CHECK(m[0].kind == CanonKind::Traverse); // over the hole at the initial level
  CHECK(m[1].end.z == doctest::Approx(2)); // down to R
  CHECK(m[2].kind == CanonKind::Feed);
  CHECK(m[2].end.z == doctest::Approx(-10));
  CHECK(m[2].text == "rigid tap");
  CHECK(m[2].state.spindle == SpindleDir::Clockwise);
  CHECK(m[3].kind == CanonKind::Feed); // out at the tapping feed, spindle reversed
  CHECK(m[3].end.z == doctest::Approx(2));
  CHECK(m[3].state.spindle == SpindleDir::CounterClockwise);
  CHECK(m[3].state.feed == doctest::Approx(625));
  CHECK(m[4].kind == CanonKind::Traverse);
  CHECK(m[4].end.z == doctest::Approx(20)); // G98: initial level
  const auto d = of_kind(p, CanonKind::Dwell);
  REQUIRE(d.size() == 1);
  CHECK(d[0].value == doctest::Approx(0.3));
  // G74 with M4: the spindle runs counter-clockwise in and clockwise out.
  const Toolpath l = run("G21 G0 Z5\nS300 M4\nG99 G74 X0 Y0 Z-8 R1 F300\nG80\nM30\n", "fanuc");
  const auto lm = feeds_and_rapids(l);
  REQUIRE(lm.size() >= 3);
  const auto& in = lm[lm.size() - 2];
  const auto& out = lm[lm.size() - 1];
  CHECK(in.end.z == doctest::Approx(-8));
  CHECK(in.state.spindle == SpindleDir::CounterClockwise);
  CHECK(out.end.z == doctest::Approx(1)); // G99: back to R
  CHECK(out.state.spindle == SpindleDir::Clockwise);
  CHECK(with_severity(l, Severity::Warning).empty());
}

TEST_CASE("G84 with Q pecks: Q deeper each time, out to R and back along the thread") {
  // Haas Mill Operator's Manual, "G84 Tapping Canned Cycle" (Q: peck depth); Fanuc "Peck rigid
  // tapping cycle" with parameter PCP = 1 (retract to R between pecks). 10 mm deep from R2 in
  // Q4 pecks: to -2, -6, then the bottom at -10; each peck backs out to R at the tapping feed
  // with the spindle reversed.
  const Toolpath p = run("G21 G90 G0 Z20\nS500 M3\nM29 S500\n"
                         "G98 G84 X10 Y5 Z-10 R2 Q4 F625\nX20\nG80\n"
                         "G84 X30 Y5 Z-10 R2 F625\nG80\nM30\n",
                         "haas");
  CHECK(errors(p) == 0);
  std::vector<CanonCommand> feeds;
  for (const CanonCommand& c : feeds_and_rapids(p))
    if (c.kind == CanonKind::Feed) feeds.push_back(c);
  // Per hole: (in, out, back) for the pecks at -2 and -6, then in to -10 and out: 8 feeds.
  REQUIRE(feeds.size() == 8 + 8 + 2);
  const double ends[8] = {-2, 2, -2, -6, 2, -6, -10, 2};
  for (int k = 0; k < 8; ++k) {
    CAPTURE(k);
    CHECK(feeds[k].end.z == doctest::Approx(ends[k]));
    CHECK(feeds[k].state.feed == doctest::Approx(625));
    const bool out = ends[k] == 2;
    CHECK(feeds[k].state.spindle == (out ? SpindleDir::CounterClockwise : SpindleDir::Clockwise));
  }
  CHECK(feeds[1].text == "rigid tap peck retract");
  CHECK(feeds[8].end.x == doctest::Approx(20)); // the second hole of the series pecks too
  CHECK(feeds[9].end.z == doctest::Approx(2));
  // After G80 a new series without Q taps in one go.
  CHECK(feeds[16].end.z == doctest::Approx(-10));
  CHECK(feeds[16].end.x == doctest::Approx(30));
  CHECK(feeds[17].end.z == doctest::Approx(2));
}

TEST_CASE("Fanuc M98 P/L forms and O-number headers, M99 returns") {
  // Fanuc Operator's Manual, "Subprogram": M98 P<program> L<repeats>, or P<repeats:4 digits
  // ...><program:4 digits>; M99 returns to the block after the call.
  const std::string program = "%\nO1000 (MAIN)\nG21 G90 G0 X0 Y0 Z5\nM98 P2000 L2\n"
                              "M98 P32000\nM30\nO2000 (SUB)\nG91 G0 X1\nG90\nM99\n%\n";
  const Toolpath p = run(program, "fanuc");
  CHECK(errors(p) == 0);
  const auto m = feeds_and_rapids(p);
  // 1 + 2 + 3 calls of the one-move subprogram: X climbs 1 mm per call.
  REQUIRE(m.size() == 6);
  CHECK(m.back().end.x == doctest::Approx(5));
  CHECK(m[1].line == 7); // the subprogram's move, 0-based line of "G91 G0 X1"
  CHECK(m[1].call_line == 3);
  CHECK(detect_dialect(make_source("x.nc", program)).name == "fanuc");
}

TEST_CASE("G65 macro call passes its arguments: Haas M97 calls a local N-number subprogram") {
  // Fanuc Custom Macro B, "G65 simple call": A->#1, B->#2, X->#24, Z->#26; the macro reads them.
  const Toolpath g = run("G21 G90 G0 X0\nG65 P9001 A2 X7 Z-3\nM30\nO9001\nG1 X#24 Z#26 F[#1*100]\n"
                         "M99\n",
                         "fanuc");
  CHECK(errors(g) == 0);
  const auto gm = feeds_and_rapids(g);
  REQUIRE(gm.size() == 2);
  CHECK(gm[1].end.x == doctest::Approx(7));
  CHECK(gm[1].end.z == doctest::Approx(-3));
  CHECK(gm[1].state.feed == doctest::Approx(200));
  // Haas Mill Operator's Manual, "M97 Local Sub-Program Call": M97 P<N number> L<repeats>.
  const Toolpath h = run("G21 G90 G0 X0 Y0\nM97 P100 L3\nM30\nN100 G91 G0 Y2\nG90\nM99\n", "haas");
  CHECK(errors(h) == 0);
  const auto hm = feeds_and_rapids(h);
  REQUIRE(hm.size() == 4);
  CHECK(hm.back().end.y == doctest::Approx(6));
}

TEST_CASE("Mach3: G4 P in seconds, M98 to O-number subprograms after M30, G43 H without a table") {
  const Toolpath p = run("G21 G90\nG43 H1\nG4 P2.5\nM98 P100\nM30\nO100\nG0 X3\nM99\n", "mach3");
  CHECK(errors(p) == 0);
  CHECK(with_severity(p, Severity::Warning).empty());
  const auto d = of_kind(p, CanonKind::Dwell);
  REQUIRE(d.size() == 1);
  CHECK(d[0].value == doctest::Approx(2.5));
  CHECK(feeds_and_rapids(p).back().end.x == doctest::Approx(3));
}

TEST_CASE("Sinumerik CYCLE81 under MCALL drills at every position until MCALL alone") {
  // SINUMERIK Programming Manual, Cycles, "CYCLE81 drilling, centring": rapid to RFP+SDIS, feed
  // to DP (or RFP-DPR), rapid to RTP. "MCALL": modal call after each positioning block.
  const Toolpath p = run("; Sinumerik\nG17 G90 G71\nT1 D1\nM6\nS2000 M3\nF150\nG0 Z50\n"
                         "MCALL CYCLE81(10, 0, 2, -12, )\nX10 Y10\nX30 Y10\nMCALL\nX50 Y10\nM30\n",
                         "siemens");
  CHECK(errors(p) == 0);
  CHECK(with_severity(p, Severity::Warning).empty());
  const auto feeds = of_kind(p, CanonKind::Feed);
  REQUIRE(feeds.size() == 2); // two holes, none after MCALL alone
  CHECK(feeds[0].end.x == doctest::Approx(10));
  CHECK(feeds[0].start.z == doctest::Approx(2)); // RFP + SDIS
  CHECK(feeds[0].end.z == doctest::Approx(-12));
  CHECK(feeds[1].end.x == doctest::Approx(30));
  const auto rapids = of_kind(p, CanonKind::Traverse);
  CHECK(rapids.back().end.x == doctest::Approx(50));
  // The rapid after each hole rises to RTP.
  int at_rtp = 0;
  for (const auto& r : rapids)
    if (std::abs(r.end.z - 10) < 1e-9 && r.start.z < r.end.z) ++at_rtp;
  CHECK(at_rtp == 2);
  // DPR: depth relative to RFP.
  const Toolpath q = run("G0 X0 Y0 Z20\nF100\nCYCLE82(10, -1, 1, , 5, 0.5)\nM30\n", "siemens");
  const auto qf = of_kind(q, CanonKind::Feed);
  REQUIRE(qf.size() == 1);
  CHECK(qf[0].end.z == doctest::Approx(-6));
  REQUIRE(of_kind(q, CanonKind::Dwell).size() == 1);
  CHECK(of_kind(q, CanonKind::Dwell)[0].value == doctest::Approx(0.5));
}

TEST_CASE("Sinumerik CYCLE83 pecks, CYCLE84 taps at pitch x speed") {
  // CYCLE83: first depth FDPR below RFP, each later peck DAM shorter (never below DAM),
  // VARI=1 retracts to RFP+SDIS after each peck.
  const Toolpath p =
      run("G0 X0 Y0 Z20\nF100\nCYCLE83(10, 0, 1, -10, , , 4, 1, 0, 0, 1, 1)\nM30\n", "siemens");
  std::vector<double> depths;
  for (const auto& f : of_kind(p, CanonKind::Feed))
    depths.push_back(f.end.z);
  // Pecks of 4, 3, 2 mm: -4, -7, -9, then the rest to -10.
  REQUIRE(depths.size() == 4);
  CHECK(depths[0] == doctest::Approx(-4));
  CHECK(depths[1] == doctest::Approx(-7));
  CHECK(depths[2] == doctest::Approx(-9));
  CHECK(depths[3] == doctest::Approx(-10));
  // CYCLE84: PIT 1.5 mm at SST 400 rpm: 600 mm/min in, SST1 800 rpm: 1200 mm/min out.
  const Toolpath t =
      run("G0 X0 Y0 Z20\nS400 M3\nCYCLE84(10, 0, 2, -15, , 0, 3, , 1.5, 0, 400, 800)\n"
          "M30\n",
          "siemens");
  const auto tf = of_kind(t, CanonKind::Feed);
  REQUIRE(tf.size() == 2);
  CHECK(tf[0].state.feed == doctest::Approx(600));
  CHECK(tf[1].state.feed == doctest::Approx(1200));
  CHECK(tf[1].state.spindle == SpindleDir::CounterClockwise);
}

TEST_CASE("Sinumerik TRANS/ATRANS shift and ROT rotates the programmed points") {
  // SINUMERIK Programming Manual, Fundamentals, "TRANS, ATRANS" and "ROT, AROT".
  const Toolpath p = run("G90 G0 X0 Y0 Z0\nTRANS X10 Y5\nG0 X1 Y1\nATRANS X1\nG0 X0 Y0\n"
                         "ROT RPL=90\nG0 X2 Y0\nTRANS\nG0 X2 Y0\nM30\n",
                         "siemens");
  CHECK(errors(p) == 0);
  const auto r = of_kind(p, CanonKind::Traverse);
  REQUIRE(r.size() == 5);
  CHECK(r[1].end.x == doctest::Approx(11));
  CHECK(r[1].end.y == doctest::Approx(6));
  CHECK(r[2].end.x == doctest::Approx(11)); // ATRANS adds 1 to the 10
  CHECK(r[2].end.y == doctest::Approx(5));
  // ROT clears the shift and rotates by 90 degrees about Z: X2 goes to Y2.
  CHECK(r[3].end.x == doctest::Approx(0).epsilon(1e-9));
  CHECK(r[3].end.y == doctest::Approx(2));
  CHECK(r[4].end.x == doctest::Approx(2)); // TRANS alone clears the frame
  CHECK(r[4].end.y == doctest::Approx(0).epsilon(1e-9));
}

TEST_CASE("unknown words, letters and characters warn with a column and the motion still counts") {
  // (A letter with no number is an error: diagnostics_test.cpp.)
  const Toolpath p = run("G21\nG1 X5 F100 FOO\nG1 X6 & \nG0 X7 (unclosed\nM30\n");
  CHECK(errors(p) == 0);
  const auto w = with_severity(p, Severity::Warning);
  REQUIRE(w.size() == 3);
  CHECK(w[0].line == 2);
  CHECK(w[0].column == 12);
  CHECK(w[0].message.find("FOO") != std::string::npos);
  CHECK(w[1].line == 3);
  CHECK(w[1].column == 7); // '&'
  CHECK(w[2].line == 4);
  const auto m = moves(p);
  REQUIRE(m.size() == 3);
  CHECK(m[0] == "STRAIGHT_FEED(5.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  CHECK(m[1] == "STRAIGHT_FEED(6.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  CHECK(m[2] == "STRAIGHT_TRAVERSE(7.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
}

TEST_CASE("a rotary axis word is carried through") {
  const Toolpath p = run("G21 G90 G0 X0 Y0 Z5 A0\nG1 X10 A90 F200\nM30\n");
  CHECK(errors(p) == 0);
  const auto f = of_kind(p, CanonKind::Feed);
  REQUIRE(f.size() == 1);
  CHECK(f[0].end.a == doctest::Approx(90));
}

TEST_CASE("reprap firmwares: G4 S in seconds is not a spindle speed, G4 P in ms") {
  const Toolpath p = run("G21\nM3 S8000\nG4 S3\nG4 P250\nM30\n", "reprap");
  const auto d = of_kind(p, CanonKind::Dwell);
  REQUIRE(d.size() == 2);
  CHECK(d[0].value == doctest::Approx(3));
  CHECK(d[1].value == doctest::Approx(0.25));
  CHECK(of_kind(p, CanonKind::SpindleSpeed).size() == 1);
}

TEST_CASE("a '%' line with more on it: refused by LinuxCNC, a comment when no control is named") {
  // A Fusion post's start file (MPCNC21.cps) writes "% vfd enable" lines as notes. rs274: "Bad
  // character '%' used"; taken as the closing '%', the program's cuts would vanish unsaid.
  const std::string text = "%\nG21 G0 X1\n% vfd enable\nG0 X2\n%(end)\nG0 X3\n%\n";
  const Toolpath linuxcnc = run(text, "linuxcnc");
  const auto e = with_severity(linuxcnc, Severity::Error);
  REQUIRE(e.size() == 2);
  CHECK(e[0].line == 3);
  CHECK(e[0].column == 1);
  CHECK(e[1].line == 5);

  const Toolpath unnamed = run(text, "");
  CHECK(errors(unnamed) == 0);
  CHECK(with_severity(unnamed, Severity::Warning).size() == 2);
  REQUIRE(moves(unnamed).size() == 3);
  CHECK(moves(unnamed).back() ==
        "STRAIGHT_TRAVERSE(3.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)");
  CHECK(unnamed.result.completed);

  // A Fanuc tape's '%' ends the program whatever follows it on the line.
  const Toolpath fanuc = run(text, "fanuc");
  CHECK(errors(fanuc) == 0);
  CHECK(moves(fanuc).size() == 1);
  // '%' alone, blanks around it, is the delimiter everywhere.
  CHECK(moves(run("%\nG21 G0 X1\n  %  \nG0 X2\n", "linuxcnc")).size() == 1);
}

TEST_CASE("Heidenhain ISO: % header with G71, '*' block ends, absolute arc centres") {
  // Heidenhain TNC User's Manual, DIN/ISO programming: "%NAME G71 *" opens a metric program;
  // I, J are the circle centre in absolute coordinates.
  const Toolpath p = run("%TEST G71 *\nN10 G00 X+10 Y+0 Z+5 *\nN20 G01 Z-1 F200 *\n"
                         "N30 G03 X+0 Y+10 I+0 J+0 *\nN99999 %TEST G71 *\n",
                         "heidenhain");
  CHECK(errors(p) == 0);
  CHECK(with_severity(p, Severity::Warning).empty());
  const auto a = of_kind(p, CanonKind::Arc);
  REQUIRE(a.size() == 1);
  CHECK(a[0].centre_first == doctest::Approx(0));
  CHECK(a[0].centre_second == doctest::Approx(0));
  CHECK(p.result.completed);
}

TEST_CASE("every FreeCAD post's sample is detected as its controller family") {
  // samples/freecad is made by scripts/make_freecad_samples.py. Posts whose output names no
  // controller and uses no family's syntax fall back to linuxcnc.
  const std::pair<const char*, const char*> expected[] = {
      {"linuxcnc", "linuxcnc"}, {"KineticNCBeamicon2", "linuxcnc"},
      {"centroid", "linuxcnc"}, {"comparams", "linuxcnc"},
      {"dynapath", "linuxcnc"}, {"fablin", "linuxcnc"},
      {"nccad", "linuxcnc"},    {"philips", "linuxcnc"},
      {"fanuc", "fanuc"},       {"grbl", "grbl"},
      {"jtech", "grbl"},        {"marlin", "reprap"},
      {"rrf", "reprap"},        {"smoothie", "reprap"},
      {"mach3_mach4", "mach3"}, {"uccnc", "mach3"}};
  for (auto [post, dialect] : expected) {
    const std::string path = std::string(NCJOULE_SOURCE_DIR) + "/samples/freecad/" + post + ".nc";
    std::FILE* f = std::fopen(path.c_str(), "rb");
    REQUIRE_MESSAGE(f != nullptr, path);
    std::string text;
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;)
      text.append(buf, n);
    std::fclose(f);
    const SourceFile source = make_source(path, text);
    CHECK_MESSAGE(detect_dialect(source).name == dialect, std::string(post));
    // And in that dialect it runs to its end without errors.
    InterpreterOptions options;
    const Toolpath p = interpret(source, options);
    CHECK_MESSAGE(errors(p) == 0, std::string(post));
    CHECK_MESSAGE(p.result.completed, std::string(post));
  }
}

TEST_CASE("the Fanuc family's additional work offsets: G54.1 P, Haas G154 P and G110-G129") {
  // Fanuc G54.1 P1-P300 and Haas G154 P1-P99 (G110-G129 = P1-P20) select offsets past G59; a
  // G53 move shows where each puts the work (machine X-100 is work X-100 - origin).
  InterpreterOptions options;
  options.work_offsets[1] = Pose{-300, 0, 0, 0, 0, 0};
  options.work_offsets[9 + 2] = Pose{-200, 0, 0, 0, 0, 0}; // G54.1 P2
  options.work_offsets[9 + 3] = Pose{-50, 0, 0, 0, 0, 0};  // G54.1 P3 = G154 P3 = G112
  for (const char* dialect : {"fanuc", "haas"}) {
    CAPTURE(dialect);
    options.dialect = find_dialect(dialect);
    for (const char* select : {"G54.1 P2", "G154 P2", "G111"}) {
      CAPTURE(select);
      const Toolpath p =
          interpret(make_source("o.nc", std::string("O1\nG21 G90 G0 X0 Y0 Z0\n") + select +
                                            "\nG0 X0\nG53 G0 X-100\nG112 G0 X0\nM30\n"),
                    options);
      CHECK(errors(p) == 0);
      CHECK(with_severity(p, Severity::Warning).empty());
      std::vector<double> xs;
      for (const CanonCommand& c : p.commands)
        if (c.kind == CanonKind::Traverse) xs.push_back(c.end.x);
      // X0 in G54 (machine -300), X0 in P2 (machine -200), machine -100, X0 in P3 (machine -50).
      CHECK(xs == std::vector<double>{0, 0, 100, 0});
    }
  }
  // LinuxCNC has no G54.1: it stays an unknown code there.
  options.dialect = find_dialect("linuxcnc");
  const Toolpath l = interpret(make_source("o.ngc", "G21\nG54.1 P2\nG0 X1\nM2\n"), options);
  CHECK(!with_severity(l, Severity::Warning).empty());
  // P out of range is the control's alarm.
  options.dialect = find_dialect("fanuc");
  CHECK(errors(interpret(make_source("o.nc", "O1\nG21\nG54.1 P400\nM30\n"), options)) == 1);
}

TEST_CASE("L is a whole number: a canned cycle's L2.5 is refused, as rs274 refuses it") {
  for (const char* dialect : {"linuxcnc", "fanuc", "mach3"}) {
    CAPTURE(std::string(dialect));
    const std::string program =
        "G21 G90\nG0 X0 Y0 Z5\nG91 G81 X10 Y0 Z-6 R-4 F100 L2.5\nG80\nG90\nM2\n";
    const Toolpath p = run(program, dialect);
    CHECK(errors(p) == 1);
    CHECK(with_severity(p, Severity::Error)[0].column == 29); // the L word
    // No hole drilled: the block is skipped, not rounded to three holes.
    CHECK(of_kind(p, CanonKind::Feed).empty());
    std::string whole = program;
    whole.replace(whole.find("L2.5"), 4, "L3");
    CHECK(errors(run(whole, dialect)) == 0);
  }
}

TEST_CASE("G16 polar coordinates as the Fanuc family and Mach3 read them") {
  auto ends = [](const Toolpath& p) {
    std::vector<std::pair<double, double>> out;
    for (const CanonCommand& c : move_commands(p))
      out.emplace_back(c.end.x, c.end.y);
    return out;
  };
  // A bolt circle about the work zero, absolute angles, then incremental ones (radius kept).
  const Toolpath fanuc = run("G21 G90 G17\nG0 X0 Y0 Z5\nG16\nG0 X50 Y0\nY90\nG91 Y90\nG90\nG15\n"
                             "G0 X10 Y10\nM30\n",
                             "fanuc");
  CHECK(errors(fanuc) == 0);
  CHECK(warnings(fanuc) == 0);
  const auto f = ends(fanuc);
  REQUIRE(f.size() == 5);
  CHECK(f[1].first == doctest::Approx(50));
  CHECK(f[1].second == doctest::Approx(0).epsilon(1e-9));
  CHECK(f[2].first == doctest::Approx(0).scale(50));
  CHECK(f[2].second == doctest::Approx(50));
  CHECK(f[3].first == doctest::Approx(-50));
  CHECK(f[3].second == doctest::Approx(0).scale(50));
  CHECK(f[4].first == doctest::Approx(10)); // G15: Cartesian again
  CHECK(f[4].second == doctest::Approx(10));
  // A drilled hole circle: the cycle's X and Y are radius and angle too.
  const Toolpath holes = run("G21 G90 G17\nG0 X0 Y0 Z5\nG16\nG81 X100 Y30 Z-5 R2 F100\nY150\n"
                             "G80\nG15\nM30\n",
                             "haas");
  CHECK(errors(holes) == 0);
  std::vector<std::pair<double, double>> plunges;
  for (const CanonCommand& c : of_kind(holes, CanonKind::Feed))
    plunges.emplace_back(c.end.x, c.end.y);
  REQUIRE(plunges.size() == 2);
  CHECK(plunges[0].first == doctest::Approx(100 * std::cos(30 * M_PI / 180)));
  CHECK(plunges[0].second == doctest::Approx(50));
  CHECK(plunges[1].first == doctest::Approx(-100 * std::cos(30 * M_PI / 180)));
  CHECK(plunges[1].second == doctest::Approx(50));
  // Mach3: the pole is where the tool was when G16 was read.
  const auto m = ends(run("G21 G90 G17\nG0 X10 Y10 Z5\nG16\nG1 X5 Y90 F100\nG15\nM30\n", "mach3"));
  REQUIRE(m.size() == 2);
  CHECK(m[1].first == doctest::Approx(10));
  CHECK(m[1].second == doctest::Approx(15));
  // LinuxCNC has no G16: a warning, and the words are Cartesian.
  const Toolpath lcnc = run("G21 G90\nG0 X0 Y0 Z5\nG16\nG0 X50 Y90\nM2\n", "linuxcnc");
  CHECK(warnings(lcnc) == 1);
  CHECK(ends(lcnc).back().second == doctest::Approx(90));
}
