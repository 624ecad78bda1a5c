"""The report's sections on the data and the runs: files read, runs found and kept, their
spread, totals, operations, blocks and where the time goes."""

import re
import statistics
import time

from .analysis import groups, op_bounds
from .constants import FEED_RATIO_TOL, LONG_STALL_S, MIN_BLOCK_S
from .logs import REPAIRED
from .output import pct, spread, upct
from .selection import fmt_range
from .stats import mad_rel, med


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
