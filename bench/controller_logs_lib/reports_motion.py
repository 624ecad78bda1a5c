"""The report's findings on motion: chains of short feed lines, rapids (rate, acceleration,
fixed time per line) and feed lines that start or end at rest."""

import math
import statistics

from .analysis import first_seen, groups
from .constants import IN_MM, MIN_BLOCK_S
from .stats import med


# ----------------------------------------------------------------------------------------
# The report's sections.

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
