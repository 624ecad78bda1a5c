"""Matches each run to the program it ran and decides whether it counts: complete, at 100%
feed override, at 100% rapid override when such runs exist."""

import re
import statistics

from .constants import FEED_RATIO_TOL, LONG_STALL_S
from .runs import safe_float


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
