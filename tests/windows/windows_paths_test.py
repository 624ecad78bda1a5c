#!/usr/bin/env python3
"""ncjoule.exe under Wine reading and writing real files through Windows paths.

- Drive-letter paths with backslashes (Z:\\...), forward slashes, relative paths with
  backslashes; folder and file names with spaces, accents and CJK letters: the program is read,
  the PROGRAM.stock next to it is found, the output file gets the right name (checked on the
  Linux side, so the UTF-8 -> UTF-16 -> file system round trip is right), and the numbers are the
  Linux build's.
- CR LF programs: annotate --in-place keeps CR LF and gives the Linux build's bytes; strip gives
  the original bytes back; the same through standard input and output (binary mode).
- Replacing an existing output leaves no temporary file; an output that is a folder or in a
  missing folder is exit 3 with the original untouched; NUL (a device) is written in place.
- --in-place refuses a file another Windows program holds open for writing (exit 3, untouched).
- The bundled profiles are found next to the installed program (profiles, -m NAME).
- The user config is %APPDATA%\\ncjoule\\config.toml (not $XDG_CONFIG_HOME or ~/.config), and
  NCJOULE_CONFIG still wins; `doctor` names where it looked.
- Messages name files with non-ASCII letters in UTF-8.
(Environment: wine_common.py.)
"""
import glob
import json
import os
import shutil
import subprocess

from wine_common import (MACHINES, ROOT, WORK, check, compare_numbers, finish, parse_json,
                         run_linux, run_wine_cmd, run_windows, win, NCJOULE_EXE)

SAMPLE = os.path.join(ROOT, "samples", "programs", "bracket-linuxcnc.ngc")
SAMPLE_STOCK = os.path.join(ROOT, "samples", "programs", "bracket-linuxcnc.stock")
GENERIC = os.path.join(MACHINES, "generic-3axis.toml")
HAAS = os.path.join(MACHINES, "haas-vf2.toml")

shutil.rmtree(os.path.join(WORK, "paths"), ignore_errors=True)
FOLDER = os.path.join(WORK, "paths", "Atelier été 部品", "sub dir")
os.makedirs(FOLDER)


def text(b):
    return b.decode("utf-8", errors="replace")


def same_estimate(windows_args, linux_args, what):
    w = run_windows("estimate", *windows_args, "--json")
    lin = run_linux("estimate", *linux_args, "--json")
    if not check(w.returncode == 0, "%s: exit %d: %s" % (what, w.returncode, text(w.stderr)[-500:])):
        return None
    a, b = parse_json(lin.stdout, what + " (Linux)"), parse_json(w.stdout, what + " (Windows)")
    if a is None or b is None:
        return None
    differences, _, _ = compare_numbers(a, b, what, ignore_strings=True)
    check(not differences, "%s: differs from Linux: %s" % (what, "; ".join(differences[:5])))
    return b


# --- names with spaces and non-ASCII letters, in folders of such names -----------------------
program = os.path.join(FOLDER, "pièce 1 (v2) 部品.ngc")
shutil.copyfile(SAMPLE, program)
shutil.copyfile(SAMPLE_STOCK, os.path.splitext(program)[0] + ".stock")
doc = same_estimate([win(program), "--machine", win(GENERIC)], [program, "--machine", GENERIC],
                    "backslash path with spaces and non-ASCII letters")
if doc:
    check(doc.get("setups", [{}])[0].get("stock_source") == "given",
          "the .stock next to a non-ASCII program was not read: %r" % doc.get("stock"))
same_estimate([win(program).replace("\\", "/"), "--machine", win(GENERIC).replace("\\", "/")],
              [program, "--machine", GENERIC], "forward-slash drive path")
rel = os.path.relpath(program, os.path.join(WORK, "paths")).replace("/", "\\")
w = run_windows("estimate", rel, "--machine", win(GENERIC), cwd=os.path.join(WORK, "paths"))
check(w.returncode == 0, "relative path with backslashes: exit %d: %s" % (w.returncode, text(w.stderr)[-300:]))

# --- annotate -o to a new file with a non-ASCII name ---------------------------------------------
out = os.path.join(FOLDER, "sortie annotée Ω.ngc")
w = run_windows("annotate", win(program), "--machine", win(GENERIC), "-o", win(out))
lin = run_linux("annotate", program, "--machine", GENERIC)
check(w.returncode == 0, "annotate -o: exit %d: %s" % (w.returncode, text(w.stderr)[-300:]))
if check(os.path.isfile(out), "annotate -o did not write %r (files: %r)" % (out, os.listdir(FOLDER))):
    with open(out, "rb") as f:
        check(f.read() == lin.stdout, "annotate -o: bytes differ from the Linux build's")
# Replacing it: the new text, and no temporary file left next to it.
with open(out, "wb") as f:
    f.write(b"old text\n")
w = run_windows("annotate", win(program), "--machine", win(GENERIC), "-o", win(out))
with open(out, "rb") as f:
    check(w.returncode == 0 and f.read() == lin.stdout, "annotate -o over an existing file")
check(not [n for n in os.listdir(FOLDER) if ".ncjoule-" in n],
      "a temporary file was left behind: %r" % os.listdir(FOLDER))

# --- CR LF ---------------------------------------------------------------------------------------
with open(SAMPLE, "rb") as f:
    lf = f.read()
crlf = lf.replace(b"\r\n", b"\n").replace(b"\n", b"\r\n")
crlf_file = os.path.join(FOLDER, "crlf é.nc")
linux_copy = os.path.join(WORK, "paths", "crlf-linux.nc")
for p in (crlf_file, linux_copy):
    with open(p, "wb") as f:
        f.write(crlf)
shutil.copyfile(SAMPLE_STOCK, os.path.splitext(crlf_file)[0] + ".stock")
shutil.copyfile(SAMPLE_STOCK, os.path.splitext(linux_copy)[0] + ".stock")
w = run_windows("annotate", "--machine", win(GENERIC), "--in-place", win(crlf_file))
lin = run_linux("annotate", "--machine", GENERIC, "--in-place", linux_copy)
check(w.returncode == 0 and lin.returncode == 0,
      "annotate --in-place CR LF: exit %d / %d: %s" % (w.returncode, lin.returncode, text(w.stderr)[-300:]))
check("annotated" in text(w.stderr), "annotate --in-place: no status line: %r" % text(w.stderr)[-300:])
with open(crlf_file, "rb") as f:
    annotated = f.read()
with open(linux_copy, "rb") as f:
    check(annotated == f.read(), "annotate --in-place of a CR LF program: bytes differ from Linux")
check(annotated != crlf and annotated.count(b"\n") == annotated.count(b"\r\n"),
      "the annotated CR LF program has bare LF line ends or no annotations")
s = run_windows("strip", win(crlf_file))
check(s.returncode == 0 and s.stdout == crlf, "strip of the CR LF program is not the original")
# Through standard input and output: nothing translated, ^Z is no end of file.
stdin_program = crlf + b"(a comment with \x1a in it)\r\n"
w = run_windows("annotate", "--machine", win(GENERIC), "-", stdin=stdin_program)
lin = run_linux("annotate", "--machine", GENERIC, "-", stdin=stdin_program)
check(w.returncode == lin.returncode and w.stdout == lin.stdout and len(w.stdout) > len(stdin_program),
      "annotate from standard input to standard output differs from Linux (%d vs %d bytes)" %
      (len(w.stdout), len(lin.stdout)))

# --- outputs that cannot be replaced -------------------------------------------------------------
w = run_windows("annotate", win(program), "--machine", win(GENERIC), "-o", win(FOLDER))
check(w.returncode == 3 and "directory" in text(w.stderr), "output to a folder: exit %d %r" %
      (w.returncode, text(w.stderr)[-200:]))
w = run_windows("annotate", win(program), "--machine", win(GENERIC), "-o",
                win(os.path.join(FOLDER, "no such folder", "x.ngc")))
check(w.returncode == 3, "output into a missing folder: exit %d" % w.returncode)
w = run_windows("annotate", win(program), "--machine", win(GENERIC), "-o", "NUL")
check(w.returncode == 0, "output to NUL: exit %d: %s" % (w.returncode, text(w.stderr)[-200:]))
check(not [n for n in os.listdir(FOLDER) if ".ncjoule-" in n], "a temporary file was left behind")

# --- a file another program is still writing -----------------------------------------------------
busy = os.path.join(FOLDER, "still being written.ngc")
shutil.copyfile(SAMPLE, busy)
with open(busy, "rb") as f:
    before = f.read()
# cmd.exe holds the file open for writing (a redirection of ncjoule's standard output, which
# --in-place leaves empty) while ncjoule runs: a post that has not closed its output yet.
r = run_wine_cmd([win(NCJOULE_EXE), "annotate", "--machine=" + win(GENERIC), "--in-place", win(busy),
                  ">>", win(busy)])
with open(busy, "rb") as f:
    after = f.read()
# (cmd.exe gives back its own exit status here, not ncjoule's 3: the message tells.)
check(r.returncode != 0, "--in-place on a file held open for writing: exit %d: %s" %
      (r.returncode, text(r.stderr)[-300:]))
check("still being written" in text(r.stderr), "no 'still being written' message: %r" % text(r.stderr)[-300:])
check(after == before, "the file held open for writing was changed")
# Once it is closed, the same command annotates it.
w = run_windows("annotate", "--machine", win(GENERIC), "--in-place", win(busy))
check(w.returncode == 0, "--in-place once the writer is gone: exit %d: %s" % (w.returncode, text(w.stderr)[-300:]))

# --- profiles installed next to the program --------------------------------------------------------
w = run_windows("profiles")
shipped = sorted(os.path.splitext(os.path.basename(p))[0] for p in glob.glob(os.path.join(MACHINES, "*.toml")))
check(w.returncode == 0 and all(name in text(w.stdout) for name in shipped),
      "profiles does not list every bundled profile: %r" % text(w.stdout)[-500:])
doc = same_estimate([win(program), "-m", "haas-vf2"], [program, "--machine", HAAS], "-m NAME")
if doc:
    check(doc["machine"]["file"].lower().endswith("share\\ncjoule\\machines\\haas-vf2.toml"),
          "-m haas-vf2 did not take the installed profile: %r" % doc["machine"]["file"])

# --- the user config in %APPDATA% -----------------------------------------------------------------
echo = run_wine_cmd(["echo", "%APPDATA%"])
appdata = text(echo.stdout).strip()
check(appdata.lower().startswith("c:\\users\\"), "APPDATA under Wine: %r" % appdata)
appdata_linux = os.path.join(os.environ["WINEPREFIX"], "drive_c", *appdata.split("\\")[1:])
config_folder = os.path.join(appdata_linux, "ncjoule")
shutil.rmtree(config_folder, ignore_errors=True)
os.makedirs(config_folder)
with open(os.path.join(config_folder, "config.toml"), "w", encoding="utf-8") as f:
    f.write('machine = "%s"\n' % win(HAAS).replace("\\", "/"))
decoy = os.path.join(WORK, "paths", "xdg")
os.makedirs(os.path.join(decoy, "ncjoule"), exist_ok=True)
with open(os.path.join(decoy, "ncjoule", "config.toml"), "w") as f:
    f.write('machine = "%s"\n' % GENERIC)
env = dict(os.environ, XDG_CONFIG_HOME=decoy, HOME=os.path.join(WORK, "paths"))
env.pop("NCJOULE_CONFIG", None)
w = run_windows("estimate", win(program), "--json", env=env)
doc = parse_json(w.stdout, "estimate with the user config") if w.returncode == 0 else None
check(doc is not None and doc["machine"]["name"] == json.loads(
    run_linux("estimate", program, "--machine", HAAS, "--json").stdout)["machine"]["name"],
      "the machine of %%APPDATA%%\\ncjoule\\config.toml was not used: exit %d %r" %
      (w.returncode, text(w.stderr)[-300:]))
w = run_windows("estimate", win(program), "--json", env=dict(env, NCJOULE_CONFIG=win(os.path.join(decoy, "ncjoule", "config.toml"))))
doc = parse_json(w.stdout, "estimate with NCJOULE_CONFIG") if w.returncode == 0 else None
check(doc is not None and doc["machine"]["name"] == "Generic 3-axis VMC",
      "NCJOULE_CONFIG did not win over %%APPDATA%%: %r" % (doc and doc["machine"]["name"]))
w = run_windows("doctor", env=env)
check("ncjoule\\config.toml" in text(w.stdout) and "AppData" in text(w.stdout),
      "doctor does not name %%APPDATA%%\\ncjoule\\config.toml: %r" % text(w.stdout)[-800:])
shutil.rmtree(config_folder, ignore_errors=True)

# --- messages with non-ASCII names -----------------------------------------------------------------
missing = os.path.join(FOLDER, "manquant ü 部品.ngc")
w = run_windows("estimate", win(missing), "--machine", win(GENERIC))
check(w.returncode == 2 and "manquant ü 部品.ngc" in text(w.stderr),
      "a missing non-ASCII file: exit %d, message %r" % (w.returncode, text(w.stderr)[-300:]))

finish("windows_paths")
