#!/usr/bin/env python3
"""Prints the scale benchmark's program of N blocks (default 1,000,000) to stdout.

Short random G1 moves over an 80 x 80 mm area at one depth, an arc every 50 blocks, one 6 mm
flat end mill, for a 100 x 100 x 10 mm stock (box:0,0,-10,100,100,0). Deterministic (a fixed
seed), so runs compare.

    python3 bench/make_scale_program.py [BLOCKS] > scale.ngc
"""
import random
import sys


def main() -> None:
    blocks = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
    rng = random.Random(1234)
    write = sys.stdout.write
    for line in ("%", "(ncjoule scale benchmark)", "(T1 D=6. CR=0. - ZMIN=-1. - FLAT END MILL)",
                 "G21 G17 G90 G94 G64", "T1 M6", "S8000 M3", "G0 X50 Y50 Z5", "G1 Z-1 F300",
                 "F1500"):
        write(line + "\n")
    x = y = 50.0
    written = 5
    while written < blocks:
        if written % 50 == 0:
            # A half circle of 1 mm radius, turning back the way it came.
            r = 1.0
            ny = y + 2 * r if y + 2 * r < 90 else y - 2 * r
            j = (ny - y) / 2
            write(f"G{2 if rng.random() < 0.5 else 3} X{x:.3f} Y{ny:.3f} I0 J{j:.3f}\n")
            y = ny
        else:
            x = min(90.0, max(10.0, x + rng.uniform(-1.0, 1.0)))
            y = min(90.0, max(10.0, y + rng.uniform(-1.0, 1.0)))
            write(f"G1 X{x:.3f} Y{y:.3f}\n")
        written += 1
    write("G0 Z5\nM5\nM30\n%\n")


if __name__ == "__main__":
    main()
