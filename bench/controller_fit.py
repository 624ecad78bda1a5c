#!/usr/bin/env python3
"""Calibrate a machine from its own logs, and check the profile on programs kept out of the fit.

The data are NIST's Smart Manufacturing Systems Test Bed (github.com/usnistgov/smstestbed): the
MTConnect SHDR logs of two Hurco VMX24s (tdp/mtc/Split), the agent's device file and the programs
they ran (tdp/mtc/NC-Code). Two cases, each fitted with `ncjoule calibrate --timing` on one
machine's runs and checked with `ncjoule check-log` on a program the fit never saw:

  A. Hurco04: fitted on the twenty plate programs (run at a reduced, logged rapid override),
     checked on the cover (NIST_MTC_CRADA_COVER_REV-A.NC; its runs are the Cover-Op3 logs).
  B. Hurco02: fitted on the box's OP1-OP3, checked on the box's OP5.

    bench/controller_fit.py --repo PATH/TO/smstestbed [--ncjoule build/plugin/ncjoule]
                            [--base samples/machines/hurco-vmx24.toml] [--case A|B]
                            [--markdown] [--keep DIR]

It prints the targets' table (the checked program's total and each operation: measured, the base
profile's prediction, the calibrated profile's), the fitted keys beside the hand-chosen
hurco-vmx24 profile's, and what each fit left out. The fits plan every program at every solver
step: allow 10-30 minutes. Standard library only.
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
NC = 'tdp/mtc/NC-Code/'
SPLIT = 'tdp/mtc/Split/'
DEVICES = 'tdp/mtc/MTConnect/Devices.xml'
BOX = {'OP1': 'NIST_MTC_CRADA_BOX_REV-A OP1 (Bottom).NC',
       'OP2': 'NIST_MTC_CRADA_BOX_REV-A OP2 (Front).NC',
       'OP3': 'NIST_MTC_CRADA_BOX_REV-A OP3 (Back).NC',
       'OP5': 'NIST_MTC_CRADA_BOX_REV-A OP5 (Cavity Side).NC'}
COVER = 'NIST_MTC_CRADA_COVER_REV-A.NC'
TARGET_TOTAL, TARGET_OP = 0.03, 0.05


class Repo:
    """The smstestbed repository: a bare git directory (read with git) or a work tree."""

    def __init__(self, path):
        self.path = os.path.abspath(path)
        self.bare = os.path.isfile(os.path.join(self.path, 'HEAD')) and \
            os.path.isdir(os.path.join(self.path, 'objects'))

    def list(self, prefix):
        if self.bare:
            out = subprocess.run(['git', '--git-dir=' + self.path, 'ls-tree', '-r', '-z',
                                  '--name-only', 'HEAD', '--', prefix],
                                 capture_output=True, check=True).stdout
            return sorted(n.decode() for n in out.split(b'\0') if n)
        base = os.path.join(self.path, prefix)
        return sorted(prefix + f for f in os.listdir(base)) if os.path.isdir(base) else []

    def read(self, name):
        """The file's bytes, or None when this copy does not hold them (large files may be
        missing from a snapshot)."""
        if self.bare:
            r = subprocess.run(['git', '--git-dir=' + self.path, 'cat-file', 'blob',
                                'HEAD:' + name], capture_output=True)
            return r.stdout if r.returncode == 0 else None
        try:
            with open(os.path.join(self.path, name), 'rb') as f:
                return f.read()
        except OSError:
            return None

    def extract(self, names, into):
        """Writes the files under `into`; returns the paths of those that were there."""
        paths = []
        for n in names:
            data = self.read(n)
            if data is None or data.startswith(b'version https://git-lfs'):
                continue
            path = os.path.join(into, os.path.basename(n))
            with open(path, 'wb') as f:
                f.write(data)
            paths.append(path)
        return paths


def run(cmd):
    t0 = time.time()
    r = subprocess.run(cmd, capture_output=True, text=True)
    return r, time.time() - t0


def calibrate(ncjoule, base, devices, programs, logs, out):
    cmd = [ncjoule, 'calibrate', '--timing', '-m', base, '--devices', devices, '-o', out]
    for p in programs:
        cmd += ['--program', p]
    for log in logs:
        cmd += ['--log', log]
    r, seconds = run(cmd)
    if r.returncode != 0:
        raise RuntimeError('calibrate --timing failed (%d): %s' % (r.returncode, r.stderr[-600:]))
    return r.stdout, seconds


def check(ncjoule, profile, devices, program, logs):
    cmd = [ncjoule, 'check-log', program, '-m', profile, '--devices', devices, '--json']
    for log in logs:
        cmd += ['--log', log]
    r, _ = run(cmd)
    if r.returncode != 0:
        raise RuntimeError('check-log failed (%d): %s' % (r.returncode, r.stderr[-600:]))
    return json.loads(r.stdout)


KEY_LINE = re.compile(r'^  (kinematics\S+)\s+([-+0-9.e]+)(?:\s+\+-\s+([-+0-9.e]+)\s+\(base ([-+0-9.e]+)\))?'
                      r'(?:\s+left as in the base: (.*))?$')


def fitted_keys(stdout):
    """{key: (value, se or None, why or None)} from calibrate's report."""
    keys = {}
    for line in stdout.splitlines():
        m = KEY_LINE.match(line)
        if m:
            keys[m.group(1)] = (float(m.group(2)), float(m.group(3)) if m.group(3) else None,
                                m.group(5))
    return keys


def fit_summary(stdout):
    m = re.search(r'^timing fit: .*$', stdout, re.M)
    runs = re.search(r'^  (\d+) runs? found: (\d+) of the programs given \((\d+) usable\), (\d+)',
                     stdout, re.M)
    notes = re.findall(r'^  note: (.*)$', stdout, re.M)
    why = {}
    for line in stdout.splitlines():
        m2 = re.match(r'^  \d+\s+\d{4}-\d\d-\d\d \d\d:\d\d:\d\d\s+\S+\s+[0-9.]+\s+\S+\s+\S+\s+\S+\s+\S+\s+\S+\s+(.*)$', line)
        if m2 and m2.group(1) != 'usable':
            for reason in m2.group(1).split('; '):
                reason = re.sub(r'\d\d:\d\d:\d\d', 'T', reason)
                reason = re.sub(r'[0-9.]+', 'N', reason)
                why[reason] = why.get(reason, 0) + 1
    return (m.group(0) if m else '-'), runs.groups() if runs else None, notes, why


def pct(p, m):
    return '-' if not m else '%+.1f%%' % (100 * (p - m) / m)


class Out:
    def __init__(self, markdown):
        self.md = markdown

    def title(self, text):
        print('\n' + ('## ' + text if self.md else text + '\n' + '-' * len(text)) + '\n')

    def table(self, head, rows):
        rows = [[str(c) for c in r] for r in rows]
        if self.md:
            print('| ' + ' | '.join(head) + ' |')
            print('|' + '|'.join('---' for _ in head) + '|')
            for r in rows:
                print('| ' + ' | '.join(r) + ' |')
        else:
            w = [max([len(h)] + [len(r[i]) for r in rows]) for i, h in enumerate(head)]
            print('  '.join(h.ljust(w[i]) for i, h in enumerate(head)))
            for r in rows:
                print('  '.join(c.ljust(w[i]) for i, c in enumerate(r)))
        print()


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--repo', required=True, help='usnistgov/smstestbed: bare git directory or work tree')
    ap.add_argument('--ncjoule', default=os.path.join(ROOT, 'build', 'plugin', 'ncjoule'))
    ap.add_argument('--base', default=os.path.join(ROOT, 'samples', 'machines', 'hurco-vmx24.toml'),
                    help='the base profile the fits start from (default: hurco-vmx24)')
    ap.add_argument('--case', choices=['A', 'B'], action='append',
                    help='run only this case (repeat for both; default: both)')
    ap.add_argument('--markdown', action='store_true')
    ap.add_argument('--keep', help='keep the extracted data and the calibrated profiles here')
    args = ap.parse_args(argv)
    ncjoule = os.path.abspath(args.ncjoule)
    if not os.access(ncjoule, os.X_OK):
        print('error: no ncjoule at %s (build it, or give --ncjoule)' % ncjoule, file=sys.stderr)
        return 1
    repo = Repo(args.repo)
    work = os.path.abspath(args.keep) if args.keep else tempfile.mkdtemp(prefix='controller_fit.')
    os.makedirs(work, exist_ok=True)
    out = Out(args.markdown)
    try:
        split = repo.list(SPLIT)
        if not split:
            print('error: %s holds no %s' % (args.repo, SPLIT), file=sys.stderr)
            return 1
        devices = repo.extract([DEVICES], work)
        if not devices:
            print('error: no %s in %s' % (DEVICES, args.repo), file=sys.stderr)
            return 1
        devices = devices[0]
        prog = {}
        for label, name in list(BOX.items()) + [('cover', COVER)] + \
                [('PLATE-%d' % k, 'NIST_MTC_CRADA_PLATE-%d.NC' % k) for k in range(1, 21)]:
            got = repo.extract([NC + name], work)
            if got:
                prog[label] = got[0]
        logs = {kind: repo.extract([n for n in split if re.search(pattern, n)], work)
                for kind, pattern in (('plates', r'/Plate-Op1-Hurco04-\d+of20\.txt$'),
                                      ('cover', r'/Cover-Op3-Hurco04-\d+of20\.txt$'),
                                      ('box', r'/Box-OP[123]-Hurco02-\d+of20\.txt$'),
                                      ('OP5', r'/Box-OP5-Hurco02-\d+of20\.txt$'))}
        plates = [prog[k] for k in sorted(prog, key=lambda s: (len(s), s)) if k.startswith('PLATE')]
        cases = [('A', 'Hurco04', 'the 20 plate programs', plates, logs['plates'],
                  'cover', prog.get('cover'), logs['cover']),
                 ('B', 'Hurco02', 'box OP1-OP3', [prog[k] for k in ('OP1', 'OP2', 'OP3') if k in prog],
                  logs['box'], 'box OP5', prog.get('OP5'), logs['OP5'])]

        print('# Calibrating the Hurco VMX24s from their own logs (NIST SMS Test Bed)' if args.markdown
              else 'Calibrating the Hurco VMX24s from their own logs (NIST SMS Test Bed)')
        print()
        print('- repository: %s; base profile: %s' % (repo.path, os.path.relpath(args.base, ROOT)
                                                     if args.base.startswith(ROOT) else args.base))
        print('- ncjoule calibrate --timing -m BASE --devices Devices.xml --program ... --log ...; '
              'ncjoule check-log PROGRAM --log ... -m PROFILE --json')
        results, keys, summaries = [], {}, {}
        for case, machine, fitted_on, programs, fit_logs, check_name, check_prog, check_logs in cases:
            if args.case and case not in args.case:
                continue
            if not programs or not fit_logs or not check_prog or not check_logs:
                print('- case %s skipped: the repository copy lacks its programs or logs' % case)
                continue
            profile = os.path.join(work, 'calibrated-%s.toml' % case)
            stdout, seconds = calibrate(ncjoule, args.base, devices, programs, fit_logs, profile)
            with open(os.path.join(work, 'calibrate-%s.txt' % case), 'w') as f:
                f.write(stdout)
            keys[case] = fitted_keys(stdout)
            summaries[case] = (fitted_on, machine, seconds) + fit_summary(stdout)
            base_check = check(ncjoule, args.base, devices, check_prog, check_logs)
            cal_check = check(ncjoule, profile, devices, check_prog, check_logs)
            results.append((case, machine, check_name, base_check, cal_check))

        out.title('Targets: the program kept out, on the profile fitted on the others')
        rows = []
        for case, machine, check_name, b, c in results:
            pb, pc = b['programs'][0], c['programs'][0]
            m = pb.get('measured', {}).get('median_s', 0)
            ok = m and abs(pc['predicted_s'] - m) / m <= TARGET_TOTAL
            rows.append([case, machine, check_name + ' (total)', pb['usable_runs'], '%.1f' % m,
                         '%.1f' % pb['predicted_s'], pct(pb['predicted_s'], m),
                         '%.1f' % pc['predicted_s'], pct(pc['predicted_s'], m),
                         'within 3%' if ok else 'NOT within 3%'])
            for ob, oc in zip(pb.get('operations', []), pc.get('operations', [])):
                mo = ob['measured']['median_s']
                ok = mo and abs(oc['predicted_s'] - mo) / mo <= TARGET_OP
                rows.append([case, machine, '  %s (T%s, line %d)' % (ob['name'], ob['tool'], ob['line']),
                             ob['measured']['runs'], '%.1f' % mo, '%.1f' % ob['predicted_s'],
                             pct(ob['predicted_s'], mo), '%.1f' % oc['predicted_s'],
                             pct(oc['predicted_s'], mo), 'within 5%' if ok else 'NOT within 5%'])
        out.table(['case', 'machine', 'checked', 'runs', 'measured s', 'base s', 'error',
                   'calibrated s', 'error', 'target'], rows)

        out.title('The fits')
        rows = []
        for case, (fitted_on, machine, seconds, line, runs, notes, why) in summaries.items():
            found = '%s runs, %s of the programs, %s usable, %s of others' % runs if runs else '-'
            rows.append([case, machine, fitted_on, found, line.replace('timing fit: ', ''),
                         '%.0f s' % seconds])
        out.table(['case', 'machine', 'fitted on', 'runs in the logs', 'fit', 'took'], rows)
        for case, (_, _, _, _, _, notes, why) in summaries.items():
            if why:
                print('Case %s, runs left out and why (times and numbers as T and N): %s' % (
                    case, '; '.join('%s (%d)' % kv for kv in sorted(why.items(), key=lambda kv: -kv[1]))))
                print()
            for n in notes:
                print('Case %s note: %s' % (case, n))
            print()

        out.title('Fitted keys against the hand-chosen hurco-vmx24 profile')
        names = sorted({k for ks in keys.values() for k in ks})
        rows = []
        for k in names:
            row = [k]
            base = None
            for case in keys:
                v = keys[case].get(k)
                if v is None:
                    row.append('-')
                    continue
                value, se, why = v
                if why:
                    row.append('%.4g (base: %s)' % (value, why.split(' (')[0]))
                else:
                    row.append('%.4g +- %.2g' % (value, se or 0))
            rows.append(row)
        hand = read_profile_keys(args.base)
        out.table(['key'] + ['case %s' % c for c in keys], rows)
        print('The base (hand-chosen) values: ' + ', '.join('%s = %s' % kv for kv in hand) + '.')
        print()
        if args.keep:
            print('Calibrated profiles and the fits\' reports: %s' % work)
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)
    return 0


def read_profile_keys(path):
    """The timing keys the base profile writes, as written (key, value)."""
    keys, table = [], ''
    wanted = re.compile(r'^(accel_\w+|arc_accel_\w+|rapid_\w+|transition_speed_ratio|settle_\w+|tool_change_\w+|'
                        r'optional_stop_\w+|program_end_\w+|coolant_on_\w+|spindle_ramp_\w+|spindle_waits)\s*=\s*([^#]+)')
    with open(path) as f:
        for line in f:
            h = re.match(r'^\[(.*)\]', line)
            if h:
                table = h.group(1)
                continue
            m = wanted.match(line.strip())
            if m and table.startswith('kinematics'):
                keys.append(('%s.%s' % (table, m.group(1)), m.group(2).strip()))
    return keys


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
