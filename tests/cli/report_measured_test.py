#!/usr/bin/env python3
"""`ncjoule report --log` on NIST's cover run (tests/logs/data): the page holds the measured run
over the predicted one (the line reached over time) and the table of measured against predicted
per operation, the program and the worst blocks, with the same numbers `ncjoule check-log --json`
prints; the same from the Streams document; options that need --log refused without it; a log
with no run of the program said in the page; and the page rendered in a real headless Chromium
without console errors.

Exits 77 (ctest SKIP_RETURN_CODE) after the checks of the page when chromium is not installed."""
import html as htmllib
import json
import os
import re
import subprocess
import sys
import tempfile

import headless_page

NCJOULE = os.environ["NCJOULE"]
SRC = os.environ["NCJOULE_SOURCE_DIR"]
DATA = os.path.join(SRC, "tests", "logs", "data")
COVER = os.path.join(DATA, "cover.nc")
DEVICES = os.path.join(DATA, "Devices-Hurco04.xml")
SHDR = ["--log", os.path.join(DATA, "cover-run.shdr"), "--devices", DEVICES]
STREAMS = ["--log", os.path.join(DATA, "cover-run.xml")]
SKIP = 77
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def run(*args):
    return subprocess.run([NCJOULE, *args], capture_output=True, text=True)


def chart_series(page, chart_id):
    """The data-series of the time chart in the figure `chart_id`, as the tooltip script reads it."""
    m = re.search(r'<figure class="chart" id="%s">.*?data-series="([^"]*)"' % re.escape(chart_id),
                  page, re.S)
    return json.loads(htmllib.unescape(m.group(1))) if m else []


def rows(page, table_class, part="tbody"):
    """(measured, min, max, predicted) of each row of a measured table, from its data attributes."""
    m = re.search(r'<table class="%s">.*?<%s>(.*?)</%s>' % (table_class, part, part), page, re.S)
    if not m:
        return []
    return [tuple(float(x) for x in r) for r in re.findall(
        r'<tr data-measured-s="([^"]*)" data-measured-min-s="([^"]*)" '
        r'data-measured-max-s="([^"]*)" data-predicted-s="([^"]*)">', m.group(1))]


def same(a, b):
    return abs(a - b) <= 1e-9 * max(1.0, abs(b))


def expected(r, key="measured"):
    return (r[key]["median_s"], r[key]["min_s"], r[key]["max_s"], r["predicted_s"])


with tempfile.TemporaryDirectory() as tmp:
    pages = {}
    for form, log in (("SHDR", SHDR), ("Streams", STREAMS)):
        r = run("check-log", COVER, "-m", "hurco-vmx24", *log, "--json")
        doc = json.loads(r.stdout or "{}")
        prog = (doc.get("programs") or [{}])[0]
        check(r.returncode == 0 and prog.get("usable_runs") == 1,
              f"{form}: check-log finds the usable run ({r.stderr[-200:]})")
        page_path = os.path.join(tmp, form + ".html")
        r = run("report", COVER, "-m", "hurco-vmx24", "--no-removal", *log, "-o", page_path)
        check(r.returncode == 0 and os.path.exists(page_path),
              f"{form}: report --log writes the page ({r.stderr[-300:]})")
        check("1 run in the logs, 1 usable" in r.stderr, f"{form}: it says what the logs hold")
        page = open(page_path, encoding="utf-8").read() if os.path.exists(page_path) else ""
        pages[form] = page_path
        check("Measured on the machine" in page, f"{form}: the page has the measured part")

        # The measured series over the predicted one.
        series = chart_series(page, "p1-progress")
        names = [s["name"] for s in series]
        check(names == ["predicted", "measured, run 1"], f"{form}: predicted and measured lines {names}")
        if len(series) == 2:
            predicted, measured = series
            run_s = doc["runs"][0]["time_s"]
            check(abs(measured["t"][-1] - run_s) < 1e-4 * run_s and measured["t"][0] == 0,
                  f"{form}: the measured line runs from the cycle start to the end "
                  f"({measured['t'][-1]} s, check-log {run_s} s)")
            check(abs(predicted["t"][-1] - prog["predicted_s"]) < 1e-4 * prog["predicted_s"],
                  f"{form}: the predicted line ends at the predicted time "
                  f"({predicted['t'][-1]} s, check-log {prog['predicted_s']} s)")
            lines = sum(1 for _ in open(COVER))
            for s in series:
                v = s["v"]
                check(len(v) >= 50 and all(a <= b for a, b in zip(v, v[1:])) and
                      1 <= v[0] and v[-1] <= lines and v[-1] > 0.9 * lines,
                      f"{form}: {s['name']}: lines of the program, in order, to its end "
                      f"({len(v)} points, {v[:1]} to {v[-1:]})")
            check(all(a <= b for a, b in zip(measured["t"], measured["t"][1:])),
                  f"{form}: the measured times run forward")

        # The tables: the numbers check-log prints.
        ops = rows(page, "measured-operations")
        want = [expected(op) for op in prog.get("operations", [])]
        check(len(ops) == len(want) == 1 and all(same(a, b) for o, w in zip(ops, want)
                                                 for a, b in zip(o, w)),
              f"{form}: the operation row equals check-log's ({ops} vs {want})")
        total = rows(page, "measured-operations", "tfoot")
        check(len(total) == 1 and all(same(a, b) for a, b in zip(total[0], expected(prog))),
              f"{form}: the program row equals check-log's ({total} vs {expected(prog)})")
        blocks = rows(page, "measured-blocks")
        want = [expected(b) for b in prog.get("worst_blocks", [])]
        check(len(blocks) == len(want) >= 5 and all(same(a, b) for o, w in zip(blocks, want)
                                                    for a, b in zip(o, w)),
              f"{form}: the worst blocks equal check-log's ({len(blocks)} rows)")
        first = prog.get("worst_blocks", [{}])[0].get("text", "")
        check(first and htmllib.escape(first) in page, f"{form}: the worst block's line is shown")
        check(not re.search(r"(https?:)?//[a-z0-9.-]+\.[a-z]{2,}/", page, re.I) and
              not re.search(r"<(script|img|iframe)[^>]*\bsrc=|<link\b", page, re.I),
              f"{form}: still self-contained")

    # Without --log the page is as before; the log's options need one.
    plain = os.path.join(tmp, "plain.html")
    r = run("report", COVER, "-m", "hurco-vmx24", "--no-removal", "-o", plain)
    check(r.returncode == 0 and "Measured on the machine" not in open(plain).read(),
          "without --log no measured part")
    r = run("report", COVER, "-m", "hurco-vmx24", "--devices", DEVICES, "-o", plain)
    check(r.returncode == 1 and "--log" in r.stderr, "--devices without --log is a usage error")

    # A log that holds another program's run only: said in the page, nothing drawn.
    other = os.path.join(tmp, "other.html")
    r = run("report", COVER, "-m", "hurco-vmx24", "--no-removal", "--log",
            os.path.join(DATA, "held-run.shdr"), "--devices", DEVICES, "-o", other)
    page = open(other).read() if os.path.exists(other) else ""
    check(r.returncode == 0 and "The logs hold no run of this program." in page and
          'id="p1-progress"' not in page, f"no run of the program: said, not drawn ({r.returncode})")

    # A log that cannot be read: no page.
    bad = os.path.join(tmp, "bad.html")
    r = run("report", COVER, "-m", "hurco-vmx24", "--log", DEVICES, "-o", bad)
    check(r.returncode == 2 and not os.path.exists(bad), "a device file given as a log: exit 2, no page")

    if not headless_page.chromium():
        print("SKIP: chromium is not installed; the page was not rendered")
        sys.exit(1 if failures else SKIP)
    status, dom, errors = headless_page.render(pages["SHDR"])
    check(status == 0 and "<svg" in dom, f"chromium loaded the page (exit {status})")
    check(not errors, f"no script errors in the console {errors[:3]}")
    charts = re.findall(r'<svg class="time-chart"', dom)
    ready = re.search(r'data-charts-ready="(\d+)"', dom)
    check(ready is not None and int(ready.group(1)) == len(charts) == 3,
          f"the script set up the 3 time charts (power, removal, the measured line) ({len(charts)})")
    progress = dom.split('id="p1-progress"')[1].split("</figure>")[0] if 'id="p1-progress"' in dom else ""
    paths = re.findall(r'<path class="line"[^>]*\sd="([^"]*)"', progress)
    check(len(paths) == 2 and min(len(re.findall(r"[ML]", d)) for d in paths) >= 50,
          f"the browser has both lines drawn with their points ({len(paths)})")

print(f"{len(failures)} failed")
sys.exit(1 if failures else 0)
