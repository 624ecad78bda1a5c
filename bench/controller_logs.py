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
import os
import shutil
import sys
import tempfile
import time

_HERE = os.path.dirname(os.path.abspath(__file__))
if _HERE not in sys.path:
    sys.path.insert(0, _HERE)

from controller_logs_lib.constants import CHECK_PATTERN, MAIN_PROGRAMS, NC_DIR
from controller_logs_lib.logs import load_logs
from controller_logs_lib.output import Out
from controller_logs_lib.predict import Prediction, run_ncjoule
from controller_logs_lib.programs import Program
from controller_logs_lib.repo import Repo
from controller_logs_lib.reports_check import report_check
from controller_logs_lib.reports_runs import (report_blocks, report_budget, report_data,
                                              report_ops, report_runs, report_spread,
                                              report_totals)
from controller_logs_lib.reports_timing import report_findings
from controller_logs_lib.runs import find_runs
from controller_logs_lib.selection import (attach_names, choose_rapid_override,
                                           fmt_range, select_runs)


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
