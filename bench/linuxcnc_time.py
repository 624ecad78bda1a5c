#!/usr/bin/env python3
"""ncjoule's block times next to LinuxCNC 2.9's real trajectory planner (see linuxcnc_time.sh).

For every program: the total run time LinuxCNC's planner takes (counted in its own 1 ms servo
cycles by the lcnc-time tool, which runs LinuxCNC headless in real time), the total ncjoule
predicts on the matching machine profile (bench/machines/linuxcnc-sim.toml), and the error of
every line that takes more than 0.1 s in LinuxCNC.

LinuxCNC charges the time of a blend arc to the line after it, and the time of moves merged by
G64 P Q (naive CAM) to the last merged line; ncjoule charges blend arcs the same way. Lines that
LinuxCNC lists without time (merged lines, settings) are folded into the next line it lists, on
both sides, so that the two are compared block by block.

LinuxCNC results are cached by the program's bytes (and the machine limits), so a second run of
the table does not run LinuxCNC again.
"""
import argparse
import concurrent.futures
import csv
import hashlib
import io
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
NC_FILES = "/usr/share/linuxcnc/ncfiles"  # Debian's linuxcnc-uspace
ACCEL, VEL = 1000, 100  # mm/s^2, mm/s: lcnc-time's machine and bench/machines/linuxcnc-sim.toml
LINE_FLOOR_S = 0.1  # per-line errors are taken over lines longer than this in LinuxCNC


def resolve(spec, cache):
    """'PATH[@LINES]': PATH relative to the repository, 'ncfiles/NAME' in LinuxCNC's nc_files,
    'corpus/NAME' in $NCJOULE_CORPUS, 'gen/NAME' a program of bench/make_cam_like.py; @LINES
    keeps the first LINES lines and appends M2."""
    path, _, keep = spec.partition("@")
    if path.startswith("gen/"):
        full = os.path.join(cache, path.replace("/", "-") + ".ngc")
        with open(full, "w") as f:
            subprocess.run([sys.executable, os.path.join(HERE, "make_cam_like.py"),
                            path[len("gen/"):]], stdout=f, check=True)
    elif path.startswith("ncfiles/"):
        full = os.path.join(NC_FILES, path[len("ncfiles/"):])
    elif path.startswith("corpus/"):
        corpus = os.environ.get("NCJOULE_CORPUS")
        if not corpus:
            sys.exit(f"linuxcnc_time: {spec}: set NCJOULE_CORPUS to the corpus folder")
        full = os.path.join(corpus, path[len("corpus/"):])
    else:
        full = path if os.path.isabs(path) else os.path.join(ROOT, path)
    if not os.path.isfile(full):
        sys.exit(f"linuxcnc_time: {spec}: no such file ({full})")
    return path, full, int(keep) if keep else 0


def program_text(full, keep):
    """The program as both planners get it: line endings made LF (lcnc-time does the same), and
    a prefix cut after `keep` lines with M2 appended."""
    text = open(full, "rb").read().decode("latin-1").replace("\r\n", "\n").replace("\r", "\n")
    if keep:
        text = "\n".join(text.split("\n")[:keep]) + "\nM2\n"
    return text


def ncjoule_program_lines(text):
    return text.count("\n") + (0 if text.endswith("\n") else 1)


def read_lines(csv_path):
    per = {}
    with open(csv_path, newline="") as f:
        for row in csv.DictReader(f):
            per[int(row["line"])] = per.get(int(row["line"]), 0.0) + float(row["seconds"])
    return per


def run_linuxcnc(tool, program, cache, key, expected_s, last_line, attempts=3):
    """Runs lcnc-time once per program and returns (total_s, {line: seconds}), from the cache
    when it has them. lcnc-time now and then hangs at the end of a run or ends one early (its
    driver polls LinuxCNC's task from outside): a run is retried when it takes more than three
    times what ncjoule predicts, or when its last line with time is before `last_line`, the
    last line ncjoule gives time to."""
    total_path = os.path.join(cache, key + ".lcnc.total")
    csv_path = os.path.join(cache, key + ".lcnc.csv")
    if os.path.exists(total_path) and os.path.exists(csv_path):
        return float(open(total_path).read()), read_lines(csv_path)
    problem = ""
    for _ in range(attempts):
        timeout = max(60, int(3 * expected_s) + 30)
        env = dict(os.environ, LCNC_LINES_CSV=csv_path + ".part", LCNC_TIMEOUT=str(timeout))
        r = subprocess.run([tool, program, str(ACCEL), str(VEL)], env=env, capture_output=True,
                           text=True)
        if r.returncode != 0 or not os.path.exists(csv_path + ".part"):
            problem = r.stderr.strip().splitlines()[-1:] or ["no output"]
            problem = problem[0]
            continue
        per = read_lines(csv_path + ".part")
        if per and max(per) < last_line:
            problem = f"the run ended at line {max(per)}, before line {last_line}"
            continue
        os.replace(csv_path + ".part", csv_path)
        with open(total_path, "w") as f:
            f.write(r.stdout.strip() + "\n")
        return float(r.stdout), per
    raise RuntimeError(f"lcnc-time failed {attempts} times on {program}: {problem}")


def run_ncjoule(ncjoule, program, machine):
    # The simulator's tool table: cutter compensation offsets by its radii, as LinuxCNC does.
    table = os.path.join(HERE, "machines", "linuxcnc-sim.tbl")
    r = subprocess.run([ncjoule, "estimate", program, "--machine", machine, "--no-removal",
                        "--tool-table", table, "--tool-units", "mm", "--csv"],
                       capture_output=True, text=True)
    if r.returncode not in (0, 2) or not r.stdout:
        raise RuntimeError(f"ncjoule failed on {program}:\n{r.stderr[-2000:]}")
    per = {}
    for row in csv.DictReader(io.StringIO(r.stdout)):
        line = int(row["line"])
        per[line] = per.get(line, 0.0) + float(row["time_s"])
    return sum(per.values()), per


def fold(lcnc, ours):
    """Pairs of (LinuxCNC, ncjoule) seconds per LinuxCNC line: ncjoule's time on lines that
    LinuxCNC does not list goes to the next line it lists (or the last one)."""
    listed = sorted(lcnc)
    if not listed:
        return []
    pairs = {line: [lcnc[line], 0.0] for line in listed}
    j = 0
    for line in sorted(ours):
        while j < len(listed) and listed[j] < line:
            j += 1
        target = listed[j] if j < len(listed) else listed[-1]
        pairs[target][1] += ours[line]
    return [tuple(pairs[line]) + (line,) for line in listed]


def percentile(values, q):
    if not values:
        return 0.0
    v = sorted(values)
    k = (len(v) - 1) * q
    lo, hi = int(k), min(int(k) + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (k - lo)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("programs", nargs="*", help="PATH[@LINES] (default: bench/linuxcnc_programs.txt)")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--machine", default=os.path.join(HERE, "machines", "linuxcnc-sim.toml"))
    ap.add_argument("--cache", default=None, help="folder for LinuxCNC results (default BUILD/linuxcnc-time)")
    ap.add_argument("--jobs", type=int, default=2, help="LinuxCNC runs side by side (real time)")
    ap.add_argument("--markdown", action="store_true", help="print the table as Markdown")
    ap.add_argument("--lines", metavar="PROGRAM", help="print the per-line comparison of one program")
    ap.add_argument("--copy-csv", metavar="DIR",
                    help="copy LinuxCNC's per-line times of each program to DIR/NAME.lcnc.csv "
                         "(how tests/kinematics/linuxcnc/*.lcnc.csv are made)")
    args = ap.parse_args()

    specs = args.programs
    if not specs:
        with open(os.path.join(HERE, "linuxcnc_programs.txt")) as f:
            specs = [l.split("#")[0].strip() for l in f]
            specs = [s for s in specs if s]
    ncjoule = os.path.join(args.build, "plugin", "ncjoule")
    if not os.access(ncjoule, os.X_OK):
        sys.exit(f"linuxcnc_time: {ncjoule} not built")
    cache = args.cache or os.path.join(args.build, "linuxcnc-time")
    os.makedirs(cache, exist_ok=True)
    tool = os.environ.get("LCNC_TIME") or shutil.which("lcnc-time.sh") or shutil.which("lcnc-time")

    jobs = []
    for spec in specs:
        name, full, keep = resolve(spec, cache)
        text = program_text(full, keep)
        key = hashlib.sha256(f"{ACCEL} {VEL}\n".encode() + text.encode("latin-1")).hexdigest()[:20]
        program = os.path.join(cache, key + ".ngc")
        if not os.path.exists(program):
            with open(program, "w", encoding="latin-1", newline="\n") as f:
                f.write(text)
        jobs.append((name, keep, program, key, ncjoule_program_lines(text)))

    # ncjoule first: its prediction bounds LinuxCNC's run time, its last timed line the run's end.
    ours = {j[3]: run_ncjoule(ncjoule, j[2], args.machine) for j in jobs}
    missing = [j for j in jobs if not os.path.exists(os.path.join(cache, j[3] + ".lcnc.total"))]
    if missing and not tool:
        sys.exit("linuxcnc_time: LinuxCNC results missing and no lcnc-time tool: set LCNC_TIME")
    if missing:
        print(f"running LinuxCNC on {len(missing)} programs in real time ({args.jobs} at a time)...",
              file=sys.stderr)
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futures = {}
        for j in jobs:
            total, lines = ours[j[3]]
            last = max((l for l, s in lines.items() if s > 0.02), default=0)
            futures[pool.submit(run_linuxcnc, tool, j[2], cache, j[3], total, last)] = j
        for fut in concurrent.futures.as_completed(futures):
            j = futures[fut]
            try:
                results[j[3]] = fut.result()
            except RuntimeError as e:
                print(f"linuxcnc_time: {j[0]}: {e}", file=sys.stderr)

    rows = []
    for name, keep, program, key, lines in jobs:
        if key not in results:
            continue
        if args.copy_csv:
            base = os.path.splitext(os.path.basename(name))[0]
            shutil.copyfile(os.path.join(cache, key + ".lcnc.csv"),
                            os.path.join(args.copy_csv, base + ".lcnc.csv"))
        lc_total, lc_lines = results[key]
        nc_total, nc_lines = ours[key]
        pairs = fold(lc_lines, nc_lines)
        errors = [abs(n - l) / l for l, n, _ in pairs if l > LINE_FLOOR_S]
        label = name + (f" (first {keep} lines)" if keep else "")
        rows.append((label, lines, lc_total, nc_total, (nc_total - lc_total) / lc_total * 100,
                     percentile(errors, 0.95) * 100, len(errors)))
        if args.lines and args.lines in (name, label):
            print("line,linuxcnc_s,ncjoule_s,error_pct")
            for l, n, line in pairs:
                print(f"{line},{l:.3f},{n:.3f},{(n - l) / l * 100 if l > 0 else 0:.1f}")

    head = ("program", "lines", "LinuxCNC s", "ncjoule s", "error %", "p95 line error %",
            "lines > 0.1 s")
    if args.markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
        for r in rows:
            print(f"| {r[0]} | {r[1]} | {r[2]:.3f} | {r[3]:.3f} | {r[4]:+.2f} | {r[5]:.2f} | {r[6]} |")
    else:
        print(f"{head[0]:<48} {head[1]:>6} {head[2]:>10} {head[3]:>10} {head[4]:>8} {head[5]:>8} {head[6]:>6}")
        for r in rows:
            print(f"{r[0]:<48} {r[1]:>6} {r[2]:>10.3f} {r[3]:>10.3f} {r[4]:>+8.2f} {r[5]:>8.2f} {r[6]:>6}")
    worst_total = max((abs(r[4]) for r in rows), default=0)
    worst_p95 = max((r[5] for r in rows), default=0)
    print(f"\nworst total error {worst_total:.2f}% (target 1%), worst p95 line error {worst_p95:.2f}%"
          f" (target 3%), {len(rows)} programs", file=sys.stderr if args.markdown else sys.stdout)


if __name__ == "__main__":
    main()
