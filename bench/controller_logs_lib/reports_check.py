"""The report's independent check: the programs kept out (OP4, OP5, the cover, the plates),
totals only."""

import re
import statistics

from .constants import CHECK_RATIO_TOL
from .output import pct, spread
from .selection import fmt_range


# ----------------------------------------------------------------------------------------
# The report's sections.

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
