#!/usr/bin/env python3
"""CAMotics' example programs with their projects: ncjoule run with the .camotics project beside
the program (its workpiece and tools read from it) against the same program with that workpiece
given by --stock and those tools by --tool. The two must agree: the project reader must give
exactly what a user typing the project's stock and tools would.

    bench/camotics_projects.py NCJOULE REPO [--machine PROFILE] [--guess]

REPO: a clone of CauldronDevelopmentLLC/CAMotics (a bare one too). Prints a table: per program,
the stock the project gives, removed volume, energy and peak power both ways, and whether they
agree (to the printed digits); then the projects whose workpiece is automatic (not a stock its
author set: ncjoule does not take it). With --guess, a second table: the same programs with the
project's tools but no stock (ncjoule's guess from the cuts), against the project's stock: a
held-out set for the guess, since each author set the stock by hand.
"""
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "corpus"))
import camotics_layout  # noqa: E402


def tool_options(project):
    """--tool arguments for the project's tools, as the project describes them (mm)."""
    out = []
    for key, t in sorted(project.get("tools", {}).items(), key=lambda kv: int(kv[0])):
        scale = 25.4 if t.get("units") == "imperial" else 1.0
        d = t.get("diameter", 0) * scale
        length = t.get("length", 0) * scale
        shape = t.get("shape", "cylindrical")
        if shape in ("cylindrical", "cylinder"):
            spec = "%s:flat:%.9g" % (key, d)
        elif shape == "ballnose" or (shape in ("spheroid", "sphere") and length == d):
            spec = "%s:ball:%.9g" % (key, d)
        elif shape in ("conical", "cone", "snubnose"):
            snub = t.get("snub_diameter", 0) * scale if shape == "snubnose" else 0
            angle = 2 * math.degrees(math.atan((d - snub) / 2 / length))
            spec = "%s:chamfer:%.9g:%.9g" % (key, d, angle) + (":%.9g" % snub if snub else "")
        else:
            continue
        out += ["--tool", spec]
    return out


def stock_option(project):
    b = project["workpiece"]["bounds"]
    return "box:" + ",".join("%.9gmm" % v for v in b["min"] + b["max"])


def figure(estimate, key):
    """A figure of an estimate's JSON; the peak power is its highest block's."""
    if key == "peak_power_w":
        return max((b.get("power_peak_w", 0) for b in estimate.get("blocks", [])), default=0)
    return estimate[key]


def run(ncjoule, args):
    r = subprocess.run([ncjoule, "estimate", "--json"] + args, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, env=dict(os.environ, NCJOULE_CONFIG=os.devnull + ".toml"))
    if not r.stdout:
        return None, r.stderr.decode(errors="replace").strip().splitlines()[-1:]
    return json.loads(r.stdout), None


def main():
    args = [a for a in sys.argv[1:]]
    machine = []
    guess = "--guess" in args
    if guess:
        args.remove("--guess")
    if "--machine" in args:
        i = args.index("--machine")
        machine = ["--machine", args[i + 1]]
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    ncjoule, repo = args
    with tempfile.TemporaryDirectory(prefix="ncjoule-camotics-") as out:
        laid = camotics_layout.lay_out(repo, out)
        print("| program | project stock (mm) | from | removed mm^3 beside / given | energy J beside / "
              "given | peak W beside / given | agree |")
        print("|---|---|---|---|---|---|---|")
        automatic = []
        agree_all = True
        for folder, project_path, is_automatic, programs in laid:
            project = json.load(open(project_path))
            if is_automatic:
                automatic.append(os.path.basename(project_path))
                continue
            for program in programs:
                beside, err1 = run(ncjoule, machine + [program])
                given, err2 = run(ncjoule, machine + ["--stock", stock_option(project)] +
                                  tool_options(project) + [program])
                name = os.path.basename(program)
                if beside is None or given is None:
                    print("| %s | | | failed: %s | | | no |" % (name, err1 or err2))
                    agree_all = False
                    continue
                rows = []
                same = True
                for key in ("removed_mm3", "energy_j", "peak_power_w"):
                    a, b = figure(beside, key), figure(given, key)
                    rows.append("%.6g / %.6g" % (a, b))
                    same = same and ("%.6g" % a) == ("%.6g" % b)
                agree_all = agree_all and same
                stock = project["workpiece"]["bounds"]
                print("| %s | %s | %s | %s | %s | %s | %s |" % (
                    name, ",".join("%g" % v for v in stock["min"] + stock["max"]),
                    beside.get("stock_from"), rows[0], rows[1], rows[2], "yes" if same else "NO"))
        if guess:
            print()
            print("| program | removed mm^3 guessed / project | energy J guessed / project | "
                  "peak W guessed / project |")
            print("|---|---|---|---|")
            for folder, project_path, is_automatic, programs in laid:
                if is_automatic:
                    continue
                project = json.load(open(project_path))
                for program in programs:
                    alone = os.path.join(out, "alone")
                    os.makedirs(alone, exist_ok=True)
                    lone = os.path.join(alone, os.path.basename(program))
                    with open(program, "rb") as src, open(lone, "wb") as dst:
                        dst.write(src.read())
                    guessed, err = run(ncjoule, machine + tool_options(project) + [lone])
                    given, _ = run(ncjoule, machine + [program])
                    os.remove(lone)
                    if guessed is None or given is None:
                        print("| %s | failed: %s | | |" % (os.path.basename(program), err))
                        continue
                    print("| %s | %s | %s | %s |" % ((os.path.basename(program),) + tuple(
                        "%.6g / %.6g" % (figure(guessed, k), figure(given, k))
                        for k in ("removed_mm3", "energy_j", "peak_power_w"))))
        print()
        print("automatic workpiece (not read): " + (", ".join(automatic) or "none"))
        print("all agree: " + ("yes" if agree_all else "NO"))
        sys.exit(0 if agree_all else 1)


if __name__ == "__main__":
    main()
