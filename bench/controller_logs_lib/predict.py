"""Runs ncjoule on a program and reads its JSON: the predicted time in total, per line and per
operation."""

import json
import os
import subprocess
import time


# ----------------------------------------------------------------------------------------
# ncjoule's prediction.

def run_ncjoule(ncjoule, prog, machine, extra, workdir):
    """ncjoule estimate --json for one program; retried while the binary is being rebuilt."""
    path = os.path.join(workdir, prog.path.split('/')[-1])
    with open(path, 'w', encoding='utf-8', newline='') as f:
        f.write(prog.text)
    cmd = [ncjoule, 'estimate', '--json', path, '-m', machine, '--no-removal'] + extra
    last = ''
    for _ in range(40):                       # up to ~2 minutes: a rebuild may be under way
        if not os.path.exists(ncjoule):
            last = 'binary missing'
            time.sleep(3)
            continue
        try:
            out = subprocess.run(cmd, capture_output=True, text=True)
        except OSError as e:
            last = str(e)
            time.sleep(3)
            continue
        if out.stdout.strip():
            try:
                return json.loads(out.stdout)
            except ValueError:
                last = 'unreadable JSON'
        else:
            # a crash (negative code) is typical of a library rebuilt before the binary
            last = 'exit code %d %s' % (out.returncode, out.stderr.strip()[-300:])
        time.sleep(3)
    raise RuntimeError('ncjoule failed on %s: %s' % (prog.name, last))


class Prediction:
    def __init__(self, doc):
        self.total = doc['time_s']
        self.per_line = {}
        self.kind = {}
        for b in doc['blocks']:
            self.per_line[b['line']] = self.per_line.get(b['line'], 0.0) + b['time_s']
            self.kind[b['line']] = b['kind']
        self.ops = [(o.get('name', ''), o.get('tool'), o['line'], o['time_s'])
                    for o in doc.get('operations', [])]

    def between(self, a, b):
        """Predicted time of lines a <= line < b."""
        return sum(t for ln, t in self.per_line.items() if a <= ln < b)
