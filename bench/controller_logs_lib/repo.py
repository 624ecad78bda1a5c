"""Lists and reads the smstestbed repository's files, from a bare git directory or a work
tree."""

import os
import subprocess

from .constants import LOG_DIRS, NC_DIR


# ----------------------------------------------------------------------------------------
# Reading the repository: a bare git directory (files read with git) or a work tree.

class Repo:
    """Lists and reads files of the smstestbed repository, bare or checked out."""

    def __init__(self, path):
        self.path = os.path.abspath(path)
        self.bare = os.path.isfile(os.path.join(self.path, 'HEAD')) and \
            os.path.isdir(os.path.join(self.path, 'objects'))
        self.missing = []            # files listed but whose contents are not here
        self._tree = None

    def valid(self):
        if self.bare:
            return self._git('rev-parse', '--verify', '-q', 'HEAD^{tree}') is not None
        return os.path.isdir(os.path.join(self.path, 'tdp', 'mtc'))

    def _git(self, *args, data=None):
        try:
            out = subprocess.run(['git', '--git-dir=' + self.path] + list(args), input=data,
                                 capture_output=True, check=True)
        except (OSError, subprocess.CalledProcessError):
            return None
        return out.stdout

    def tree(self):
        """{path: object id (bare) or absolute path (work tree)} of every file."""
        if self._tree is not None:
            return self._tree
        self._tree = {}
        if self.bare:
            out = self._git('ls-tree', '-r', '-z', 'HEAD', '--', *LOG_DIRS, NC_DIR) or b''
            for rec in out.split(b'\0'):
                if not rec:
                    continue
                meta, name = rec.split(b'\t', 1)
                kind, oid = meta.split()[1:3]
                if kind == b'blob':
                    self._tree[name.decode('utf-8', 'replace')] = oid.decode()
        else:
            for top in LOG_DIRS + (NC_DIR,):
                base = os.path.join(self.path, top)
                for d, _, files in os.walk(base):
                    for f in files:
                        full = os.path.join(d, f)
                        self._tree[os.path.relpath(full, self.path).replace(os.sep, '/')] = full
        return self._tree

    def read_many(self, names):
        """{name: text} for the names whose contents are here; the rest go to self.missing."""
        tree = self.tree()
        out = {}
        if self.bare:
            # One git process for all blobs: thousands of small daily files otherwise take long.
            oids = [tree[n] for n in names]
            raw = self._git('cat-file', '--batch', data=('\n'.join(oids) + '\n').encode()) or b''
            pos = 0
            for n in names:
                end = raw.index(b'\n', pos)
                header = raw[pos:end].split()
                pos = end + 1
                if len(header) < 3 or header[1] != b'blob':      # "<oid> missing"
                    self.missing.append(n)
                    continue
                size = int(header[2])
                out[n] = raw[pos:pos + size].decode('utf-8', 'replace')
                pos += size + 1
        else:
            for n in names:
                try:
                    with open(tree[n], 'rb') as f:
                        data = f.read()
                except OSError:
                    self.missing.append(n)
                    continue
                if data.startswith(b'version https://git-lfs'):   # an LFS pointer, not data
                    self.missing.append(n)
                    continue
                out[n] = data.decode('utf-8', 'replace')
        return out
