#!/usr/bin/env python3
"""Compare ncjoule's predicted times with a real controller's logs.

The data are the NIST Smart Manufacturing Systems Test Bed's (github.com/usnistgov/smstestbed):
MTConnect samples of a Hurco VMX24 (Hurco02) running the CAM-posted programs of the CRADA box,
OP1 to OP3, twenty parts each. The logs say which line is running (Block_Number), the path speed
(Feed_Rate, mm/s), the spindle speed, the tool and the overrides, every 0.12-0.19 s.

    bench/controller_logs.py --repo PATH/TO/smstestbed [-m hurco-vmx24]
                             [--ncjoule build/plugin/ncjoule] [--markdown] [-- EXTRA ncjoule ARGS]

It prints: the runs found and the ones kept (complete, 100% feed override), the measured and
predicted totals, operations and blocks, what the logs show about the control's timing (tool
changes, spindle run-up, stand-stills at M-codes, settling after rapids), and, apart, the same
comparison for the programs kept out as an independent check (OP4, OP5, the cover, the plates).
Standard library only.
"""

import argparse
import calendar
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

# The programs whose runs may be used to choose settings, and the ones kept for an
# independent check only (never used to fit anything; printed in their own table).
NC_DIR = 'tdp/mtc/NC-Code'
MAIN_PROGRAMS = {
    'OP1': 'NIST_MTC_CRADA_BOX_REV-A OP1 (Bottom).NC',
    'OP2': 'NIST_MTC_CRADA_BOX_REV-A OP2 (Front).NC',
    'OP3': 'NIST_MTC_CRADA_BOX_REV-A OP3 (Back).NC',
}
CHECK_PATTERN = re.compile(r'NIST_MTC_CRADA_(BOX_REV-A (OP4|OP5)|COVER_REV-A|PLATE-\d+)\b.*\.NC$')

# Where the logs are. tdp/mtc/PartData is left out: its files are the Split files joined per
# part (the same samples again). tdp/mtc/Raw is left out: Clean holds the same days cleaned.
LOG_DIRS = ('tdp/mtc/Clean', 'tdp/mtc/Split', 'raw')
LOG_FILE = re.compile(r'(^tdp/mtc/(Clean|Split)/[^/]+\.txt$)|(^raw/Hurco\d\d/[^/]+\.txt$)')

MIN_BLOCK_S = 0.5        # blocks shorter than this are below the log's time resolution
FEED_RATIO_TOL = 0.02    # measured path speed / programmed F must be within this of 1.00
LONG_STALL_S = 60.0      # one line taking longer than this means the run was held
CHECK_RATIO_TOL = 0.10   # the check programs' short moves keep their speed below F: looser
IN_MM = 25.4


# ----------------------------------------------------------------------------------------
# Reading the repository: a bare git directory (files read with git) or a work tree.

class Repo:
    """Lists and reads files of the smstestbed repository, bare or checked out."""

    def __init__(self, path):
        self.path = os.path.abspath(path)
        self.bare = os.path.isfile(os.path.join(self.path, 'HEAD')) and \
            os.path.isdir(os.path.join(self.path, 'objects'))
        self.missing = []            # files listed but whose contents are not here
        self._tree = None

    def valid(self):
        if self.bare:
            return self._git('rev-parse', '--verify', '-q', 'HEAD^{tree}') is not None
        return os.path.isdir(os.path.join(self.path, 'tdp', 'mtc'))

    def _git(self, *args, data=None):
        try:
            out = subprocess.run(['git', '--git-dir=' + self.path] + list(args), input=data,
                                 capture_output=True, check=True)
        except (OSError, subprocess.CalledProcessError):
            return None
        return out.stdout

    def tree(self):
        """{path: object id (bare) or absolute path (work tree)} of every file."""
        if self._tree is not None:
            return self._tree
        self._tree = {}
        if self.bare:
            out = self._git('ls-tree', '-r', '-z', 'HEAD', '--', *LOG_DIRS, NC_DIR) or b''
            for rec in out.split(b'\0'):
                if not rec:
                    continue
                meta, name = rec.split(b'\t', 1)
                kind, oid = meta.split()[1:3]
                if kind == b'blob':
                    self._tree[name.decode('utf-8', 'replace')] = oid.decode()
        else:
            for top in LOG_DIRS + (NC_DIR,):
                base = os.path.join(self.path, top)
                for d, _, files in os.walk(base):
                    for f in files:
                        full = os.path.join(d, f)
                        self._tree[os.path.relpath(full, self.path).replace(os.sep, '/')] = full
        return self._tree

    def read_many(self, names):
        """{name: text} for the names whose contents are here; the rest go to self.missing."""
        tree = self.tree()
        out = {}
        if self.bare:
            # One git process for all blobs: thousands of small daily files otherwise take long.
            oids = [tree[n] for n in names]
            raw = self._git('cat-file', '--batch', data=('\n'.join(oids) + '\n').encode()) or b''
            pos = 0
            for n in names:
                end = raw.index(b'\n', pos)
                header = raw[pos:end].split()
                pos = end + 1
                if len(header) < 3 or header[1] != b'blob':      # "<oid> missing"
                    self.missing.append(n)
                    continue
                size = int(header[2])
                out[n] = raw[pos:pos + size].decode('utf-8', 'replace')
                pos += size + 1
        else:
            for n in names:
                try:
                    with open(tree[n], 'rb') as f:
                        data = f.read()
                except OSError:
                    self.missing.append(n)
                    continue
                if data.startswith(b'version https://git-lfs'):   # an LFS pointer, not data
                    self.missing.append(n)
                    continue
                out[n] = data.decode('utf-8', 'replace')
        return out


# ----------------------------------------------------------------------------------------
# The G-code: enough of it to know what each line does and how long its moves are.

WORD = re.compile(r'([A-Z])\s*([-+]?(?:\d+\.?\d*|\.\d+))')


class Line:
    """One line of a program: its motion ('rapid', 'feed', 'arc', 'home', 'cycle' or None),
    modal feed (mm/s), length and axis displacements (mm), whether its start and end are known
    (not after a machine home, a tool change or another work offset), M-codes, S, T."""
    __slots__ = ('no', 'text', 'code', 'motion', 'feed_mm_s', 'length_mm', 'delta', 'axes',
                 'known', 'tool_change', 'tool', 'mcodes', 'spindle', 'cycle')


class Program:
    """One NC file read line by line, with modal state, as the Hurco reads it.

    Line numbers are 1-based and count every line of the file (%, comments included):
    that is how the log's Block_Number counts (see block_meaning)."""

    def __init__(self, name, path, text):
        self.name, self.path, self.text = name, path, text
        self.lines = []
        self.m6 = []                   # (line, tool) of every tool change
        self.end_line = None           # the M30/M2 line
        self._read(text.replace('\r', '').split('\n'))

    def _read(self, raw_lines):
        scale, absolute, motion, feed, cycle, wcs = IN_MM, True, None, None, None, 54.0
        pos = {'X': 0.0, 'Y': 0.0, 'Z': 0.0}
        known = {'X': False, 'Y': False, 'Z': False}   # machine homes make a position unknown
        for no, raw in enumerate(raw_lines, 1):
            ln = Line()
            ln.no, ln.text = no, raw.strip()
            body = re.sub(r'\(.*?\)|;.*', '', raw.upper()).strip()
            words = WORD.findall(body)
            ln.code = bool(words)
            g = [float(v) for k, v in words if k == 'G']
            m = [int(float(v)) for k, v in words if k == 'M']
            w = {k: float(v) for k, v in words if k not in 'GMN'}
            home = any(abs(x - 28) < 1e-6 or abs(x - 53) < 1e-6 for x in g)
            for x in g:
                if x in (0, 1, 2, 3):
                    motion, cycle = int(x), None
                elif x in (73, 74, 76, 81, 82, 83, 84, 85, 86, 89):
                    motion = cycle = int(x)
                elif x == 80:
                    cycle = None
                    motion = None if motion not in (0, 1, 2, 3) else motion
                elif x == 20:
                    scale = IN_MM
                elif x == 21:
                    scale = 1.0
                elif x == 90:
                    absolute = True
                elif x == 91:
                    absolute = False
                elif 54 <= x <= 59 and x != wcs:
                    wcs = x
                    known = {a: False for a in known}          # another work offset
            if 'F' in w:
                feed = w['F'] * scale / 60.0
            ln.feed_mm_s, ln.mcodes, ln.cycle = feed, m, cycle
            ln.spindle = w.get('S')
            ln.tool = int(w['T']) if 'T' in w else None
            ln.tool_change = 6 in m
            if ln.tool_change:
                self.m6.append((no, ln.tool))
                known = {a: False for a in known}   # the control moves to its change position
            if (2 in m or 30 in m) and self.end_line is None:
                self.end_line = no
            axes = [a for a in 'XYZ' if a in w]
            ln.axes = ''.join(axes)
            ln.motion = None
            ln.length_mm = 0.0
            ln.delta = (0.0, 0.0, 0.0)
            ln.known = True
            if axes and home:
                ln.motion, ln.known = 'home', False
                for a in axes:
                    known[a] = False
            elif axes and motion is not None:
                new = dict(pos)
                for a in axes:
                    new[a] = w[a] * scale if absolute else pos[a] + w[a] * scale
                ln.known = all(known[a] for a in axes)
                if motion in (2, 3) and ('I' in w or 'J' in w):
                    ln.length_mm = arc_length(pos, new, w.get('I', 0) * scale,
                                              w.get('J', 0) * scale, motion == 2)
                else:
                    ln.length_mm = math.dist([pos[a] for a in 'XYZ'], [new[a] for a in 'XYZ'])
                ln.motion = {0: 'rapid', 1: 'feed', 2: 'arc', 3: 'arc'}.get(motion, 'cycle')
                ln.delta = tuple(new[a] - pos[a] for a in 'XYZ')
                pos = new
                for a in axes:
                    known[a] = True
            self.lines.append(ln)

    def line(self, no):
        return self.lines[no - 1] if 1 <= no <= len(self.lines) else None


def arc_length(p0, p1, i, j, clockwise):
    """Length of an XY arc (G17) with centre offsets I, J, plus its Z travel."""
    cx, cy = p0['X'] + i, p0['Y'] + j
    r = math.hypot(i, j)
    a0 = math.atan2(p0['Y'] - cy, p0['X'] - cx)
    a1 = math.atan2(p1['Y'] - cy, p1['X'] - cx)
    sweep = (a0 - a1) if clockwise else (a1 - a0)
    sweep %= 2 * math.pi
    if sweep < 1e-9:
        sweep = 2 * math.pi                                  # start = end: a full circle
    return math.hypot(r * sweep, p1['Z'] - p0['Z'])


# ----------------------------------------------------------------------------------------
# The logs: timestamp|key|value|key|value... on change only; one timeline per machine.

_MINUTE = {}


def epoch(ts):
    """Seconds since 1970 of an MTConnect time stamp like 2017-02-07T19:38:27.6093750Z."""
    head = ts[:16]
    base = _MINUTE.get(head)
    if base is None:
        base = calendar.timegm(time.strptime(head, '%Y-%m-%dT%H:%M'))
        _MINUTE[head] = base
    return base + float(ts[17:].rstrip('Z') or 0)


class Source:
    """One log file: which machine, and the time span it covers without a gap."""

    def __init__(self, name, machine, t0, t1):
        self.name, self.machine, self.t0, self.t1 = name, machine, t0, t1


def load_logs(repo):
    """All samples of all log files, deduplicated, as {machine: [(t, key, value, source)]}.

    The Split files are pieces of Clean files (some of which are missing here), so a sample
    may be in two files: it is kept once. Each file's span is kept, to tell a run that lies
    within one file (no gap) from one that straddles the gaps between pieces."""
    names = sorted(n for n in repo.tree() if LOG_FILE.match(n))
    texts = repo.read_many(names)
    timelines, sources, seen = {}, [], set()
    for name in names:
        text = texts.get(name)
        if text is None:
            continue
        mach = re.search(r'(Hurco\d\d)', name, re.I)
        machine = mach.group(1).capitalize() if mach else 'unknown'
        events = timelines.setdefault(machine, [])
        t_first = t_last = None
        for rec in repair_records(text):
            parts = rec.split('|')
            if len(parts) < 3 or not parts[0][:2] == '20':
                continue
            try:
                t = epoch(parts[0])
            except ValueError:
                continue
            t_first = t if t_first is None else min(t_first, t)
            t_last = t if t_last is None else max(t_last, t)
            src = len(sources)
            for k, v in zip(parts[1::2], parts[2::2]):
                key = (machine, parts[0], k, v)
                if key in seen:
                    continue
                seen.add(key)
                events.append((t, k, v, src))
        if t_first is not None:
            sources.append(Source(name, machine, t_first, t_last))
    for events in timelines.values():
        events.sort(key=lambda e: e[0])
    return timelines, sources, len(names)


STAMP = re.compile(r'^\d{4}-\d\d-\d\dT')


REPAIRED = [0]                   # records glued back together (see repair_records)


def repair_records(text):
    """The records of a log file, each on one line.

    NIST's cleaning script (tdp/mtc/Clean/HurcoDataClean.py) put a line break before every
    "2017" to split records, also inside values: Block_Number 22017 became "...|2" and a line
    "2017". A line that does not start with a time stamp is glued back to the one before."""
    out = []
    for rec in text.splitlines():
        rec = rec.strip()
        if not rec:
            continue
        if STAMP.match(rec) or not out:
            out.append(rec)
        else:
            out[-1] += rec
            REPAIRED[0] += 1
    return out


class Run:
    """One cycle start to program end (or to whatever ended it) on one machine."""

    def __init__(self, machine, t0, state):
        self.machine, self.t0, self.t1 = machine, t0, None
        self.state0 = dict(state)             # overrides etc. as last logged (maybe long ago)
        self.statuses = []                    # (t, status) after the start
        self.blocks = []                      # (t, line) each time Block_Number changed
        self.tools = []                       # (t, tool, line at the time)
        self.feed = []                        # (t, mm/s)
        self.spindle = []                     # (t, rpm)
        self.overrides = {'Feed_Override': [], 'Rapid_Override': [], 'Spindle_Override': []}
        self.names = []                       # (t, Program_Name_Running)
        self.sources = set()
        self.end = None                       # 'completed' or why it ended
        self.program = None                   # matched Program
        self.why = []                         # reasons it is not kept
        self.feed_ratio = None
        self.rapid_peak = None


def find_runs(timelines):
    """Cut each machine's timeline into runs: Program_Status ACTIVE after a stop/end starts
    one; PROGRAM_COMPLETED ends it. Holds and stops in between stay in the run (and mark it)."""
    runs = []
    for machine, events in timelines.items():
        state, run = {}, None
        for t, k, v, src in events:
            if k == 'Program_Status':
                if run is None and v == 'ACTIVE':
                    run = Run(machine, t, state)
                    # the Block_Number 0 and the feed at cycle start come just before ACTIVE
                    run.blocks.append((t, safe_int(state.get('Block_Number'), 0)))
                    run.feed.append((t, safe_float(state.get('Feed_Rate'), 0.0)))
                    run.spindle.append((t, safe_float(state.get('Spindle_Speed'), 0.0)))
                    run.sources.add(src)
                elif run is not None:
                    run.statuses.append((t, v))
                    if v in ('PROGRAM_COMPLETED', 'READY', 'UNAVAILABLE'):
                        run.t1, run.end = t, ('completed' if v == 'PROGRAM_COMPLETED' else v)
                        runs.append(run)
                        run = None
            elif run is not None:
                run.sources.add(src)
                if k == 'Block_Number':
                    n = safe_int(v)
                    if n is not None and (not run.blocks or run.blocks[-1][1] != n):
                        run.blocks.append((t, n))
                elif k == 'Current_Tool':
                    tool = safe_float(v)
                    if tool is not None:
                        run.tools.append((t, int(tool), run.blocks[-1][1] if run.blocks else 0))
                elif k == 'Feed_Rate':
                    f = safe_float(v)
                    if f is not None:
                        run.feed.append((t, f))
                elif k == 'Spindle_Speed':
                    s = safe_float(v)
                    if s is not None:
                        run.spindle.append((t, s))
                elif k in run.overrides:
                    o = safe_float(v)
                    if o is not None:
                        run.overrides[k].append((t, o))
                elif k == 'Program_Name_Running':
                    run.names.append((t, v))
                elif k == 'avail' and v == 'UNAVAILABLE':
                    run.t1, run.end = t, 'machine unavailable'
                    runs.append(run)
                    run = None
            state[k] = v
    return runs


def safe_int(v, default=None):
    try:
        return int(float(v))
    except (TypeError, ValueError):
        return default


def safe_float(v, default=None):
    try:
        return float(v)
    except (TypeError, ValueError):
        return default


# ----------------------------------------------------------------------------------------
# Which program a run ran, and whether it counts.

def match_program(run, programs, sources):
    """The program whose structure the run shows: its tool changes at that program's M6 lines
    with its tool numbers, and its last line its M30 line. The program name the log gives is
    used only to choose among programs of the same structure (the plates), and only when it
    was logged in the same file: across the gaps between Split files it goes stale."""
    last = run.blocks[-1][1] if run.blocks else 0
    seen_tools = [(line, tool) for _, tool, line in run.tools if tool > 0]
    fits = []
    for prog in programs:
        if prog.end_line is None or last != prog.end_line:
            continue
        m6 = set(prog.m6)
        if all((line, tool) in m6 for line, tool in seen_tools):
            fits.append(prog)
    name = logged_name(run)
    if len(fits) > 1 and name:
        named = [p for p in fits if same_name(p.path.split('/')[-1], name)]
        fits = named or fits
    if len(fits) > 1:
        # no name: NIST's Split file of plate k (Plate-Op1-Hurco04-kof20) ran PLATE-k
        for src in run.sources:
            m = re.search(r'Plate-Op1-Hurco\d\d-(\d+)of', sources[src].name)
            if m:
                hinted = [p for p in fits if p.path.upper().endswith('PLATE-%d.NC' % int(m.group(1)))]
                fits = hinted or fits
    run.logged_name = name
    if fits:
        run.program = fits[0]
        run.ambiguous = len(fits) > 1
    return run.program


def logged_name(run):
    """Program_Name_Running if it was logged in this run or earlier in the same file."""
    if run.names:
        return run.names[-1][1].strip()
    return getattr(run, 'name_same_file', None)


def same_name(file_name, logged):
    """NIST_MTC_CRADA_BOX_REV-A OP1 (Bottom).NC vs NIST_MTC_CRADA_BOX_REV-A_OP1.NC."""
    def key(s):
        s = re.sub(r'\(.*?\)', '', s.upper())
        return re.sub(r'[^A-Z0-9]', '', s.replace('.NC', ''))
    return key(file_name) == key(logged)


def attach_names(runs, timelines, sources):
    """For each run, the program name logged before it within the same log file."""
    for machine, events in timelines.items():
        last = {}                              # source -> last Program_Name_Running seen
        mine = sorted((r for r in runs if r.machine == machine), key=lambda r: r.t0)
        i = 0
        for t, k, v, src in events:
            while i < len(mine) and mine[i].t0 <= t:
                first_src = min(mine[i].sources) if mine[i].sources else None
                if first_src is not None and first_src in last:
                    mine[i].name_same_file = last[first_src]
                i += 1
            if k == 'Program_Name_Running':
                last[src] = v.strip()


def within_one_source(run, sources):
    """True when one log file covers the whole run (no gap between Split pieces inside)."""
    return any(s.t0 <= run.t0 and run.t1 <= s.t1 + 1e-6
               for s in sources if s.machine == run.machine)


def judge_run(run, sources):
    """Why a run is not a complete, undisturbed run of its program (empty list: it is)."""
    why = []
    prog = run.program
    if run.end != 'completed':
        why.append('ended: ' + str(run.end))
    if not within_one_source(run, sources):
        why.append('spans a gap between log files')
    odd = sorted({s for _, s in run.statuses if s not in ('ACTIVE', 'PROGRAM_COMPLETED')})
    if odd:
        why.append('status ' + '/'.join(odd))
    if prog is None:
        return why + ['no program file fits (ends at line %d)' % (run.blocks[-1][1] if run.blocks else 0)]
    starts = [n for _, n in run.blocks if n > 0]
    first_m6 = prog.m6[0][0] if prog.m6 else prog.end_line
    if not starts or starts[0] > first_m6 + 1:
        why.append('does not start at the top (first line %s)' % (starts[0] if starts else '-'))
    if any(b2 < b1 for (_, b1), (_, b2) in zip(run.blocks[1:], run.blocks[2:])):
        why.append('lines run backwards (restart)')
    longest = max((t2 - t1 for (t1, _), (t2, _) in zip(run.blocks, run.blocks[1:])), default=0)
    if longest > LONG_STALL_S:
        why.append('held %.0f s on one line' % longest)
    return why


def override_values(run, key):
    """Every value the override had during the run, starting with the one logged before it."""
    vals = [safe_float(run.state0.get(key))] + [v for _, v in run.overrides[key]]
    return [v for v in vals if v is not None]


def measured_feed_ratio(run):
    """Path speed over programmed F while steady feed lines run: the feed override the run
    really had. The log's Feed_Override is not to be trusted alone (see the report)."""
    prog = run.program
    ratios = []
    bi = 0
    for t, f in run.feed:
        while bi + 1 < len(run.blocks) and run.blocks[bi + 1][0] <= t:
            bi += 1
        t_in, n = run.blocks[bi]
        if t - t_in < 0.1 or f <= 0:
            continue                          # just switched: the speed may be the last line's
        ln = prog.line(n)
        nxt = prog.line(n + 1)
        if not ln or ln.motion not in ('feed', 'arc') or not ln.feed_mm_s:
            continue
        if nxt is not None and nxt.code and nxt.motion not in ('feed', 'arc'):
            continue                          # slowing down for what follows
        r = f / ln.feed_mm_s
        if 0.5 < r < 2.0:
            ratios.append(r)
    return statistics.median(ratios) if len(ratios) >= 10 else None


def rapid_peak(run):
    """Highest path speed logged in the run, mm/s (the rapids, at the rapid override)."""
    return max((f for _, f in run.feed), default=None)


def select_runs(runs, programs, sources):
    """Complete runs of each program, and among them the ones at 100% feed override."""
    for run in runs:
        match_program(run, programs, sources)
        run.why = judge_run(run, sources)
        run.complete = not run.why
        run.feed_ratio = measured_feed_ratio(run) if run.program and run.blocks else None
        run.rapid_peak = rapid_peak(run)
        fo = override_values(run, 'Feed_Override')
        ro = override_values(run, 'Rapid_Override')
        run.fo_range = (min(fo), max(fo)) if fo else None
        run.ro_range = (min(ro), max(ro)) if ro else None
        run.kept = False
        if not run.complete:
            continue
        if not fo or run.fo_range[0] < 99 or run.fo_range[1] > 101:
            run.why.append('feed override logged %s' % fmt_range(run.fo_range, '%'))
        if run.feed_ratio is None:
            run.why.append('feed override not measurable')
        elif abs(run.feed_ratio - 1) > FEED_RATIO_TOL:
            run.why.append('feeds ran at %.0f%% of F' % (100 * run.feed_ratio))
        run.kept = not run.why


def choose_rapid_override(kept):
    """Prefer the runs at 100% rapid override; say so when there are none."""
    at100 = [r for r in kept if r.ro_range and r.ro_range[0] >= 99.5 and r.ro_range[1] <= 100.5]
    if at100:
        for r in kept:
            if r not in at100:
                r.kept = False
                r.why.append('rapid override logged %s (runs at 100%% exist)' % fmt_range(r.ro_range, '%'))
        return 100.0, at100
    return None, kept


def fmt_range(rng, unit=''):
    if not rng:
        return 'unknown'
    a, b = rng
    return ('%.0f%s' % (a, unit)) if abs(a - b) < 0.5 else ('%.0f-%.0f%s' % (a, b, unit))


# ----------------------------------------------------------------------------------------
# ncjoule's prediction.

def run_ncjoule(ncjoule, prog, machine, extra, workdir):
    """ncjoule estimate --json for one program; retried while the binary is being rebuilt."""
    path = os.path.join(workdir, prog.path.split('/')[-1])
    with open(path, 'w', encoding='utf-8', newline='') as f:
        f.write(prog.text)
    cmd = [ncjoule, 'estimate', '--json', path, '-m', machine, '--no-removal'] + extra
    last = ''
    for _ in range(40):                       # up to ~2 minutes: a rebuild may be under way
        if not os.path.exists(ncjoule):
            last = 'binary missing'
            time.sleep(3)
            continue
        try:
            out = subprocess.run(cmd, capture_output=True, text=True)
        except OSError as e:
            last = str(e)
            time.sleep(3)
            continue
        if out.stdout.strip():
            try:
                return json.loads(out.stdout)
            except ValueError:
                last = 'unreadable JSON'
        else:
            # a crash (negative code) is typical of a library rebuilt before the binary
            last = 'exit code %d %s' % (out.returncode, out.stderr.strip()[-300:])
        time.sleep(3)
    raise RuntimeError('ncjoule failed on %s: %s' % (prog.name, last))


class Prediction:
    def __init__(self, doc):
        self.total = doc['time_s']
        self.per_line = {}
        self.kind = {}
        for b in doc['blocks']:
            self.per_line[b['line']] = self.per_line.get(b['line'], 0.0) + b['time_s']
            self.kind[b['line']] = b['kind']
        self.ops = [(o.get('name', ''), o.get('tool'), o['line'], o['time_s'])
                    for o in doc.get('operations', [])]

    def between(self, a, b):
        """Predicted time of lines a <= line < b."""
        return sum(t for ln, t in self.per_line.items() if a <= ln < b)


# ----------------------------------------------------------------------------------------
# Measurements from the kept runs.

def groups(run):
    """The run as (first line, next line, start, duration): each time Block_Number changed.

    A line shorter than a sample period may never show; its time then falls to the line
    before it, so a group is lines first <= line < next, compared with the same lines'
    prediction. The last group runs to PROGRAM_COMPLETED."""
    out = []
    marks = run.blocks + [(run.t1, None)]
    for (t, n), (t2, n2) in zip(marks, marks[1:]):
        out.append((n, n2 if n2 is not None else n + 1, t, t2 - t))
    return out


def op_bounds(run, pred):
    """Measured duration of each operation: from its M6 line showing (cycle start for the
    first) to the next operation's M6 line showing (program end for the last)."""
    starts = []
    for i, (_, _, line, _) in enumerate(pred.ops):
        if i == 0:
            starts.append(run.t0)
            continue
        t = next((t for t, n in run.blocks if n >= line), None)
        starts.append(t)
    starts.append(run.t1)
    return [(b - a) if a is not None and b is not None else None
            for a, b in zip(starts, starts[1:])]


def stationary_time(run, t0, t1):
    """Seconds of [t0, t1) with the path speed logged as 0 (the axes standing still)."""
    still, last_t, last_f = 0.0, t0, None
    for t, f in run.feed:
        if t <= t0:
            last_f = f
            continue
        if t >= t1:
            break
        if last_f is not None and last_f <= 0.05:
            still += t - last_t
        last_t, last_f = t, f
    if last_f is not None and last_f <= 0.05:
        still += t1 - last_t
    return still


def spindle_ramps(run, up=True):
    """Spindle speed changes seen in a run, as straight-line fits.

    Returns [(t_zero, slope rpm/s, top rpm)] for each run-up from standstill (up=True, ended
    by the first sample lower than the one before) or run-down to standstill: the samples strictly between 1500 rpm and 500 rpm below the top
    are fitted, as the first and last samples of a ramp may be missing (samples are taken
    every 0.12-0.19 s and only logged on change). t_zero is when the fitted line is at 0 rpm
    (the start of a run-up, the end of a run-down)."""
    out, seg, prev = [], None, 0.0
    for t, s in run.spindle:
        rising = s > prev + 1
        falling = s < prev - 1
        if seg is None:
            if up and prev <= 1 and rising:
                seg = [(t, s)]
            elif not up and prev >= 1000 and falling:
                seg = [(t, prev), (t, s)]
        elif up:
            if falling:                     # past the top: the run-up ended at the last sample
                out.append(seg)
                seg = None
            else:
                seg.append((t, s))
        else:
            if rising:
                seg = None                  # speeding up again before standstill: not a stop
            else:
                seg.append((t, s))
                if s <= 1:
                    out.append(seg)
                    seg = None
        prev = s
    fits = []
    for seg in out:
        top = max(s for _, s in seg) if up else seg[0][1]
        pts = [(t, s) for t, s in seg if 1500 < s < top - 500]
        if len(pts) < 3:
            continue
        a_b = fit_line(pts)
        if not a_b or (a_b[1] <= 0) != (not up):
            continue
        a, b = a_b
        fits.append((-a / b, abs(b), top))
    return fits


# ----------------------------------------------------------------------------------------
# Output: plain text or markdown tables.

class Out:
    def __init__(self, markdown):
        self.md = markdown

    def title(self, text, level=2):
        if self.md:
            print('\n' + '#' * level + ' ' + text + '\n')
        else:
            print('\n' + text + '\n' + ('=' if level <= 2 else '-') * len(text))

    def para(self, text):
        print(text if self.md else text)
        print()

    def bullets(self, items):
        for it in items:
            print('- ' + it)
        print()

    def table(self, head, rows):
        rows = [[cell(c) for c in r] for r in rows]
        if self.md:
            head = [h.replace('|', '\\|') for h in head]
            rows = [[c.replace('|', '\\|') for c in r] for r in rows]
            print('| ' + ' | '.join(head) + ' |')
            print('|' + '|'.join('---' for _ in head) + '|')
            for r in rows:
                print('| ' + ' | '.join(r) + ' |')
        else:
            w = [max([len(h)] + [len(r[i]) for r in rows]) for i, h in enumerate(head)]
            print('  '.join(h.ljust(w[i]) for i, h in enumerate(head)))
            print('  '.join('-' * w[i] for i in range(len(head))))
            for r in rows:
                print('  '.join(c.rjust(w[i]) if looks_numeric(c) else c.ljust(w[i])
                                for i, c in enumerate(r)))
        print()


def cell(c):
    if c is None:
        return '-'
    if isinstance(c, float):
        return '%.2f' % c
    return str(c)


def looks_numeric(s):
    return bool(re.match(r'^[-+]?[\d.]+(%| s)?$', s))


def pct(x):
    return '-' if x is None else '%+.1f%%' % (100 * x)


def upct(x):
    return '-' if x is None else '%.1f%%' % (100 * x)


def med(xs):
    xs = [x for x in xs if x is not None]
    return statistics.median(xs) if xs else None


def spread(xs):
    """(min, median, max) as text."""
    xs = [x for x in xs if x is not None]
    if not xs:
        return '-'
    return '%.1f / %.1f / %.1f' % (min(xs), statistics.median(xs), max(xs))


def mad_rel(xs):
    """Median absolute deviation over the median: a robust run-to-run spread."""
    m = statistics.median(xs)
    return statistics.median(abs(x - m) for x in xs) / m if m > 0 else None


def fit_line(points):
    """Least-squares y = a + b x; returns (a, b)."""
    n = len(points)
    if n < 2:
        return None
    mx = sum(x for x, _ in points) / n
    my = sum(y for _, y in points) / n
    sxx = sum((x - mx) ** 2 for x, _ in points)
    if sxx <= 0:
        return None
    b = sum((x - mx) * (y - my) for x, y in points) / sxx
    return my - b * mx, b


# ----------------------------------------------------------------------------------------
# The report's sections.

def report_data(out, repo, n_files, sources, timelines):
    out.title('Data')
    by_dir = {}
    for s in sources:
        d = s.name.rsplit('/', 1)[0]
        d = 'raw/Hurco*' if d.startswith('raw/') else d
        by_dir[d] = by_dir.get(d, 0) + 1
    items = ['repository: %s (%s)' % (repo.path, 'bare git directory' if repo.bare else 'work tree'),
             'log files listed: %d; read: %s' % (n_files, ', '.join('%s %d' % kv for kv in sorted(by_dir.items()))),
             'samples per machine: ' + ', '.join('%s %d' % (m, len(e)) for m, e in sorted(timelines.items()))]
    if REPAIRED[0]:
        items.append('records broken by NIST\'s cleaning script and glued back: %d (a value '
                     'holding "2017", e.g. Block_Number 12017 or 22017, was cut in two; read as '
                     'is, such a run seems to jump back to line 1 or 2)' % REPAIRED[0])
    miss = [m for m in repo.missing]
    if miss:
        items.append('files listed but not in this copy (skipped): %d: %s' % (
            len(miss), ', '.join(m.split('/')[-1] if not m.startswith('raw/') else m for m in miss[:12])
            + (' ...' if len(miss) > 12 else '')))
    out.bullets(items)


def run_label(run, sources):
    """The program a run ran: the matched file, else the logged name or the Split file's name
    (NIST named the pieces Box-OP2-...), marked with ? as no program file fits it."""
    if run.program:
        return run.program.name
    if run.logged_name:
        m = re.search(r'(OP\d|PLATE-?\d*|COVER)', run.logged_name.upper())
        return (m.group(1) if m else run.logged_name) + '?'
    for src in sorted(run.sources):
        m = re.search(r'Box-(OP\d)', sources[src].name)
        if m:
            return m.group(1) + '?'
    return '?'


def log_file(run, sources):
    """The log file(s) a run was read from, short."""
    names = sorted({sources[s].name.split('/')[-1].replace('.txt', '') for s in run.sources})
    return names[0] + (' +%d' % (len(names) - 1) if len(names) > 1 else '')


def other_version(run, label, progs):
    """For a run of OPn that no file fits: where the file would have ended it."""
    prog = progs.get(label.rstrip('?'))
    if run.program or not prog or not run.blocks:
        return ''
    return ' (the file\'s M30 is line %d: another version or a part of the program ran)' % prog.end_line


def report_runs(out, runs, names, sources, progs):
    out.title('Runs found in the logs')
    out.para('A run is Program_Status ACTIVE to PROGRAM_COMPLETED. It is complete when it ran '
             'from the top of the program to its M30 line (Block_Number = the M30 line, tool '
             'changes at the program\'s M6 lines with its tool numbers), with no status but '
             'ACTIVE in between (no FEED_HOLD, no PROGRAM_STOPPED), no line held over %.0f s, '
             'and inside one log file (no gap). It is kept when, besides, its logged feed '
             'override stayed within 99-101%% and its measured path speed on steady feed lines '
             'was within %.0f%% of the programmed F, at 100%% rapid override when such runs '
             'exist.' % (LONG_STALL_S, 100 * FEED_RATIO_TOL))
    rows = []
    for r in sorted(runs, key=lambda r: r.t0):
        label = run_label(r, sources)
        if not any(label.startswith(n) for n in names):
            continue
        rows.append([label, time.strftime('%Y-%m-%d %H:%M', time.gmtime(r.t0)), r.machine,
                     log_file(r, sources),
                     '%.1f' % (r.t1 - r.t0) if r.t1 else '-',
                     r.blocks[-1][1] if r.blocks else '-',
                     fmt_range(r.fo_range, '%'),
                     '-' if r.feed_ratio is None else '%.3f' % r.feed_ratio,
                     fmt_range(r.ro_range, '%'),
                     '-' if r.rapid_peak is None else '%.0f' % r.rapid_peak,
                     'kept' if r.kept else '; '.join(r.why) + other_version(r, label, progs)])
    # (a '?' label: the name comes from the log or NIST's Split file name, no file fits)
    out.table(['program', 'start (UTC)', 'machine', 'log file', 'time s', 'last line', 'feed ovr (log)',
               'speed/F', 'rapid ovr (log)', 'peak mm/s', 'kept / why not'], rows)
    out.para('"feed ovr (log)"/"rapid ovr (log)": the values logged during the run, starting '
             'with the last one logged before it (which, across the gaps between Split files, may '
             'be stale); "speed/F": measured path speed over programmed F on steady feed lines '
             '(the feed override the run really had); "peak mm/s": the highest path speed '
             'logged. "?": no program file fits the run; its name comes from the log or from '
             'NIST\'s Split file name.')


def report_spread(out, kept_by, all_by, names):
    out.title('Runs per program and their run-to-run spread')
    rows = []
    for name in names:
        ks = kept_by.get(name, [])
        al = all_by.get(name, [])
        comp = [r for r in al if r.complete]
        times = [r.t1 - r.t0 for r in ks]
        ro = sorted({fmt_range(r.ro_range, '%') for r in ks})
        rows.append([name, len(al), len(comp), len(ks), ', '.join(ro) or '-', spread(times),
                     '-' if len(times) < 2 else '%.1f%%' % (100 * (max(times) - min(times)) / statistics.median(times))])
    out.table(['program', 'runs', 'complete', 'kept', 'rapid ovr', 'total s min / median / max', 'max-min'], rows)


def report_totals(out, kept_by, preds, names):
    out.title('Totals: measured (median of the kept runs) vs predicted')
    rows = []
    for name in names:
        ks = kept_by.get(name, [])
        if not ks:
            rows.append([name, 0, '-', '%.1f' % preds[name].total, '-'])
            continue
        m = statistics.median(r.t1 - r.t0 for r in ks)
        rows.append([name, len(ks), '%.1f' % m, '%.1f' % preds[name].total,
                     pct((preds[name].total - m) / m)])
    out.table(['program', 'runs', 'measured s', 'predicted s', 'error'], rows)


def report_ops(out, kept_by, preds, names):
    out.title('Operations (a tool change starts one)')
    rows = []
    for name in names:
        ks = kept_by.get(name, [])
        pred = preds[name]
        per_op = [op_bounds(r, pred) for r in ks]
        for i, (opname, tool, line, pt) in enumerate(pred.ops):
            got = [p[i] for p in per_op if p[i] is not None]
            # the tool the log shows after this operation's M6 (should be the same number)
            logged = sorted({tl for r in ks for _, tl, ln in r.tools if ln == line and tl > 0})
            m = med(got)
            rows.append([name, i + 1, 'T%s' % tool, line,
                         'T' + '/'.join(str(t) for t in logged) if logged else '-',
                         spread(got), '%.1f' % pt, pct((pt - m) / m) if m else '-'])
    out.table(['program', 'op', 'tool', 'M6 line', 'log tool', 'measured s min / median / max',
               'predicted s', 'error'], rows)


def block_table(kept, pred):
    """Per group of lines (first, next): durations across the kept runs."""
    table = {}
    for r in kept:
        for a, b, _, d in groups(r):
            if a == 0:
                continue                       # cycle start to the first line shown
            table.setdefault((a, b), []).append(d)
    return table


def report_blocks(out, kept_by, preds, names, progs):
    out.title('Blocks measured at %.1f s or more' % MIN_BLOCK_S)
    out.para('Each line (or run of lines, when the lines after it were too short to show in the '
             'log) is compared with the prediction for the same lines, in every kept run where it '
             'showed the same way. Relative error = (predicted - measured) / measured, measured = '
             'median over the runs. The run-to-run spread is the median absolute deviation of the '
             'line\'s time across runs over its median: the log\'s own noise (one sample is '
             '0.12-0.19 s).')
    rows, by_kind = [], {}
    for name in names:
        ks = kept_by.get(name, [])
        if not ks:
            continue
        pred = preds[name]
        errs, spreads, n = [], [], 0
        for (a, b), ds in sorted(block_table(ks, pred).items()):
            if len(ds) < max(2, len(ks) // 2):
                continue
            m = statistics.median(ds)
            if m < MIN_BLOCK_S:
                continue
            p = pred.between(a, b)
            e = (p - m) / m
            s = mad_rel(ds)
            errs.append(e)
            spreads.append(s)
            n += 1
            ln = progs[name].line(a)
            kind = pred.kind.get(a, '?')
            if ln is not None and ln.mcodes:
                kind += ' with ' + '/'.join('M%d' % x for x in ln.mcodes)
            if any(pred.per_line.get(x) for x in range(a + 1, b)):
                kind += ' +'                 # the group holds later lines with time too
            by_kind.setdefault(kind, []).append((e, s, m, p))
        rows.append([name, n, upct(med([abs(e) for e in errs])), pct(med(errs)),
                     upct(med(spreads))])
    out.table(['program', 'blocks', 'median abs error', 'median error', 'run-to-run spread'], rows)
    krows = []
    for kind, vals in sorted(by_kind.items(), key=lambda kv: -len(kv[1])):
        krows.append([kind, len(vals), upct(med([abs(v[0]) for v in vals])), pct(med([v[0] for v in vals])),
                      upct(med([v[1] for v in vals])), '%.2f' % sum(v[2] for v in vals),
                      '%.2f' % sum(v[3] for v in vals)])
    out.para('By the kind ncjoule gives the first line, with its M-codes (+: the group also '
             'holds later lines that have time):')
    out.table(['kind', 'blocks', 'median abs error', 'median error', 'run-to-run spread',
               'measured s (sum)', 'predicted s (sum)'], krows)


def line_category(ln):
    """Which part of a program's time a line belongs to, for the time budget."""
    if ln is None:
        return 'cycle start, before the first line shows'
    m = set(ln.mcodes)
    if ln.tool_change:
        return 'tool change (M6 line)'
    if m & {0, 1}:
        return 'M0/M01 stop line'
    if m & {2, 30}:
        return 'M30 line to PROGRAM_COMPLETED'
    if m & {3, 4, 8}:
        return 'spindle/coolant start lines (M3, M8)'
    if ln.motion == 'home' or m & {5, 9} or re.search(r'G5[4-9]', ln.text.upper()) and ln.motion == 'rapid' and not ln.known:
        return 'M5, Z home (G28) and unload (G58) lines'
    if ln.motion == 'rapid':
        return 'other rapid lines'
    if ln.motion in ('feed', 'arc'):
        return 'feed lines (G1/G2/G3)'
    return 'other lines'


def report_budget(out, kept_by, progs, names, preds):
    """Where the measured time goes, by kind of line, against the prediction for the same lines."""
    out.title('Where the time goes')
    out.para('Each run cut into its groups of lines (a group starts when Block_Number changes), '
             'each group filed under its first line\'s kind; measured: median over the kept runs '
             'of each run\'s sum; predicted: ncjoule\'s time for the same lines. Seconds.')
    rows = []
    for name in names:
        ks = kept_by.get(name, [])
        if not ks:
            continue
        prog, pred = progs[name], preds[name]
        sums, psums = {}, {}
        for r in ks:
            per = {}
            for a, b, _, d in groups(r):
                cat = line_category(prog.line(a) if a > 0 else None)
                per[cat] = per.get(cat, 0.0) + d
                if r is ks[0]:
                    psums[cat] = psums.get(cat, 0.0) + pred.between(a, b)
            for cat, v in per.items():
                sums.setdefault(cat, []).append(v)
        order = sorted(sums, key=lambda c: -statistics.median(sums[c]))
        for cat in order:
            m = statistics.median(sums[cat])
            p = psums.get(cat, 0.0)
            rows.append([name, cat, '%.1f' % m, '%.1f' % p, '%+.1f' % (p - m)])
    out.table(['program', 'lines', 'measured s', 'predicted s', 'predicted - measured'], rows)


def feed_chains(prog):
    """Runs of 10 or more feed lines (G1/G2/G3, no M-codes) between two other lines."""
    chains, cur = [], []
    for ln in prog.lines:
        if not ln.code:
            continue
        if ln.motion in ('feed', 'arc') and not ln.mcodes and ln.feed_mm_s:
            cur.append(ln)
            continue
        if len(cur) >= 10:
            chains.append((cur, ln.no))
        cur = []
    return chains


def report_chains(out, kept_by, progs, names, preds):
    """Chains of feed lines: does the control hold the programmed feed through short lines?"""
    bins = {}
    edges = (0.1, 0.3, 0.6, 1.0, 3.0, 10.0, float('inf'))
    for name in names:
        prog, pred = progs[name], preds[name]
        for chain, after in feed_chains(prog):
            nos = [ln.no for ln in chain]
            med_len = statistics.median(ln.length_mm for ln in chain)
            feed = round(statistics.median(ln.feed_mm_s for ln in chain) * 60 / IN_MM)
            b = (next(e for e in edges if med_len < e), feed)
            for r in kept_by.get(name, []):
                f = first_seen(r)
                # from the first line that showed after the chain's first (which starts from
                # rest) to the line after the chain showing
                start = next((n for n in nos[1:] if n in f), None)
                if start is None or after not in f:
                    continue
                lines = [ln for ln in chain if ln.no >= start]
                acc = bins.setdefault(b, [0, 0, 0.0, 0.0, 0.0, set()])
                acc[0] += 1
                acc[1] += len(lines)
                acc[2] += f[after] - f[start]
                acc[3] += sum(ln.length_mm / ln.feed_mm_s for ln in lines)
                acc[4] += pred.between(start, after)
                acc[5].add(name)
    rows = []
    lows = dict(zip(edges, (0.0,) + edges[:-1]))
    for (e, feed) in sorted(bins):
        n, lines, m, ideal, p, where = bins[(e, feed)]
        rows.append(['%g-%s' % (lows[e], '' if e == float('inf') else '%g' % e), feed,
                     ' '.join(sorted(where)), n, lines, '%.3f' % (m / ideal), '%.3f' % (m / p),
                     '%+.1f' % (1000 * (m - p) / lines)])
    out.para('Chains of 10 or more feed lines between two other lines, timed in each kept run '
             'from their second line showing to the line after them showing, by the median length '
             'of their lines (mm) and their median F. "measured / (L/F)": the time over what the programmed feed '
             'gives; "measured / ncjoule": over the prediction; "ms per line": the difference to '
             'ncjoule per line. A ratio above 1 with lines of under a millimetre means the control '
             'does not hold F through them (the logged speed dips at the corners).')
    out.table(['line length mm', 'F in/min', 'programs', 'chain runs', 'lines', 'measured / (L/F)',
               'measured / ncjoule', 'ms per line over ncjoule'], rows)
    return rows


def report_findings(out, kept_by, progs, names, preds):
    """What the logs show about the control's timing, from the kept OP1-OP3 runs only."""
    out.title('What the logs show (kept OP1-OP3 runs only)')
    out.para(block_meaning(kept_by, progs, names))

    # 1. Cycle start and the first tool change; later tool changes.
    rows = []
    same_tool = []
    for name in names:
        ks = kept_by.get(name, [])
        prog = progs[name]
        if not ks or not prog.m6:
            continue
        first_line = prog.m6[0][0]
        to_first, first_m6, start_to_after = [], [], []
        later = {}
        for r in ks:
            t_m6 = next((t for t, n in r.blocks if n >= first_line), None)
            t_after = next((t for t, n in r.blocks if n > first_line), None)
            if t_m6 is not None:
                to_first.append(t_m6 - r.t0)
            if t_m6 is not None and t_after is not None:
                first_m6.append(t_after - t_m6)
                start_to_after.append(t_after - r.t0)
            for line, tool in prog.m6[1:]:
                t_a = next((t for t, n in r.blocks if n == line), None)
                t_b = next((t for t, n in r.blocks if n > line), None)
                if t_a is not None and t_b is not None:
                    later.setdefault((line, tool), []).append(t_b - t_a)
            # a change to the tool already in the spindle: M6 with no Current_Tool event
            for line, tool in prog.m6:
                if not any(ln == line for _, _, ln in r.tools):
                    same_tool.append((name, line, tool))
        rows.append([name, 'first (T%s, line %d)' % (prog.m6[0][1], first_line), len(first_m6),
                     spread(to_first), spread(first_m6), spread(start_to_after)])
        for (line, tool), ds in later.items():
            rows.append([name, 'later (T%s, line %d)' % (tool, line), len(ds), '-', spread(ds), '-'])
    out.para('Tool changes. "cycle start to M6 line": Program_Status ACTIVE to the first sample '
             'showing the M6 line; "M6 line": from it showing to the next line showing; "cycle '
             'start to next line": the whole first change as a program sees it (the header lines '
             'before M6 are settings). Seconds, min / median / max over the kept runs.')
    out.table(['program', 'tool change', 'runs', 'cycle start to M6 line', 'M6 line',
               'cycle start to next line'], rows)
    all_later = [d for name in names for r in kept_by.get(name, [])
                 for (line, tool) in progs[name].m6[1:]
                 for d in [line_time(r, line)] if d is not None]
    firsts = [d for name in names for r in kept_by.get(name, []) if progs[name].m6
              for d in [line_time_from_start(r, progs[name].m6[0][0])] if d is not None]
    summary = ['first tool change of a program (cycle start to the line after M6): median %.2f s '
               '(n=%d, %s)' % (med(firsts), len(firsts), spread(firsts)) if firsts else 'first tool change: -',
               'later tool changes (M6 line alone): median %.2f s (n=%d, %s)' % (
                   med(all_later), len(all_later), spread(all_later)) if all_later else 'later: -']
    if same_tool:
        summary.append('M6 lines with no tool change in the log (tool already in the spindle): %d' % len(same_tool))
    else:
        summary.append('no change to the tool already in the spindle: every M6 of the kept runs '
                       'changed the tool (each program starts with a tool other than the one '
                       'the previous program ended with), so the logs cannot time it.')
    out.bullets(summary)

    # 2. The lines around each tool change: M5, G28/M9, M01, M3, M8.
    mlines = report_mcode_lines(out, kept_by, progs, names, preds)

    # 3. Spindle run-up and run-down from the Spindle_Speed samples.
    spindle = report_spindle(out, kept_by, progs, names)

    # 4. Rapids: time against length; settling.
    rapids = report_rapids(out, kept_by, progs, names, preds)

    # 5. Feed lines that end at rest, and chains of short feed lines.
    feeds = report_feed_stops(out, kept_by, progs, names, preds)
    chains = report_chains(out, kept_by, progs, names, preds)

    # 6. Canned cycles.
    cyc = [(name, ln.no, ln.cycle) for name in names for ln in progs[name].lines if ln.cycle]
    out.para('Canned cycles (G81/G83/G84, peck tapping with Q): %s' % (
        'OP1-OP3 hold none: no G73/G8x line in any of them (checked line by line), so the logs '
        'of OP1-OP3 cannot time a drilling or tapping cycle. Only OP5 (G81, G83, G84) and the '
        'plates (G81) have cycles, and those are the independent check: they are not used '
        'here.' if not cyc else '%d cycle lines' % len(cyc)))

    # 7. The numbers a timing model needs, in one place.
    out.para('In short (medians over the kept runs of OP1-OP3; seconds unless said):')
    items = []
    starts = {}
    for n in names:
        firsts_shown = [(r, next((t for t, b in r.blocks if b > 0), r.t0)) for r in kept_by.get(n, [])]
        if firsts_shown:
            starts[n] = (med([t - r.t0 for r, t in firsts_shown]),
                         med([stationary_time(r, r.t0, t) for r, t in firsts_shown]))
    items.append('cycle start to the first line showing: ' + ', '.join(
        '%s %.2f (%.2f standing)' % (n, a, b) for n, (a, b) in starts.items()))
    if firsts:
        items.append('first tool change of a program, cycle start to the line after M6: %.2f '
                     '(%s; per program: %s)' % (med(firsts), spread(firsts), ', '.join(
                         '%s %.2f' % (n, med([line_time_from_start(r, progs[n].m6[0][0])
                                              for r in kept_by.get(n, [])]))
                         for n in names if kept_by.get(n) and progs[n].m6)))
    if all_later:
        items.append('later tool change, the M6 line alone: %.2f (%s, n=%d); a change to the '
                     'tool already in the spindle: not in the logs' % (
                         med(all_later), spread(all_later), len(all_later)))
    for cat, label in (('M01 (optional stop, after G28 Z0 M9)', 'M01 line (optional stop off: status stays ACTIVE)'),
                       ('M30 (to PROGRAM_COMPLETED)', 'M30 line to PROGRAM_COMPLETED'),
                       ('Z rapid + M8 (the line after the M3 line)', 'Z rapid + M8 line after the M3 line'),
                       ('M3 line to the first feed line (whole)', 'M3 line showing to the first feed line showing'),
                       ('G0 X Y S12000 M3 (after M6)', 'G0 X Y S12000 M3 line'),
                       ('M5', 'M5 line')):
        if cat in mlines:
            m, st, n = mlines[cat]
            items.append('%s: %.2f, of which %.2f standing (n=%d)' % (label, m, st, n))
    if spindle:
        items.append('spindle run-up: linear, %.0f rpm/s (%.3f s per 1000 rpm), starting %.2f after '
                     'the M3 line shows: 0 to 12000 rpm in %.2f; run-down %.0f rpm/s; the control '
                     'waits for neither (only S12000 is in OP1-OP3)' % (
                         spindle['slope'], 1000 / spindle['slope'], spindle['delay'],
                         12000 / spindle['slope'], spindle.get('down', float('nan'))))
    if rapids:
        items.append('rapids: Z %.0f mm/s; best fit acceleration %.1f m/s2 with %.3f s fixed per '
                     'rapid line (dog-leg, rest to rest); measured minus ncjoule: %+.3f per rapid line'
                     % (rapids['v'], rapids['a'], rapids['fixed'], rapids['vs_ncjoule']))
    for cls, (n, over_lf, over_nc) in sorted(feeds.items()):
        items.append('feed line %s: %+.3f over L/F, %+.3f over ncjoule (n=%d lines)' % (
            cls, over_lf, over_nc, n))
    if chains:
        items.append('chains of feed lines, measured / (L/F) by line length and feed: ' + ', '.join(
            '%s mm at F%s: %s' % (row[0], row[1], row[5]) for row in chains))
    out.bullets(items)


def block_meaning(kept_by, progs, names):
    """What Block_Number is, shown on the data: the values at the tool changes and at the end
    against the M6 and M30 lines' numbers in the file and their N words."""
    examples = []
    for name in names:
        ks = kept_by.get(name, [])
        if not ks:
            continue
        prog = progs[name]
        at_change = [ln for _, tool, ln in ks[0].tools if tool > 0]
        n_words = [re.match(r'N(\d+)', prog.line(no).text.upper()) for no, _ in prog.m6]
        examples.append('%s: Block_Number at its tool changes %s and at the end %d; the M6 lines '
                        'are lines %s (N%s) and M30 is line %d' % (
                            name, '/'.join(map(str, at_change)), ks[0].blocks[-1][1],
                            '/'.join(str(no) for no, _ in prog.m6),
                            '/N'.join(m.group(1) if m else '?' for m in n_words), prog.end_line))
    return ('Block_Number is the 1-based line number in the file (the % line is line 1, comment '
            'lines count), not the N number (the posts number in tens and wrap: N9990 is '
            'followed by N100): ' + '; '.join(examples) + '. It changes when the line '
            'starts executing (after a rapid the logged path speed is 0 at the change), so a '
            'line\'s time is the time between two changes. A line shorter than a sample period '
            '(0.12-0.19 s) may not show at all; its time then goes to the line before it.')


def line_time(run, line):
    t_a = next((t for t, n in run.blocks if n == line), None)
    t_b = next((t for t, n in run.blocks if n > line), None)
    return None if t_a is None or t_b is None else t_b - t_a


def line_time_from_start(run, line):
    t_b = next((t for t, n in run.blocks if n > line), None)
    return None if t_b is None else t_b - run.t0


def report_mcode_lines(out, kept_by, progs, names, preds):
    """Stand-stills: lines that take seconds with the axes at rest (M01, M8 after M3, M30)."""
    cats = {}
    for name in names:
        prog = progs[name]
        pred = preds[name]
        for r in kept_by.get(name, []):
            gs = {a: (b, t, d) for a, b, t, d in groups(r)}
            for ln in prog.lines:
                if not ln.code or ln.no not in gs:
                    continue
                b, t, d = gs[ln.no]
                if b != ln.no + 1 and not all(not prog.line(x).code for x in range(ln.no + 1, b)):
                    continue                     # time shared with lines not seen
                cat = None
                m = set(ln.mcodes)
                if 1 in m:
                    cat = 'M01 (optional stop, after G28 Z0 M9)'
                elif 30 in m:
                    cat = 'M30 (to PROGRAM_COMPLETED)'
                elif 8 in m:
                    cat = 'Z rapid + M8 (the line after the M3 line)'
                elif 3 in m:
                    cat = 'G0 X Y S12000 M3 (after M6)'
                elif 5 in m:
                    cat = 'M5'
                elif ln.motion == 'home':
                    cat = 'G91 G28 Z0 M9 (Z home)' if 9 in m else 'G28/G53 home'
                elif re.search(r'G58', ln.text.upper()):
                    cat = 'G90 G58 X12. Y20. (to the unload position)'
                if cat:
                    still = stationary_time(r, t, t + d)
                    cats.setdefault(cat, []).append((d, still, pred.between(ln.no, b)))
            # from the spindle start to the first cut: what a program waits for its spindle
            first = first_seen(r)
            for ln in prog.lines:
                if 3 not in ln.mcodes or ln.no not in first:
                    continue
                feed = next((x for x in prog.lines[ln.no:] if x.motion in ('feed', 'arc')), None)
                if feed is not None and feed.no in first:
                    t0, t1 = first[ln.no], first[feed.no]
                    cats.setdefault('M3 line to the first feed line (whole)', []).append(
                        (t1 - t0, stationary_time(r, t0, t1), pred.between(ln.no, feed.no)))
    rows = []
    for cat, vals in sorted(cats.items()):
        rows.append([cat, len(vals), spread([v[0] for v in vals]), spread([v[1] for v in vals]),
                     '%.2f' % med([v[2] for v in vals])])
    out.para('Lines around the tool changes and the program end. "standing": the part of the '
             'line with the path speed logged as 0. Seconds, min / median / max over all such '
             'lines of the kept runs; "predicted" is ncjoule\'s (median) for the same line.')
    out.table(['line', 'n', 'measured s', 'standing s', 'predicted s'], rows)
    return {cat: (med([v[0] for v in vals]), med([v[1] for v in vals]), len(vals))
            for cat, vals in cats.items()}


def report_spindle(out, kept_by, progs, names):
    """Run-up and run-down of the spindle, from straight-line fits to the Spindle_Speed samples."""
    ups, downs = [], []
    for name in names:
        prog = progs[name]
        m3 = [ln.no for ln in prog.lines if 3 in ln.mcodes]
        m5 = [ln.no for ln in prog.lines if 5 in ln.mcodes]
        for r in kept_by.get(name, []):
            first = first_seen(r)
            # when the M3/M5 line showed; an M5 line is often too short to show: then the
            # line after it, which starts at most one sample later
            shown_m3 = [first[n] for n in m3 if n in first]
            shown_m5 = [first.get(n, first.get(n + 1)) for n in m5]
            for t0, slope, top in spindle_ramps(r, up=True):
                near = [t for t in shown_m3 if t0 - 3 <= t <= t0 + 0.2]
                ups.append((t0 - max(near) if near else None, slope, top))
            for t0, slope, top in spindle_ramps(r, up=False):
                t_start = t0 - top / slope
                near = [t for t in shown_m5 if t is not None and t_start - 3 <= t <= t_start + 0.5]
                downs.append((t_start - max(near) if near else None, slope, top))
    if not ups:
        out.para('Spindle: no run-up seen.')
        return {}
    slope = med([u[1] for u in ups])
    delays = [u[0] for u in ups if u[0] is not None]
    delay = med(delays)
    tops = sorted({round(u[2], -2) for u in ups})
    rows = [['%d' % rpm, '%.2f' % (rpm / slope), '%.2f' % (delay + rpm / slope)]
            for rpm in (1000, 2000, 4000, 6000, 8000, 10000, 12000)]
    out.para('Spindle run-up, from straight lines fitted to the Spindle_Speed samples of %d '
             'run-ups from standstill in the kept runs (top speeds seen: %s rpm; every M3 of '
             'OP1-OP3 is S12000, so speeds above 12000 and run-ups to a lower target are not '
             'observed). The speed rises linearly at a median %.0f rpm/s (min %.0f, max %.0f): '
             '%.3f s per 1000 rpm. The ramp starts %.2f s (median) after the M3 line shows '
             '(min %.2f, max %.2f; the line shows up to one sample after it starts). Seconds to '
             'reach each speed:' % (
                 len(ups), ', '.join('%d' % t for t in tops), slope, min(u[1] for u in ups),
                 max(u[1] for u in ups), 1000 / slope, delay, min(delays), max(delays)))
    out.table(['rpm', 'from the ramp start', 'from the M3 line'], rows)
    items = []
    if downs:
        ds = med([d[1] for d in downs])
        dl = [d[0] for d in downs if d[0] is not None]
        items.append('run-down from 12000 rpm (after each M5): linear at a median %.0f '
                     'rpm/s (%d stops), %.2f s from 12000 to 0; it starts %+.2f s (median, %d '
                     'stops after an M5) from the M5 line showing (or, when that line was too '
                     'short to show, the line after it). The control does not wait for it: the '
                     'M5 line itself lasts ~0.2 s and the next line (G91 G28 Z0) moves Z home '
                     'meanwhile.' % (ds, len(downs), 12000 / ds,
                                     med(dl) if dl else float('nan'), len(dl)))
    items.append('The control does not wait for the spindle at the M3 line either: the M3 line '
                 '(G0 X Y S12000 M3) ends with its XY rapid, ~1 s, while the spindle needs ~%.1f s; '
                 'but the next line (Z rapid with M8) then stands ~6 s (table above), so the first '
                 'feed line comes long after the spindle is at speed.' % (12000 / slope))
    out.bullets(items)
    return {'slope': slope, 'delay': delay, 'down': med([d[1] for d in downs]) if downs else None}


def first_seen(run):
    """{line: time it first showed} for a run."""
    d = {}
    for t, n in run.blocks:
        d.setdefault(n, t)
    return d


def trapezoid_s(length, v, a):
    """Time of a move of this length from rest to rest at top speed v and acceleration a."""
    length = abs(length)
    if length <= 0:
        return 0.0
    if length >= v * v / a:
        return length / v + v / a
    return 2 * math.sqrt(length / a)


def rapid_sequences(kept_by, progs, names):
    """Runs of rapid lines between two feed lines, timed in each kept run.

    A single short rapid often falls between two samples, but the run of rapids between two
    cuts (retract, move over, approach) starts when its first line shows and ends when the next
    feed line shows: both are changes the log catches. Returns [(lines, median s, runs)] for
    sequences whose lines all have known start and end points and no M/S/T words."""
    data = []
    for name in names:
        prog = progs[name]
        code = [ln for ln in prog.lines if ln.code]
        plain = [ln.motion == 'rapid' and ln.known and not ln.mcodes and ln.spindle is None
                 and ln.tool is None for ln in code]
        i = 1
        while i < len(code):
            if plain[i] and code[i - 1].motion in ('feed', 'arc'):
                j = i
                while j < len(code) and plain[j]:
                    j += 1
                if j < len(code) and code[j].motion in ('feed', 'arc'):
                    ms = []
                    for r in kept_by.get(name, []):
                        f = first_seen(r)
                        if code[i].no in f and code[j].no in f:
                            ms.append(f[code[j].no] - f[code[i].no])
                    if len(ms) >= 3:
                        data.append((code[i:j], statistics.median(ms), len(ms)))
                i = j
            else:
                i += 1
    return data


def fit_rapids(data, v_axis):
    """Least-squares acceleration and fixed time per rapid line: each line modelled as every
    axis moving on its own (dog-leg) from rest to rest with a trapezoid at v_axis and a, plus
    the fixed time. Returns (a m/s2, fixed s, rms s) and the profile of rms over a."""
    def model(lines, a):
        return sum(max(trapezoid_s(d, v_axis, a) for d in ln.delta) for ln in lines)
    profile = []
    for a10 in range(5, 81):
        a = a10 / 10.0
        motion = [model(lines, a * 1000) for lines, _, _ in data]
        n = [len(lines) for lines, _, _ in data]
        meas = [m for _, m, _ in data]
        # the best fixed time per line for this a: least squares of meas - motion = s * n
        s = sum((m - mo) * k for m, mo, k in zip(meas, motion, n)) / sum(k * k for k in n)
        rms = math.sqrt(sum((m - mo - s * k) ** 2 for m, mo, k in zip(meas, motion, n)) / len(n))
        profile.append((a, s, rms))
    best = min(profile, key=lambda p: p[2])
    return best, profile


def report_rapids(out, kept_by, progs, names, preds):
    """G0 lines: how long they take beyond their motion."""
    data = rapid_sequences(kept_by, progs, names)
    z_top = []
    for name in names:
        for r in kept_by.get(name, []):
            for a, b, t, d in groups(r):
                ln = progs[name].line(a)
                if ln and ln.motion == 'home' and ln.axes == 'Z':
                    z_top.extend(f for tt, f in r.feed if t <= tt < t + d)
    v = max(z_top) if z_top else 500.0
    peaks = [r.rapid_peak for name in names for r in kept_by.get(name, []) if r.rapid_peak]
    items = ['rapid rate: the Z axis alone (G91 G28 Z0 lines) tops at %.0f mm/s = %.0f in/min '
             'in every kept run; XY rapids reach %.0f mm/s (median of the runs\' peaks) along '
             'diagonals, so X and Y move at their own rates (at least %.0f mm/s each: a '
             'dog-leg, not one straight line at one speed).' % (
                 v, v * 60 / IN_MM, med(peaks) or 0, (med(peaks) or 0) / math.sqrt(2))]
    if not data:
        out.bullets(items)
        return {}
    (a, s, rms), profile = fit_rapids(data, v)
    nlines = sum(len(lines) for lines, _, _ in data)
    lens = [max(abs(d) for d in ln.delta) for lines, _, _ in data for ln in lines]
    pred_excess = []
    for lines, m, _ in data:
        # measured minus ncjoule's prediction for the same lines, per line
        name = next(n for n in names if any(l is lines[0] for l in progs[n].lines))
        p = sum(preds[name].per_line.get(ln.no, 0.0) for ln in lines)
        pred_excess.append((m - p) / len(lines))
    out.para('Rapid (G0) lines. A short rapid often falls between two samples, so the rapids '
             'between two cuts are timed together: from the first rapid line showing to the next '
             'feed line showing (both caught by the log), median over the kept runs. %d such '
             'sequences (%d lines, the longest axis move %.1f-%.1f mm, median %.1f mm) are fitted '
             'with every line a dog-leg move from rest to rest (each axis a trapezoid at %.0f '
             'mm/s and acceleration a) plus a fixed time per line. Least squares:' % (
                 len(data), nlines, min(lens), max(lens), statistics.median(lens), v))
    rows = [['%.1f' % p[0], '%+.3f' % p[1], '%.3f' % p[2]] for p in profile
            if abs(p[0] - a) < 1e-9 or p[0] in (1.0, 1.5, 2.0, 3.0, 4.0, 6.0)]
    out.table(['a m/s2', 'fixed s per line', 'rms s'], rows)
    items.append('best fit: acceleration %.1f m/s2 with %.3f s per rapid line on top of the '
                 'motion (rms %.3f s per sequence); the two trade off (see the table: a lower '
                 'acceleration needs less fixed time), the minimum is clear but shallow.' % (a, s, rms))
    items.append('measured minus ncjoule\'s prediction on the same sequences: median %+.3f s per '
                 'rapid line with this profile.' % med(pred_excess))
    out.bullets(items)
    return {'v': v, 'a': a, 'fixed': s, 'vs_ncjoule': med(pred_excess)}


def report_feed_stops(out, kept_by, progs, names, preds):
    """Feed lines followed by a rapid or an M-code end at rest: how much longer than L/F?"""
    rows = {}
    for name in names:
        prog, pred = progs[name], preds[name]
        code = [ln for ln in prog.lines if ln.code]
        nxt_code = {code[k].no: code[k + 1] for k in range(len(code) - 1)}
        prv_code = {code[k + 1].no: code[k] for k in range(len(code) - 1)}
        per_line = {}
        for r in kept_by.get(name, []):
            f = first_seen(r)
            for ln in code:
                nx = nxt_code.get(ln.no)
                if nx is not None and ln.no in f and nx.no in f:
                    per_line.setdefault(ln.no, []).append(f[nx.no] - f[ln.no])
        for no, ds in per_line.items():
            ln = prog.line(no)
            if ln.motion not in ('feed', 'arc') or not ln.feed_mm_s or len(ds) < 3:
                continue
            m = statistics.median(ds)
            if m < MIN_BLOCK_S:
                continue
            prev, nxt = prv_code.get(no), nxt_code.get(no)
            starts_rest = prev is None or prev.motion not in ('feed', 'arc')
            ends_rest = nxt is None or nxt.motion not in ('feed', 'arc')
            cls = '%s, %s' % ('from rest' if starts_rest else 'from a feed line',
                              'to rest' if ends_rest else 'into a feed line')
            ideal = ln.length_mm / ln.feed_mm_s
            rows.setdefault(cls, []).append((m - ideal, m - pred.per_line.get(no, 0.0), m, ideal))
    out.para('Feed lines (G1/G2/G3) of %.1f s or more, timed from showing to the next line '
             'showing (median over the kept runs), by what comes before and after them (a rapid '
             'or an M-code means the path is at rest there). "over L/F": measured minus length '
             '/ programmed feed (at these feeds, 12.7-63.5 mm/s, acceleration costs only '
             'milliseconds); "over ncjoule": measured minus predicted. Seconds, median per line.'
             % MIN_BLOCK_S)
    out.table(['feed lines', 'n', 'median measured s', 'over L/F s', 'over ncjoule s'],
              [[cls, len(v), '%.2f' % med([x[2] for x in v]), '%+.3f' % med([x[0] for x in v]),
                '%+.3f' % med([x[1] for x in v])] for cls, v in sorted(rows.items())])
    return {cls: (len(v), med([x[0] for x in v]), med([x[1] for x in v])) for cls, v in rows.items()}


def report_check(out, runs, check_progs, preds_check):
    """The independent check: only totals and operations, nothing fitted on them."""
    out.title('Independent check (OP4, OP5, cover, plates: not used for anything above)')
    rows = []
    by = {}
    for r in runs:
        if r.program and r.program.name in check_progs and r.complete:
            by.setdefault(r.program.name, []).append(r)
    for name in sorted(by, key=natural):
        rs = by[name]
        pred = preds_check.get(name)
        fo = [r for r in rs if r.fo_range and 99 <= r.fo_range[0] and r.fo_range[1] <= 101
              and (r.feed_ratio is None or abs(r.feed_ratio - 1) <= CHECK_RATIO_TOL)]
        use = fo or rs
        times = [r.t1 - r.t0 for r in use]
        m = statistics.median(times)
        amb = any(getattr(r, 'ambiguous', False) for r in use)
        rows.append([name + (' (?)' if amb else ''), len(rs), len(fo),
                     ', '.join(sorted({fmt_range(r.ro_range, '%') for r in use})),
                     spread(times), '%.1f' % pred.total if pred else '-',
                     pct((pred.total - m) / m) if pred else '-'])
    if not rows:
        out.para('No complete run of these programs in the logs read.')
        return
    out.para('Complete runs of the programs kept out. "at 100%%": runs whose feed override was '
             'within 99-101%% (logged) and whose feeds ran within %.0f%% of F; the times are '
             'theirs when there are any, else all complete runs\'. ncjoule is run as for OP1-OP3 '
             '(no rapid override: runs logged below 100%% rapid take longer for that). (?): the '
             'program name was not logged and several programs have the same structure.'
             % (100 * CHECK_RATIO_TOL))
    out.table(['program', 'complete runs', 'at 100%', 'rapid ovr', 'measured s min / median / max',
               'predicted s', 'error'], rows)


def natural(s):
    return [int(x) if x.isdigit() else x for x in re.split(r'(\d+)', s)]


# ----------------------------------------------------------------------------------------

def default_ncjoule():
    here = os.path.dirname(os.path.abspath(__file__))
    return os.path.join(os.path.dirname(here), 'build', 'plugin', 'ncjoule')


def parse_args(argv):
    extra = []
    if '--' in argv:
        i = argv.index('--')
        argv, extra = argv[:i], argv[i + 1:]
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--repo',
                    help='the usnistgov/smstestbed repository: a bare git directory or a work tree')
    ap.add_argument('--ncjoule', default=default_ncjoule(),
                    help='the ncjoule binary (default: build/plugin/ncjoule of this project)')
    ap.add_argument('-m', '--machine', default='generic-3axis',
                    help='machine profile passed to ncjoule as -m (default generic-3axis)')
    ap.add_argument('--markdown', action='store_true', help='print markdown tables')
    args = ap.parse_args(argv)
    args.extra = extra
    return args


def main(argv):
    args = parse_args(argv)
    if not args.repo:
        print('error: give --repo: the usnistgov/smstestbed repository (a bare git directory '
              'or a work tree)', file=sys.stderr)
        return 1
    repo = Repo(args.repo)
    if not os.path.isdir(repo.path) or not repo.valid():
        print('error: %s is not the smstestbed repository (a bare git directory with HEAD, or a '
              'work tree with tdp/mtc)' % args.repo, file=sys.stderr)
        return 1
    ncjoule = os.path.abspath(args.ncjoule)
    for _ in range(10):                         # the binary may be rebuilt under us
        if os.path.isfile(ncjoule) or not os.path.isdir(os.path.dirname(ncjoule)):
            break
        time.sleep(3)
    if not (os.path.isfile(ncjoule) and os.access(ncjoule, os.X_OK)):
        print('error: ncjoule not found or not executable: %s (build it, or give --ncjoule)'
              % ncjoule, file=sys.stderr)
        return 1

    # Programs: the three that may be used, and the independent check.
    tree = repo.tree()
    nc_files = {n.split('/')[-1]: n for n in tree if n.startswith(NC_DIR + '/') and n.upper().endswith('.NC')}
    want = {name: NC_DIR + '/' + f for name, f in MAIN_PROGRAMS.items()}
    missing = [p for p in want.values() if p not in tree]
    if missing:
        print('error: the repository has no %s' % ', '.join(missing), file=sys.stderr)
        return 1
    check = {}
    for f, path in nc_files.items():
        mm = CHECK_PATTERN.search(f)
        if mm:
            label = mm.group(2) or mm.group(1).replace('_REV-A', '')
            check[label] = path
    texts = repo.read_many(list(want.values()) + list(check.values()))
    progs = {name: Program(name, p, texts[p]) for name, p in want.items() if p in texts}
    if len(progs) < len(want):
        print('error: could not read %s' % ', '.join(p for p in want.values() if p not in texts),
              file=sys.stderr)
        return 1
    check_progs = {name: Program(name, p, texts[p]) for name, p in check.items() if p in texts}

    timelines, sources, n_files = load_logs(repo)
    runs = find_runs(timelines)
    attach_names(runs, timelines, sources)
    select_runs(runs, list(progs.values()) + list(check_progs.values()), sources)

    names = list(MAIN_PROGRAMS)
    all_by, kept_by = {}, {}
    for r in runs:
        if r.program and r.program.name in progs:
            all_by.setdefault(r.program.name, []).append(r)
    for name in names:
        kept = [r for r in all_by.get(name, []) if r.kept]
        _, kept = choose_rapid_override(kept)
        kept_by[name] = kept

    workdir = tempfile.mkdtemp(prefix='controller_logs.')
    try:
        preds = {n: Prediction(run_ncjoule(ncjoule, p, args.machine, args.extra, workdir))
                 for n, p in progs.items()}
        used_check = {r.program.name for r in runs if r.program and r.program.name in check_progs and r.complete}
        preds_check = {n: Prediction(run_ncjoule(ncjoule, check_progs[n], args.machine, args.extra, workdir))
                       for n in sorted(used_check)}
    except RuntimeError as e:
        print('error: %s' % e, file=sys.stderr)
        return 1
    finally:
        shutil.rmtree(workdir, ignore_errors=True)

    out = Out(args.markdown)
    out.title('ncjoule vs the Hurco VMX24 logs of the NIST SMS Test Bed', 1)
    out.bullets(['ncjoule: %s estimate --json FILE -m %s --no-removal%s' % (
        ncjoule, args.machine, (' ' + ' '.join(args.extra)) if args.extra else ''),
        'programs: %s' % ', '.join('%s = %s' % (n, MAIN_PROGRAMS[n]) for n in names)])
    report_data(out, repo, n_files, sources, timelines)
    report_runs(out, runs, names, sources, progs)
    report_spread(out, kept_by, all_by, names)
    ros = sorted({fmt_range(r.ro_range, '%') for n in names for r in kept_by.get(n, [])})
    if ros == ['100%']:
        out.para('All kept runs ran at 100% rapid override, so ncjoule is compared as it is '
                 '(no rapid scaling needed).')
    else:
        out.para('WARNING: no kept run of some program ran at 100%% rapid override (%s): tell '
                 'ncjoule, e.g. with a profile whose rapid rates are scaled by the override, '
                 'passed after --.' % ', '.join(ros))
    report_totals(out, kept_by, preds, names)
    report_ops(out, kept_by, preds, names)
    report_budget(out, kept_by, progs, names, preds)
    report_blocks(out, kept_by, preds, names, progs)
    report_findings(out, kept_by, progs, names, preds)
    report_check(out, runs, check_progs, preds_check)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
