"""Measurements from a run's samples: the groups of lines as the log shows them, operation
times, time standing still, spindle ramps, when each line first showed."""

from .stats import fit_line


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


def first_seen(run):
    """{line: time it first showed} for a run."""
    d = {}
    for t, n in run.blocks:
        d.setdefault(n, t)
    return d
