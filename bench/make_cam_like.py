#!/usr/bin/env python3
"""Prints one of a few programs shaped like CAM output, for bench/linuxcnc_time.sh ("gen/NAME").

    python3 bench/make_cam_like.py NAME > NAME.ngc

  adaptive  trochoidal clearing: a helical ramp, then loops of tangent arcs and short links at
            F2000, as adaptive/dynamic clearing strategies post them
  finish    3D finishing raster over a dome: moves of 0.1 to 0.2 mm at F3000, G64 without P
  finish-p  the same raster under G64 P0.01 (Q = P: LinuxCNC merges nearly straight runs)
Deterministic, so runs compare.
"""
import math
import sys


def fmt(v):
    s = f"{v:.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def header(mode):
    return ["%", "(cam-like benchmark program)", "G21 G17 G90 G94 " + mode, "T1 M6", "S12000 M3",
            "M8"]


def adaptive():
    out = header("G64 P0.02")
    out += ["G0 X0 Y0 Z5", "G0 Z1"]
    # Helical ramp down to Z-2 on a 3 mm circle, two turns.
    out.append("G1 X3 Y0 Z1 F800")
    out.append("G3 X3 Y0 Z-0.5 I-3 J0")
    out.append("G3 X3 Y0 Z-2 I-3 J0")
    x = 3.0
    for i in range(60):
        # A trochoidal loop of radius 2 advancing 0.6 mm along X each time.
        out.append(f"G3 X{fmt(x - 4)} Y0 I-2 J0" + (" F2000" if i == 0 else ""))
        out.append(f"G3 X{fmt(x + 0.6)} Y0 I{fmt(2.3)} J0")
        x += 0.6
    out += ["G0 Z5", "M9", "M5", "M30", "%"]
    return out


def finish(mode):
    out = header(mode)
    out += ["G0 X-20 Y-20 Z5", "G1 Z0 F1000"]
    rows = 12
    for row in range(rows):
        y = -20 + row * 40 / (rows - 1)
        xs = [-20 + k * 0.15 for k in range(int(40 / 0.15) + 1)]
        if row % 2:
            xs.reverse()
        for n, x in enumerate(xs):
            z = 8 * math.cos(math.hypot(x, y) / 20) - 8
            out.append(f"G1 X{fmt(x)} Y{fmt(y)} Z{fmt(z)}" + (" F3000" if n == 0 and row == 0 else ""))
    out += ["G0 Z5", "M9", "M5", "M30", "%"]
    return out


def main():
    name = sys.argv[1] if len(sys.argv) > 1 else ""
    programs = {"adaptive": adaptive, "finish": lambda: finish("G64"),
                "finish-p": lambda: finish("G64 P0.01")}
    if name not in programs:
        sys.exit(__doc__)
    print("\n".join(programs[name]()))


if __name__ == "__main__":
    main()
