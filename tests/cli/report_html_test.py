#!/usr/bin/env python3
"""`ncjoule report` in a real headless Chromium: the page is self-contained (no external URL),
loads without script errors, its charts have data, and a screenshot of it is not blank.

Exits 77 (ctest SKIP_RETURN_CODE) when chromium is not installed."""
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

import headless_page

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
PROGRAMS = os.path.join(ROOT, "samples/programs")
HAAS = os.path.join(ROOT, "samples/machines/haas-vf0-pavanaskar2014.toml")
SKIP = 77
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def png_pixels(path):
    """Decodes an 8-bit RGB/RGBA non-interlaced PNG (what Chromium writes): (width, height, rows)."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and color in (2, 6) and interlace == 0, "unexpected PNG format"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    bpp = 3 if color == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * bpp
    rows, prev = [], bytearray(stride)
    for y in range(height):
        filt = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if filt == 1:
                line[i] = (line[i] + a) & 255
            elif filt == 2:
                line[i] = (line[i] + b) & 255
            elif filt == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif filt == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return width, height, bpp, rows


chromium = headless_page.chromium()
if not chromium:
    print("SKIP: chromium is not installed (scripts/setup.sh installs it); the HTML report was not checked in a browser")
    sys.exit(SKIP)

with tempfile.TemporaryDirectory() as tmp:
    page = os.path.join(tmp, "report.html")
    x = os.path.join(PROGRAMS, "pavanaskar-facing-x.ngc")
    y = os.path.join(PROGRAMS, "pavanaskar-facing-y.ngc")
    with open(os.path.splitext(x)[0] + ".stock") as f:
        stock = f.read().strip()
    r = subprocess.run([NCJOULE, "report", x, y, "--machine", HAAS, "--stock", stock, "-o", page],
                       capture_output=True, text=True)
    check(r.returncode == 0 and os.path.exists(page), f"report written ({r.stderr.strip()[:200]!r})")
    check(not [n for n in os.listdir(tmp) if n != "report.html"], "no temporary file left behind")
    with open(page, encoding="utf-8") as f:
        html = f.read()
    check(not re.search(r"(https?:)?//[a-z0-9.-]+\.[a-z]{2,}/", html, re.I),
          "no external URL anywhere in the page")
    check(not re.search(r"<(script|img|iframe)[^>]*\bsrc=|<link\b", html, re.I),
          "no script, image or style sheet loaded from elsewhere")
    for title in ["Comparison", "Power over time", "Material removal rate over time",
                  "Energy per operation, by component", "Energy per component",
                  "Energy per program, by component"]:
        check(title in html, f"section '{title}'")

    # The operation table has the air-cutting time of each operation (14.7 s of the X facing's
    # feed moves cut nothing: its entry, exit and step-over moves).
    table = html.split("<th class=\"name\">Operation</th>")[1].split("</table>")[0]
    check("<th>Air cut</th>" in table and "<td>14.7 s</td>" in table,
          "the operation table shows air cutting per operation")

    # Warnings are shown in the page, escaped, not only counted: a program with no F word on its
    # first feed move and no stock.
    warned = os.path.join(tmp, "warned.ngc")
    with open(warned, "w") as f:
        f.write("G21 G90\nT1 M6\nS30000 M3\nG0 X0 Y0 Z1\nG1 Z-1 F100\nX40 <b>\nM2\n")
    page2 = os.path.join(tmp, "warned.html")
    r = subprocess.run([NCJOULE, "report", warned, "--machine", HAAS, "-o", page2],
                       capture_output=True, text=True)
    with open(page2, encoding="utf-8") as f:
        html2 = f.read()
    check("warning(s) while estimating" in html2 and "<li class=\"note\">" in html2,
          "warnings listed in the page")
    check("<b>" not in html2.split("warning(s) while estimating")[1],
          "program text in warnings is escaped")

    # A page stays under 1 MB for a program under 10k blocks: here 6000 blocks of an inch
    # program (zig-zag passes at depths that change the power, and arcs), whose page gives its
    # volumes in in^3 and names where its cost's prices came from.
    big = os.path.join(tmp, "many-blocks.ngc")
    with open(big, "w") as f:
        f.write("G20 G90 G17\nT1 M6\nS5000 M3\nG0 X0 Y0 Z0.1\n")
        for i in range(3000):
            pass_y = 0.01 * i
            depth = -0.02 - 0.01 * (i % 7)
            f.write(f"G1 X{4 if i % 2 == 0 else 0:.4f} Y{pass_y:.4f} Z{depth:.4f} F{40 + 10 * (i % 5)}\n")
            f.write(f"G2 X{4 if i % 2 == 0 else 0:.4f} Y{pass_y + 0.005:.4f} R0.01\n")
        f.write("G0 Z1\nM30\n")
    big_page = os.path.join(tmp, "many-blocks.html")
    r = subprocess.run([NCJOULE, "report", big, "--machine", HAAS, "--tool", "1:flat:0.25in",
                        "--stock", "box:-0.2in,-0.2in,-0.2in,4.2in,30.2in,0", "--price", "0.3",
                        "-o", big_page], capture_output=True, text=True)
    size = os.path.getsize(big_page) if os.path.exists(big_page) else 0
    check(r.returncode == 0 and 0 < size < 1_000_000,
          f"a page of a 6000-block program is under 1 MB ({size} bytes; {r.stderr[-200:]!r})")
    with open(big_page, encoding="utf-8") as f:
        html3 = f.read()
    check("Material removed" in html3 and "in&sup3;" in html3 and "mm&sup3;" not in html3,
          "an inch program's page gives volumes in in^3 only")
    check("MRR up to" in html3 and "in\u00b3/min" in html3 and "mm\u00b3/s" not in html3,
          "an inch program's toolpath tooltips give the removal rate in in^3/min")
    check("Cycle time" in html3 and "Electricity used" in html3 and "Cost of the run" in html3,
          "the cards are titled in plain words")
    check("/kWh (from command line (--price))" in html3 and "0.300" in html3,
          "the cost card names where the price came from")

    # A page that cannot be written leaves no file and says why, with exit 3.
    bad = os.path.join(tmp, "no-such-dir", "r.html")
    r = subprocess.run([NCJOULE, "report", x, "--machine", HAAS, "--stock", stock, "-o", bad],
                       capture_output=True, text=True)
    check(r.returncode == 3 and "no-such-dir" in r.stderr, f"unwritable output: exit 3 ({r.returncode})")

    status, dom, errors = headless_page.render(page, chromium)
    check(status == 0 and "<svg" in dom, f"chromium loaded the page (exit {status})")
    check(not errors, f"no script errors in the console {errors[:3]}")
    charts = re.findall(r'<svg class="time-chart"', dom)
    ready = re.search(r'data-charts-ready="(\d+)"', dom)
    check(ready is not None and int(ready.group(1)) == len(charts) == 5,
          f"the script set up all {len(charts)} time charts (2 programs x 2 + the comparison)")
    lines = re.findall(r'<path class="line"[^>]*\sd="([^"]*)"', dom)
    points = [len(re.findall(r"[ML]", d)) for d in lines]
    check(len(lines) == 6 and min(points) >= 20, f"every line has points: {points}")
    check(max(points) <= 2000, "at most 2000 points per line")
    bars = re.findall(r'<rect class="bar"', dom)
    check(len(bars) >= 10, f"bar charts have bars ({len(bars)})")
    check("pavanaskar-facing-x.ngc" in dom and "best" in dom, "the comparison names the best")
    # The toolpath, from above and from the front, for each program: feed moves coloured by
    # power, each with a tooltip naming its source line; rapids dashed.
    views = re.findall(r'<svg class="toolpath-view"', dom)
    check(len(views) == 4, f"XY and XZ views for both programs ({len(views)})")
    feeds = re.findall(r'<path class="feed" data-line="(\d+)" stroke="(#[0-9a-f]{6})"[^>]*>'
                       r'<title>lines? (\d+)(?:-\d+)?: feed, ([^<]*)</title>', dom)
    x_lines = 0
    for program in (x, y):
        with open(program) as f:
            x_lines = max(x_lines, len(f.read().splitlines()))
    # A run of moves drawn in one colour is one path, its tooltip naming the lines it covers.
    check(len(feeds) > 10 and all(a == b for a, _, b, _ in feeds),
          f"feed runs with their lines in a tooltip ({len(feeds)})")
    check(all(1 <= int(a) <= x_lines for a, _, _, _ in feeds), "tooltip lines are lines of the program")
    check(len({c for _, c, _, _ in feeds}) >= 2 and all("W" in t for _, _, _, t in feeds),
          "feed moves in more than one colour of the power scale, with their power")
    check(len(re.findall(r'<path class="rapid"', dom)) > 0, "rapids drawn")
    ops = re.findall(r'<rect class="op"[^>]*><title>([^<]*)</title>', dom)
    check(len(ops) == 2 and all("FACE1" in t and "kJ" in t for t in ops),
          f"the operation timeline: one bar per operation with its numbers ({ops})")

    shot = os.path.join(tmp, "report.png")
    with tempfile.TemporaryDirectory() as profile:
        r = subprocess.run([chromium, *headless_page.FLAGS, "--user-data-dir=" + profile,
                            "--screenshot=" + shot, "--window-size=1280,1800",
                            "--virtual-time-budget=5000", "file://" + page],
                           capture_output=True, text=True, timeout=180)
    check(os.path.exists(shot) and os.path.getsize(shot) > 20000,
          f"screenshot written ({os.path.getsize(shot) if os.path.exists(shot) else 0} bytes)")
    if os.path.exists(shot):
        width, height, bpp, rows = png_pixels(shot)
        check((width, height) == (1280, 1800), f"screenshot is 1280 x 1800 ({width} x {height})")
        colours = set()
        for row in rows[::10]:
            for i in range(0, len(row), bpp * 10):
                colours.add(row[i:i + 3])
        check(len(colours) > 50, f"the screenshot is not blank ({len(colours)} colours sampled)")
        # The toolpath view is drawn: pixels of the power scale's colours near the top of the
        # page (the legend and the feed moves).
        scale = {(0x25, 0x34, 0x94), (0x2c, 0x7f, 0xb8), (0x41, 0xb6, 0xc4), (0x7f, 0xcd, 0xbb),
                 (0xfe, 0xcc, 0x5c), (0xfd, 0x8d, 0x3c), (0xe3, 0x1a, 0x1c)}
        seen = set()
        for row in rows[:1800]:
            for i in range(0, len(row), bpp):
                px = tuple(row[i:i + 3])
                if px in scale:
                    seen.add(px)
        check(len(seen) >= 3, f"the toolpath and its power scale are drawn ({len(seen)} scale colours seen)")
        # The header band is dark and the page below it light: the style sheet applied.
        check(sum(rows[20][:3]) < 200 and sum(rows[1000][3 * 5:3 * 5 + 3]) > 600,
              "dark header band over a light page")
        keep = os.environ.get("NCJOULE_KEEP_SCREENSHOT")
        if keep:
            shutil.copy(shot, keep)

print(f"{len(failures)} failed")
sys.exit(1 if failures else 0)
