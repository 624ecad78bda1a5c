#!/usr/bin/env python3
"""Prints a synthetic LinuxCNC program of N blocks (default 1,000,000) to stdout.

A pocket-like toolpath: rows of short G1 moves joined by G2/G3 half circles, a few tool
changes with their spindle starts, and plunges between layers. Deterministic, so runs compare.

    python3 bench/make_synthetic.py [BLOCKS] > synthetic.ngc
"""
import sys


def main() -> None:
    blocks = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
    out = sys.stdout
    write = out.write
    header = ["%", "(ncjoule synthetic benchmark program)", "G21 G17 G90 G94 G64 P0.01"]
    for line in header:
        write(line + "\n")
    written = 1  # the G21 line
    tool_every = max(blocks // 4, 1)
    row_moves = 40
    step = 0.5  # mm per G1 move along a row
    row_gap = 2.0  # mm between rows (the arc diameter)
    x = y = 0.0
    direction = 1
    moves_in_row = 0
    tool = 0
    layer = 0
    while written < blocks:
        if written % tool_every == 1 or tool == 0:
            tool += 1
            for line in (f"T{tool} M6", f"S{6000 + 500 * tool} M3", "G0 Z5", "G0 X0 Y0",
                         f"G1 Z{-0.5 * (layer + 1):.3f} F300", "F1200"):
                write(line + "\n")
            written += 6
            x = y = 0.0
            direction, moves_in_row = 1, 0
            continue
        if moves_in_row < row_moves:
            x += direction * step
            write(f"G1 X{x:.3f} Y{y:.3f}\n")
            moves_in_row += 1
        else:
            # Half circle to the next row, turning the way the row ends.
            code = "G3" if direction > 0 else "G2"
            y += row_gap
            write(f"{code} X{x:.3f} Y{y:.3f} I0 J{row_gap / 2:.3f}\n")
            direction, moves_in_row = -direction, 0
            if y > 200:
                layer += 1
                write(f"G0 Z5\nG0 X0 Y0\nG1 Z{-0.5 * (layer + 1):.3f} F300\nF1200\n")
                written += 4
                x = y = 0.0
        written += 1
    write("M5\nM30\n%\n")


if __name__ == "__main__":
    main()
