#!/usr/bin/env python3
"""The work budgets end to end: a program that asks for more moves, path samples or removal work
than allowed stops with exit 5 (not 2, which is for programs a control refuses), says which budget,
where (file:line) and how to raise it (an option and a user-config key), and writes nothing: no
output file, no page, the original untouched under --in-place. The budgets are set small, so
each run takes milliseconds; the user config's keys set them too, and a bad value there is an
error at its line."""
import os
import subprocess
import sys
import tempfile

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
GENERIC = os.path.join(ROOT, "samples", "machines", "generic-3axis.toml")
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def run(*args, env=None):
    return subprocess.run([NCJOULE, *args], capture_output=True, text=True,
                          env=env or dict(os.environ))


# A slot cut back and forth in a loop of a million turns: 2 million moves, 180 km of cutting.
LOOP = ("G21 G90 G17\n(T1 D=6. CR=0. - ZMIN=-1. - FLAT END MILL)\nT1 M6\nS8000 M3\n"
        "G0 X0 Y10 Z5\nG1 Z-1 F300\no100 repeat [1000000]\nG1 X90 F1200\nG1 X0\n"
        "o100 endrepeat\nG0 Z5\nM30\n")
SHORT = LOOP.replace("[1000000]", "[3]")
STOCK = ["--stock", "box:-5,0,-5,95,20,0"]

with tempfile.TemporaryDirectory() as tmp:
    program = os.path.join(tmp, "loop.ngc")
    with open(program, "w") as f:
        f.write(LOOP)
    short = os.path.join(tmp, "short.ngc")
    with open(short, "w") as f:
        f.write(SHORT)

    # Moves: annotate -o writes nothing, --in-place leaves the file as it was.
    out = os.path.join(tmp, "out.ngc")
    r = run("annotate", program, "-m", GENERIC, *STOCK, "--max-moves", "1000", "-o", out)
    check(r.returncode == 5 and not os.path.exists(out),
          f"annotate past --max-moves: exit 5, nothing written ({r.returncode}: {r.stderr[-300:]})")
    check("loop.ngc:8:" in r.stderr or "loop.ngc:9:" in r.stderr,
          f"... it says where: the loop's line ({r.stderr[-300:]})")
    check("more than 1000 moves" in r.stderr and "--max-moves" in r.stderr
          and "max_moves" in r.stderr, "... which budget, and how to raise it")
    r = run("annotate", program, "-m", GENERIC, *STOCK, "--max-moves", "1000", "--in-place")
    with open(program) as f:
        check(r.returncode == 5 and f.read() == LOOP,
              f"annotate --in-place past the budget leaves the file as it was ({r.returncode})")

    # Path samples and removal work: estimate exits 5 and prints no numbers.
    r = run("estimate", short, "-m", GENERIC, *STOCK, "--max-path-samples", "50", "--json")
    check(r.returncode == 5 and r.stdout == "" and "--max-path-samples" in r.stderr
          and "max_path_samples" in r.stderr and "short.ngc:" in r.stderr,
          f"estimate past --max-path-samples: exit 5, no output ({r.returncode}: "
          f"{r.stderr[-300:]})")
    r = run("estimate", short, "-m", GENERIC, *STOCK, "--grid", "0.5", "--max-removal-work", "5000")
    check(r.returncode == 5 and "--max-removal-work" in r.stderr and "max_removal_work" in r.stderr,
          f"estimate past --max-removal-work: exit 5 ({r.returncode}: {r.stderr[-300:]})")
    r = run("estimate", short, "-m", GENERIC, *STOCK, "--grid", "0.5")
    check(r.returncode == 0, f"... within the default budgets the same program runs ({r.stderr})")

    # report and compare stop the same way: no page.
    page = os.path.join(tmp, "page.html")
    r = run("report", program, "-m", GENERIC, "--no-removal", "--max-moves", "1000", "-o", page)
    check(r.returncode == 5 and not os.path.exists(page),
          f"report past the budget: exit 5, no page ({r.returncode})")
    r = run("compare", short, program, "-m", GENERIC, "--no-removal", "--max-moves", "1000")
    check(r.returncode == 5, f"compare past the budget: exit 5 ({r.returncode})")
    r = run("canon", program, "--max-moves", "1000")
    check(r.returncode == 5 and "--max-moves" in r.stderr,
          f"canon past the budget: exit 5 ({r.returncode})")

    # The user config sets the budgets; the command line wins over it.
    config = os.path.join(tmp, "config.toml")
    with open(config, "w") as f:
        f.write("max_moves = 1000\n")
    env = dict(os.environ, NCJOULE_CONFIG=config)
    r = run("estimate", program, "-m", GENERIC, "--no-removal", env=env)
    check(r.returncode == 5 and "more than 1000 moves" in r.stderr,
          f"max_moves in the user config sets the budget ({r.returncode}: {r.stderr[-200:]})")
    r = run("estimate", short, "-m", GENERIC, "--no-removal", "--max-moves", "100000", env=env)
    check(r.returncode == 0, f"--max-moves wins over the config's ({r.returncode})")
    with open(config, "w") as f:
        f.write("# budgets\nmax_removal_work = 0\n")
    r = run("estimate", short, "-m", GENERIC, "--no-removal", env=env)
    check(r.returncode == 2 and "config.toml:2:" in r.stderr and "max_removal_work" in r.stderr,
          f"a budget of 0 in the config is an error at its line ({r.returncode}: {r.stderr})")

print(f"{len(failures) == 0 and 1 or 0} passed, {len(failures) and 1 or 0} failed")
sys.exit(1 if failures else 0)
