"""Reads an NC program line by line: each line's motion, feed, length, M-codes and tool
changes, as the Hurco reads it."""

import math
import re

from .constants import IN_MM


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
