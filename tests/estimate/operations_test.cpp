// Operations, found once in the pipeline: split at tool changes and at the post's operation
// comments, named after the comment the post wrote (above, on or below the tool change), never
// after a tool list entry or commented-out code.
#include <doctest/doctest.h>

#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"
#include "operations.hpp"

using namespace ncjoule;
using ncjoule::estimate_detail::operation_name_in;

namespace {

const MachineProfile& machine() {
  static const MachineProfile m =
      load_profile(std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/generic-3axis.toml");
  return m;
}

Estimate run(const std::string& text, bool removal = false) {
  EstimateOptions options;
  options.simulate_removal = removal;
  options.stock = parse_stock_spec("box:-10,-10,-5,60,30,0");
  return estimate_program(make_source("ops.ngc", text), machine(), options);
}

std::vector<std::string> names(const Estimate& e) {
  std::vector<std::string> out;
  for (const OperationSummary& op : e.operations)
    out.push_back(op.name);
  return out;
}

} // namespace

TEST_CASE("an operation per tool change, named by the comment above it") {
  const Estimate e = run("G21 G90\n"
                         "G0 X0 Y0 Z5\n" // before the first tool change: rapids only
                         "(Face1)\n"
                         "M5 (spindle off)\n"
                         "G28 G91 Z0\n" // a retract does not stop the look up
                         "G90\n"
                         "T1 M6\n"
                         "S1000 M3\n"
                         "G1 Z-1 F100\n"
                         "G1 X10\n"
                         "(G00 Z3)\n" // commented-out code is no name
                         "M9\n"
                         "T2 M6 (Drill, 4 holes)\n"
                         "G1 X20\n"
                         "M30\n");
  REQUIRE(names(e) ==
          std::vector<std::string>{"before first operation", "Face1", "Drill, 4 holes"});
  CHECK(e.operations[1].tool == 1);
  CHECK(e.operations[1].line == 6);
  CHECK(e.operations[2].tool == 2);
  double time = 0, energy = 0;
  for (const OperationSummary& op : e.operations)
    time += op.time_s, energy += op.energy_j;
  CHECK(time == doctest::Approx(e.time_s));
  CHECK(energy == doctest::Approx(e.energy.energy_j));
  // Every block knows its operation (CSV, JSON).
  for (const LineSummary& b : e.lines)
    if (b.line >= 8 && b.line <= 9) CHECK(b.operation == 2);
}

TEST_CASE("boilerplate, rules, resets and bare operation numbers are no names") {
  // The shapes real posts write around an operation: Fusion's personal-use notice, a Fanuc
  // post's cleanup banner, SolidWorks CAM's rules, a reset comment and "OP 2" next to the
  // operation's own description.
  const Estimate e = run("%\nO1001 (PART)\n"
                         "(When using Fusion for Personal Use, the feedrate of rapid)\n"
                         "(moves is reduced to match the feedrate of cutting moves,)\n"
                         "(which can increase machining time. Unrestricted rapid moves)\n"
                         "(are available with a Fusion Subscription.)\n"
                         "G21 G90\n"
                         "(FACE BOTTOM)\n"
                         "(----------------------)\n"
                         "T1 M6\n"
                         "S1000 M3\n"
                         "G0 X0 Y0 Z5\n"
                         "G1 Z-1 F100\n"
                         "G1 X10\n"
                         "(--- END OF PREVIOUS OPERATION INTERMEDIATE CLEANUP ---)\n"
                         "M5\n"
                         "(*** DRILL .25 HOLES ***)\n"
                         "(OP 2)\n"
                         "(RESET OFFSETS)\n"
                         "T2 M6\n"
                         "G1 X20\n"
                         "M30\n%\n");
  CHECK(names(e) == std::vector<std::string>{"FACE BOTTOM", "DRILL .25 HOLES"});
  CHECK(operation_name_in("Op. 3").empty());
  CHECK(operation_name_in("OPERATION #12").empty());
  CHECK(operation_name_in("OP 2 ROUGH POCKET") == "OP 2 ROUGH POCKET");
  // A call or control word commented out (genes-encoder.ngc: "(o<tedautoz> call)") is code.
  CHECK(operation_name_in("o<tedautoz> call").empty());
  CHECK(operation_name_in("O100 CALL [1] [2]").empty());
  CHECK(operation_name_in("o200 endsub").empty());
  CHECK(operation_name_in("Outline call-outs") == "Outline call-outs");
  CHECK(operation_name_in("== Contour1 ==") == "Contour1");
}

TEST_CASE("LinuxCNC's comment commands: a message names, debug and log output do not") {
  // pcb2gcode asks for each drill with a message; hand-written programs print their variables.
  CHECK(operation_name_in("MSG, Change tool bit to drill size 0.4mm") ==
        "Change tool bit to drill size 0.4mm");
  CHECK(operation_name_in("msg,Attach the probe tool") == "Attach the probe tool");
  CHECK(operation_name_in("DEBUG, slot width is #<slot_deg>").empty());
  CHECK(operation_name_in("debug,icutter_deg= #<icutter_deg>").empty());
  CHECK(operation_name_in("PRINT, depth #<depth>").empty());
  CHECK(operation_name_in("LOGOPEN,probe-results.txt").empty());
  CHECK(operation_name_in("PROBEOPEN points.txt").empty());
  CHECK(operation_name_in("MSG,").empty());
}

TEST_CASE("generators' markers and debug output name nothing, names with such words still do") {
  CHECK(operation_name_in("path_direction = x").empty());
  CHECK(operation_name_in("xy != p_xy && z > 0:Rapid to Start, Plunge").empty());
  CHECK(operation_name_in("COMMAND_COOLANT_OFF").empty());
  CHECK(operation_name_in("SECTION begin").empty());
  CHECK(operation_name_in("START end").empty());
  CHECK(operation_name_in("CHANGE TOOL begin").empty());
  CHECK(operation_name_in("[Process]").empty());
  CHECK(operation_name_in("Map: Allow Rapid Z = true").empty());
  CHECK(operation_name_in("X Min: 7.588 - X Max: 226.309").empty());
  CHECK(operation_name_in("start: 2.064,7.620").empty());
  CHECK(operation_name_in("G1->G0 Mapping Properties:").empty());
  CHECK(operation_name_in("Feed: Max Toolpath Speed = 1000").empty());
  CHECK(operation_name_in("Map: SafeZ Mode = Retract : default").empty());
  CHECK(operation_name_in("Pocket: Layer 6") == "Pocket: Layer 6");
  CHECK(operation_name_in("2D Contour tabs") == "2D Contour tabs");
  CHECK(operation_name_in("ROUGH_POCKET") == "ROUGH_POCKET");
  CHECK(operation_name_in("Finish the end") == "Finish the end");
}

TEST_CASE("a name on a line with only a block number: N10 (Face1)") {
  // Fusion's Tormach and Haas posts number every block, the operation's comment too.
  const Estimate e = run("N5 G21 G90\nN10 (Face1)\nN15 T1 M6\nN20 S1000 M3\nN25 G1 X5 F100\n"
                         "N30 (Drill1)\nN35 T2 M6\nN40 G1 X10\nN45 G1 X12 (not a name: code)\n"
                         "M30\n");
  CHECK(names(e) == std::vector<std::string>{"Face1", "Drill1"});
  // FreeCAD's block mode: the markers around each operation are no names.
  CHECK(operation_name_in("Block-expand: 0").empty());
  CHECK(operation_name_in("Path: 3mm Endmill003").empty());
  CHECK(operation_name_in("14").empty());
}

TEST_CASE("two operations with one tool split at the post's operation comment") {
  const Estimate e = run("G21 G90\n"
                         "(T1 D=6. CR=0. - ZMIN=-2. - FLAT END MILL)\n"
                         "(2D CONTOUR1)\n"
                         "T1 M6\n"
                         "S8000 M3\n"
                         "G0 X0 Y0 Z5\n"
                         "G1 Z-1 F300\n"
                         "G1 X20\n"
                         "G0 Z5\n"
                         "(2D POCKET2)\n"
                         "G0 X5 Y5\n"
                         "G1 Z-2 F300\n"
                         "G1 X15\n"
                         "M30\n");
  REQUIRE(names(e) == std::vector<std::string>{"2D CONTOUR1", "2D POCKET2"});
  CHECK(e.operations[1].tool == 1);
  CHECK(e.operations[1].line == 10); // its first block
}

TEST_CASE("FreeCAD's begin/finish operation comments: the name, not the note") {
  const Estimate e = run("G21\n"
                         "(begin operation: TC: 6mm Endmill)\n"
                         "(TC: 6mm Endmill)\n"
                         "M6 T1\n"
                         "M3 S8000\n"
                         "(finish operation: TC: 6mm Endmill)\n"
                         "(begin operation: Facing)\n"
                         "(Coolant On:Flood)\n"
                         "G0 X0 Y0 Z5\n"
                         "G1 Z-0.5 F300\n"
                         "G1 X20\n"
                         "(finish operation: Facing)\n"
                         "(begin operation: Pocket)\n"
                         "(Coolant On:Flood)\n"
                         "G1 Y10\n"
                         "M2\n");
  CHECK(names(e) == std::vector<std::string>{"Facing", "Pocket"});
}

TEST_CASE("a name below the tool change: the header's tool list is never a name") {
  const Estimate e = run("(T1 D=20. CR=0. - ZMIN=-1. - FLAT END MILL)\n"
                         "G90 G94 G17 G21\n"
                         "T1 M6\n"
                         "S5500 M3\n"
                         "(FACE1)\n"
                         "G1 X2 F100\n"
                         "M5\n"
                         "T2 M6\n"
                         "G1 X3\n"
                         "M30\n");
  REQUIRE(names(e) == std::vector<std::string>{"FACE1", "T2"});
}

TEST_CASE("a program without operations is one, named program") {
  const Estimate e = run("G21 G1 X10 F100\nG1 Y10\nM2\n");
  REQUIRE(names(e) == std::vector<std::string>{"program"});
  CHECK(e.operations[0].time_s == doctest::Approx(e.time_s));
}

TEST_CASE("the time split: rapids, cutting, air cutting, tool changes, dwells add up") {
  const Estimate e = run("G21 G90\n"
                         "(T1 D=6. CR=0. - ZMIN=-2. - FLAT END MILL)\n"
                         "T1 M6\n"
                         "S8000 M3\n"
                         "G0 X-8 Y5 Z5\n"
                         "G1 Z-1 F600\n"
                         "G1 X-6\n" // in the air: the stock starts at X-10... inside
                         "G1 X20\n" // cuts
                         "G0 Z5\n"
                         "G0 X0 Y100\n"
                         "G1 Z-1\n" // beyond the stock: air
                         "G4 P1\n"
                         "M30\n",
                         true);
  const TimeSplit& t = e.time;
  CHECK(t.total_s() == doctest::Approx(e.time_s));
  CHECK(t.tool_changes == 1);
  CHECK(t.dwell_s == doctest::Approx(1.0));
  CHECK(t.air_cut_s > 0);
  CHECK(t.cutting_s() > 0);
  CHECK(t.air_cut_s < t.feed_s);
  double air = 0;
  for (const OperationSummary& op : e.operations)
    air += op.time.air_cut_s;
  CHECK(air == doctest::Approx(t.air_cut_s));
}

TEST_CASE("FreeCAD's first operation is named, not 'before first operation', and a grbl post's "
          "commented tool change gives the tool") {
  // FreeCAD's grbl post (block mode): a fixture and a tool controller before the first
  // operation, the tool change written as a comment (grbl has no changer).
  const Estimate e = run("(Exported by FreeCAD)\n"
                         "(Begin preamble)\n"
                         "G17 G90\n"
                         "G21\n"
                         "(Block-name: Fixture)\n"
                         "(Begin operation: Fixture)\n"
                         "(Path: Fixture)\n"
                         "G54\n"
                         "(Finish operation: Fixture)\n"
                         "(Block-name: 3mm Endmill001)\n"
                         "(Begin operation: 3mm Endmill001)\n"
                         "(3mm Endmill001)\n"
                         "(Begin toolchange)\n"
                         "( M6 T2 )\n"
                         "M3 S10000\n"
                         "(Finish operation: 3mm Endmill001)\n"
                         "(Block-name: Profile_hole)\n"
                         "(Begin operation: Profile_hole)\n"
                         "(Profile_hole)\n"
                         "G0 Z6\n"
                         "G0 X0 Y0\n"
                         "G1 Z-1 F400\n"
                         "G1 X10\n"
                         "(Finish operation: Profile_hole)\n"
                         "(Block-name: Adaptive)\n"
                         "(Begin operation: Adaptive)\n"
                         "(Adaptive)\n"
                         "G0 Z6\n"
                         "G1 Z-1\n"
                         "G1 Y10\n"
                         "M2\n");
  REQUIRE(names(e) == std::vector<std::string>{"Profile_hole", "Adaptive"});
  CHECK(e.operations[0].tool == 2);
  CHECK(e.operations[1].tool == 2);
  CHECK(e.operations[0].time_s > 0);
  // The tool controller's label above the commented change describes T2.
  REQUIRE(e.tools.count(2) == 1);
  CHECK(e.tools.at(2).diameter_mm == doctest::Approx(3));
  bool noted = false;
  for (const Diagnostic& d : e.diagnostics)
    noted = noted || (d.line == 14 && d.message.find("T2") != std::string::npos);
  CHECK(noted);
  // A program that changes tools itself keeps its own: a commented-out change is one taken out.
  const Estimate own = run("G21\nT1 M6\nS1000 M3\n( M6 T2 )\nG1 X5 F100\nM2\n");
  REQUIRE_FALSE(own.operations.empty());
  CHECK(own.operations.back().tool == 1);
}

TEST_CASE("Estlcam's stop between operations keeps its own name, not the next one's time") {
  // Estlcam writes a stop as an operation of its own: rapids away, and O-word subprograms
  // (defined inline) that park the machine and pause.
  const Estimate e = run("(Project Enclosure)\n"
                         "(Created by Estlcam version 10 build 10.012)\n"
                         "G90\n"
                         "M03 S12000\n"
                         "G00 Z5\n"
                         "(No. 1: Mill Right Hole)\n"
                         "G00 X2 Y0\n"
                         "G01 Z-1 F100\n"
                         "G01 X4\n"
                         "G00 Z5\n"
                         "(No. 2: Stop After Right Hole)\n"
                         "G00 X0 Y0 Z5\n"
                         "O100 sub\n"
                         "G00 Z25\n"
                         "G00 Y-50\n"
                         "O100 endsub\n"
                         "O110 sub\n"
                         "M00\n"
                         "G00 X0\n"
                         "O110 endsub\n"
                         "O100 call\n"
                         "(MSG,Rotate 90 degrees - next hole is the LEFT SIDE)\n"
                         "O110 call\n"
                         "(No. 3: Mill Left Hole)\n"
                         "G00 X10 Y0 Z5\n"
                         "G01 Z-1 F100\n"
                         "G01 X40\n"
                         "G01 Y20\n"
                         "G00 Z5\n"
                         "M30\n");
  REQUIRE(names(e) == std::vector<std::string>{"before first operation", "No. 1: Mill Right Hole",
                                               "No. 2: Stop After Right Hole",
                                               "No. 3: Mill Left Hole"});
  CHECK(e.operations[2].line == 11);
  CHECK(e.operations[3].line == 24);
  // The stop holds its rapids, the next operation its cuts.
  CHECK(e.operations[3].time_s > e.operations[1].time_s);
  CHECK(e.operations[3].time_s > 15); // 30 mm + 20 mm at 100 mm/min
}

TEST_CASE("NX's motion comments and a Fusion set-up note name no operation") {
  // NX posts describe each move in a comment; a Fusion program's manual "FLIP PART" note comes
  // before the operation it precedes.
  const Estimate nx = run("%\nO0001\n"
                          "N0010 G40 G17 G90 G71\n"
                          "(FACE_MILLING)\n"
                          "N0020 T01 M06\n"
                          "N0030 G0 G90 X0 Y0 S3000 M03\n"
                          "(Linear move)\n"
                          "N0040 G1 Z-1 F200\n"
                          "(Circular move CCLW XY plane)\n"
                          "N0050 G3 X10 Y0 I5 J0\n"
                          "(Linear move)\n"
                          "N0060 G1 X20\n"
                          "(Rapid move)\n"
                          "N0070 G0 Z5\n"
                          "(Circular move CLW XY plane)\n"
                          "N0080 G2 X30 Y0 I5 J0\n"
                          "M30\n%\n");
  CHECK(names(nx) == std::vector<std::string>{"FACE_MILLING"});
  CHECK(operation_name_in("Circular move CCLW XY plane").empty());
  CHECK(operation_name_in("Linear move").empty());
  CHECK(operation_name_in("Engage move").empty());
  const Estimate flip = run("%\nO1001\n"
                            "(FACE TOP)\n"
                            "T1 M6\n"
                            "S5000 M3\n"
                            "G0 X0 Y0 Z5\n"
                            "G1 Z-1 F300\n"
                            "G1 X20\n"
                            "G0 Z5\n"
                            "M5\n"
                            "(FLIP PART)\n"
                            "M0\n"
                            "(FACE BOTTOM)\n"
                            "S5000 M3\n"
                            "G0 X0 Y0 Z5\n"
                            "G1 Z-1 F300\n"
                            "G1 X20\n"
                            "M5\n"
                            "(FLIP PART)\n"
                            "M0\n"
                            "(DRILL)\n"
                            "T2 M6\n"
                            "S3000 M3\n"
                            "G0 X5 Y5 Z5\n"
                            "G1 Z-3 F100\n"
                            "M30\n%\n");
  CHECK(names(flip) == std::vector<std::string>{"FACE TOP", "FACE BOTTOM", "DRILL"});
  // A comment above a tool change names its operation; one below it (a layer) does not.
  const Estimate layer =
      run("G21\n(Pocket)\nT1 M6\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X5\nG0 Z5\n"
          "(Profiles)\nT2 M6\n(Profile: Layer 6)\nG0 X10 S10000 M3\n"
          "G1 Z-1 F300\nG1 X20\nM30\n");
  CHECK(names(layer) == std::vector<std::string>{"Pocket", "Profiles"});
}
