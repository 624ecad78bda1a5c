"""The report's findings on the control's timing: what Block_Number is, tool changes, the lines
around them, spindle run-up and run-down, and the summary of all timing findings."""

import re

from .analysis import first_seen, groups, spindle_ramps, stationary_time
from .output import spread
from .reports_motion import report_chains, report_feed_stops, report_rapids
from .stats import med


# ----------------------------------------------------------------------------------------
# The report's sections.

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
