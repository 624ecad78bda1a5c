"""Cuts each machine's timeline into runs, cycle start to program end, with what the log
says happened during each."""


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
