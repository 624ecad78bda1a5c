#!/usr/bin/env python3
"""Writes the short programs whose LinuxCNC 2.9 per-line timings are the golden data of
linuxcnc_rule_test.cpp. Each exercises a few of the planner rules (docs/timing-vs-linuxcnc.md).

    python3 tests/kinematics/linuxcnc/make_programs.py OUT_DIR

The .lcnc.csv files next to them are LinuxCNC 2.9's per-line times for them (trivkins XYZ,
1000 mm/s^2 and 100 mm/s per axis, 1 ms servo cycle), made with
    bench/linuxcnc_time.sh --copy-csv tests/kinematics/linuxcnc tests/kinematics/linuxcnc/*.ngc
"""
import math
import os
import sys


def fmt(v):
    s = f"{v:.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def corners():
    out = ["(corners: G64 without P, G64 P, G61, G61.1)", "G21 G17 G90 G94", "G0 X0 Y0 Z0"]
    for mode, feed in (("G64", 3000), ("G64 P0.05", 3000), ("G61", 3000), ("G61.1", 3000),
                       ("G64", 1500)):
        out.append(mode)
        out += [f"G1 X20 Y0 F{feed}", "X20 Y15", "X0 Y15", "X0 Y0"]
        # a triangle with a sharp and two shallow corners, and a zigzag of 2 mm legs
        out += ["X30 Y2", "X0 Y4", "X0 Y0"]
        for i in range(1, 11):
            out.append(f"X{2 * i} Y{1 if i % 2 else 0}")
        out += ["G1 X0 Y0"]
    out.append("M2")
    return out


def surface():
    """3D surfacing: rows of 0.4 mm moves over z = 1.5 sin(x/4) cos(y/9), as CAM finishing."""
    out = ["(surface: short 3D segments)", "G21 G17 G90 G94", "G0 X0 Y0 Z5", "G1 Z0 F600"]
    mode = ["G64", "G64 P0.01 Q0", "G64 P0.002 Q0"]
    y = 0.0
    for row in range(6):
        out.append(mode[row // 2])
        xs = [i * 0.4 for i in range(101)]
        if row % 2:
            xs.reverse()
        feed = 1500 if row % 2 == 0 else 2400
        first = True
        for x in xs:
            z = 1.5 * math.sin(x / 4) * math.cos(y / 9)
            out.append(f"G1 X{fmt(x)} Y{fmt(y)} Z{fmt(z)}" + (f" F{feed}" if first else ""))
            first = False
        y += 0.5
    out += ["G0 Z5", "M2"]
    return out


def engrave():
    """Strokes with plunges and retracts, spindle and coolant as a post writes them."""
    out = ["(engrave: plunges, rapids, spindle and coolant)", "G21 G17 G90 G94 G64", "T1 M6",
           "S8000 M3", "M8", "G0 Z3"]
    strokes = [[(0, 0), (0, 8), (4, 8), (4, 4), (0, 4)], [(6, 0), (8, 8), (10, 0)],
               [(8.5, 3), (7.5, 3)], [(12, 0), (12, 8), (15, 6), (12, 4), (15, 2), (12, 0)],
               [(18, 8), (18, 0), (21, 0)]]
    for k, s in enumerate(strokes):
        out.append(f"G0 X{fmt(s[0][0])} Y{fmt(s[0][1])}")
        out.append("G0 Z0.5")
        out.append("G1 Z-0.3 F200")
        for i, (x, y) in enumerate(s[1:]):
            out.append(f"G1 X{fmt(x)} Y{fmt(y)}" + (" F900" if i == 0 else ""))
        out.append("G0 Z3")
    out += ["M9", "M5", "G0 X0 Y0", "M2"]
    return out


def arcs():
    out = ["(arcs: tangent and cornered line-arc and arc-arc joins, helices, small radii)",
           "G21 G17 G90 G94 G64", "G0 X0 Y0 Z0", "G1 X10 F1800",
           "G3 X20 Y10 I0 J10",            # tangent line -> arc
           "G1 X20 Y20",                   # tangent arc -> line
           "G2 X30 Y30 I10 J0",            # tangent line -> arc
           "G3 X40 Y20 I0 J-10",           # arc -> arc, reversed curvature, tangent
           "G1 X50 Y30",                   # arc -> line at an angle
           "G2 X60 Y20 I0 J-10",           # line -> arc at an angle
           "G3 X70 Y20 I5 J0",             # arc -> arc at an angle
           "G1 X70 Y10",
           "G2 X70 Y10 I-2 J0 Z-2",        # a full-turn helix
           "G1 X75 Y10 Z-2",
           "G1 X76 Y10 F6000",
           "G3 X78 Y10 I1 J0",             # small radius: speed held by the arc's own limit
           "G3 X76 Y10 I-1 J0",
           "G2 X74 Y10 I-1 J0",
           "G1 X74 Y0 F1800",
           "G18 G2 X80 Z-2 I3 K0",         # XZ plane
           "G17 G1 X90 Y0 Z-2",
           "G19 G3 Y6 Z-2 J3 K0",          # YZ plane
           "G17 G1 X90 Y10",
           "G0 Z5", "M2"]
    return out


def naive_cam():
    """G64 P Q: near-collinear points merged into one move (Q = P), and a flat arc as two lines."""
    out = ["(naivecam: G64 P Q merging)", "G21 G17 G90 G94", "G0 X0 Y0 Z0", "G64 P0.02"]
    for i in range(1, 61):
        x = i * 0.5
        y = 0.008 * math.sin(i * 1.7)
        out.append(f"G1 X{fmt(x)} Y{fmt(y)}" + (" F1200" if i == 1 else ""))
    out += ["G1 X30 Y10", "G2 X40 Y10 I5 J-200", "G1 X40 Y0"]
    out.append("G64 P0.02 Q0.001")
    for i in range(1, 41):
        x = 40 - i * 0.5
        y = -0.008 * math.sin(i * 1.3)
        out.append(f"G1 X{fmt(x)} Y{fmt(y)}")
    out += ["G0 Z5", "M2"]
    return out


def split_arcs():
    """G64 P with small corner arcs: an arc's middle joins the lines before it and its end does
    not, so the naive-CAM detector sends its two halves in two straight moves."""
    out = ["(splitarcs: arcs split between two naive-CAM moves)", "G21 G17 G90 G94", "G0 X0 Y0 Z0",
           "G64 P0.5", "F1200"]
    for k, r in enumerate((1.0, 0.6, 1.0)):
        w, h = 20 - 4 * k, 12 - 2 * k
        out += [f"G1 X{fmt(w - r)} Y0", f"G3 X{fmt(w)} Y{fmt(r)} I0 J{fmt(r)}",
                f"G1 X{fmt(w)} Y{fmt(h - r)}", f"G3 X{fmt(w - r)} Y{fmt(h)} I{fmt(-r)} J0",
                f"G1 X{fmt(r)} Y{fmt(h)}", f"G3 X0 Y{fmt(h - r)} I0 J{fmt(-r)}",
                f"G1 X0 Y{fmt(r)}", f"G3 X{fmt(r)} Y0 I{fmt(r)} J0"]
        if k == 1:
            out.append("F2400")
    # An S of two small arcs after a line, then lines again.
    out += ["G1 X10 Y0", "G3 X11 Y1 I0 J1", "G2 X12 Y2 I1 J0", "G1 X12 Y8", "G1 X0 Y8",
            "G0 Z5", "M2"]
    return out


def stops():
    out = ["(stops: codes that empty the queue, and some that do not)", "G21 G17 G90 G94 G64",
           "G0 X0 Y0 Z0", "G1 X10 F1200", "X20 Y2", "M7", "X30 Y0", "X40 Y2", "M9", "X50 Y0",
           "S2000", "X60 Y2", "G4 P0.25", "X70 Y0", "G43 H1", "X80 Y2", "G49", "X90 Y0",
           "T2", "X100 Y2", "F900", "X110 Y0", "(MSG,half way)", "X120 Y2", "G54", "X130 Y0",
           "G0 X140 Y2", "G0 X150 Y0", "G1 X160 Y2", "X150 Y2", "X160 Y2.01",
           "M3 S1000", "G1 X170 Y0", "X180 Y2", "X190 Y0", "M5", "G1 X200", "M2"]
    return out


def short():
    """Very short moves at high feed: speed held to a length per servo cycle, linear ramps."""
    out = ["(short: segments of a few servo cycles)", "G21 G17 G90 G94 G64", "G0 X0 Y0 Z0",
           "F6000"]
    x = 0.0
    for i in range(80):
        x += 0.05 if i % 3 else 0.12
        out.append(f"G1 X{fmt(x)} Y{fmt(0.02 * (i % 2))}")
    for i in range(40):
        x += 0.3
        out.append(f"G1 X{fmt(x)} Y{fmt(2 + 0.3 * (i % 2))}")
    out += ["G0 Z5", "M2"]
    return out


PROGRAMS = {"corners": corners, "surface": surface, "engrave": engrave, "arcs": arcs,
            "naivecam": naive_cam, "splitarcs": split_arcs, "stops": stops, "short": short}


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    for name, make in PROGRAMS.items():
        with open(os.path.join(folder, name + ".ngc"), "w") as f:
            f.write("\n".join(make()) + "\n")


if __name__ == "__main__":
    main()
