"""Reads the MTConnect log files into one timeline of samples per machine, gluing back the
records NIST's cleaning script broke."""

import calendar
import re
import time

from .constants import LOG_FILE


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
