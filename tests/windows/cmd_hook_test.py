#!/usr/bin/env python3
"""The generic Windows hook (postprocessor-templates/generic/ncjoule-hook.cmd) under Wine's cmd.

- FILE mode: a program whose name has spaces, non-ASCII letters, & ( ) and ! is annotated in
  place by the real ncjoule.exe (strip gives it back), the hook says so and exits 0;
- nothing breaks a post: ncjoule missing, a profile that does not load, a file that does not
  exist, a double quote in a setting: exit 0, a warning, the file as it was;
- no machine profile set: ncjoule's own (the user config's, else its generic one) is used;
- /watch FOLDER /once: every NC file of the folder is annotated, other files are left alone.
(Environment: wine_common.py.)
"""
import os
import shutil

from wine_common import (MACHINES, ROOT, WORK, check, failures, finish, run_wine_cmd, run_windows, win,
                         NCJOULE_EXE)

HOOK = os.path.join(ROOT, "postprocessor-templates", "generic", "ncjoule-hook.cmd")
HAAS = os.path.join(MACHINES, "haas-vf0-pavanaskar2014.toml")
SAMPLE = os.path.join(ROOT, "samples", "programs", "pavanaskar-facing-x.ngc")
SAMPLE_STOCK = os.path.join(ROOT, "samples", "programs", "pavanaskar-facing-x.stock")

shutil.rmtree(os.path.join(WORK, "cmd hook"), ignore_errors=True)
FOLDER = os.path.join(WORK, "cmd hook", "Posts été")
os.makedirs(FOLDER)

# The hook relies on things of Windows' cmd that Wine's cmd (8.0) does not do: removing a
# double quote in delayed expansion (!all:"=! gives '"=' there) and a for /f over a text made
# of delimiters only running no loop (the hook's check of whole seconds). Under such a cmd every setting is refused (the hook
# then warns, exits 0 and changes nothing, as it must), so nothing else can be tested: the test
# says so and is skipped (exit 77), rather than testing another hook than the one shipped.
probe = os.path.join(WORK, "cmd hook", "probe.cmd")
with open(probe, "wb") as f:
    f.write(b'@echo off\r\nsetlocal EnableDelayedExpansion\r\nset "all=a"b"\r\n'
            b'set "unquoted=!all:"=!"\r\necho [!unquoted!]\r\n'
            b'set "one=a"\r\nfor /f "delims=" %%C in ("x!one!y") do echo [%%C]\r\n'
            b'for /f "delims=x0123456789" %%C in ("x1x3") do echo [not only delimiters]\r\n')
answer = run_wine_cmd([win(probe)]).stdout
works = {"quote removal in !var:\"=!": b"[ab]" in answer,
         "delayed expansion in for /f": b"[xay]" in answer,
         "for /f on a text of delimiters only": b"[not only" not in answer}
if not all(works.values()):
    print("SKIP: this Wine's cmd lacks what the hook uses: " +
          ", ".join(k for k, v in works.items() if not v))
    # What can be checked all the same: the hook refuses, warns, exits 0, changes nothing.
    p = os.path.join(FOLDER, "refused.nc")
    shutil.copyfile(SAMPLE, p)
    env = dict(os.environ, NCJOULE=win(NCJOULE_EXE), NCJOULE_MACHINE=win(HAAS))
    r = run_wine_cmd([win(HOOK), win(p)], env=env)
    with open(p, "rb") as f:
        check(r.returncode == 0 and b"warning" in r.stderr and f.read() == open(SAMPLE, "rb").read(),
              "under this cmd the hook must warn, exit 0 and leave the file: exit %d %r" %
              (r.returncode, r.stderr[-300:]))
    if failures:
        finish("cmd_hook")
    raise SystemExit(77)


def text(b):
    return b.decode("utf-8", errors="replace")


def hook(args, **settings):
    env = dict(os.environ, NCJOULE=win(NCJOULE_EXE), NCJOULE_MACHINE=win(HAAS), NCJOULE_QUIET="0",
               NCJOULE_INTERVAL="1")
    for k, v in settings.items():
        if v is None:
            env.pop(k, None)
        else:
            env[k] = v
    return run_wine_cmd([win(HOOK), *args], env=env)


def read(p):
    with open(p, "rb") as f:
        return f.read()


def post(name):
    p = os.path.join(FOLDER, name)
    shutil.copyfile(SAMPLE, p)
    shutil.copyfile(SAMPLE_STOCK, os.path.splitext(p)[0] + ".stock")
    return p


original = read(SAMPLE)

# FILE mode, a name cmd.exe would act on if the hook let it.
p = post("pièce & co (v2)!.nc")
r = hook([win(p)])
check(r.returncode == 0, "file mode: exit %d" % r.returncode)
check("ncjoule-hook: annotated" in text(r.stdout),
      "file mode: no 'annotated' line: %r %r" % (text(r.stdout)[-300:], text(r.stderr)[-300:]))
annotated = read(p)
check(annotated != original and b"NCJ " in annotated, "file mode: the file is not annotated")
s = run_windows("strip", win(p))
check(s.returncode == 0 and s.stdout == original, "file mode: strip does not give the post back")
r = hook([win(p)])
check(r.returncode == 0 and "unchanged" in text(r.stdout), "file mode, again: not 'unchanged': %r" %
      text(r.stdout)[-300:])

# Nothing fails the post, and the file stays as it was.
for what, settings in [
        ("ncjoule missing", {"NCJOULE": win(os.path.join(WORK, "no such folder", "ncjoule.exe"))}),
        ("a profile that does not load", {"NCJOULE_MACHINE": win(SAMPLE)}),
        ("a double quote in a setting", {"NCJOULE_ARGS": '--dialect "fanuc'})]:
    p = post("untouched.nc")
    r = hook([win(p)], **settings)
    check(r.returncode == 0, "%s: exit %d" % (what, r.returncode))
    check("warning" in text(r.stderr), "%s: no warning: %r" % (what, text(r.stderr)[-300:]))
    check(read(p) == original, "%s: the file was changed" % what)
# No machine profile set: ncjoule takes its own (the user config's, else the generic one).
p = post("no-machine.nc")
r = hook([win(p)], NCJOULE_MACHINE=None)
check(r.returncode == 0 and b"NCJ " in read(p), "no NCJOULE_MACHINE: not annotated: %r" %
      text(r.stderr)[-300:])
r = hook([win(os.path.join(FOLDER, "missing.nc"))])
check(r.returncode == 0 and "no such file" in text(r.stderr), "a missing file: %r" % text(r.stderr)[-300:])

# /watch FOLDER /once
watched = os.path.join(WORK, "cmd hook", "Output 部品")
os.makedirs(watched)
for name in ("a.nc", "b prog.tap"):
    shutil.copyfile(SAMPLE, os.path.join(watched, name))
with open(os.path.join(watched, "notes.txt"), "wb") as f:
    f.write(b"G1 X1\r\n")
r = hook(["/watch", win(watched), "/once"], NCJOULE_STOCK=open(SAMPLE_STOCK).read().strip())
check(r.returncode == 0, "/watch /once: exit %d" % r.returncode)
for name in ("a.nc", "b prog.tap"):
    check(b"NCJ " in read(os.path.join(watched, name)), "/watch /once: %s not annotated: %r %r" %
          (name, text(r.stdout)[-300:], text(r.stderr)[-300:]))
check(read(os.path.join(watched, "notes.txt")) == b"G1 X1\r\n", "/watch /once: notes.txt changed")

finish("cmd_hook")
