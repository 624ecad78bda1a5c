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
