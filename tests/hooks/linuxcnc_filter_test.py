"""The LinuxCNC [FILTER] program (postprocessor-templates/linuxcnc/ncjoule-filter) by the filter
contract: LinuxCNC runs it as `sh -c "PROGRAM 'FILE'"` with stdin closed, takes the G-code from
stdout, reads FILTER_PROGRESS=N lines on stderr, and treats a non-zero exit as a failure (stderr
is the message). Every readable program is shown (exit 0): annotated where ncjoule can estimate
it, else as it is with the reason on stderr. The original file is never modified.

Usage: NCJOULE=path/to/ncjoule NCJOULE_SOURCE_DIR=repo python3 linuxcnc_filter_test.py
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.environ.get("NCJOULE_SOURCE_DIR",
                      os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
NCJOULE = os.path.abspath(os.environ.get("NCJOULE", "ncjoule"))
FILTER = os.path.join(ROOT, "postprocessor-templates", "linuxcnc", "ncjoule-filter")
MACHINE = os.path.join(ROOT, "samples", "machines", "zhou2017-anziani2025.toml")
SAMPLE = os.path.join(ROOT, "samples", "programs", "anziani-table2-5.ngc")
with open(os.path.join(ROOT, "samples", "programs", "anziani-table2-5.stock")) as f:
    STOCK = f.read().strip()

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL " + message)
    return condition


def q(text):
    return "'" + text.replace("'", "'\\''") + "'"


def run_filter(program, file, env=None):
    """Like LinuxCNC: sh -c "PROGRAM 'FILE'" with stdin closed."""
    full_env = dict(os.environ)
    for k in ("NCJOULE", "NCJOULE_MACHINE", "NCJOULE_STOCK", "NCJOULE_ARGS", "INI_FILE_NAME",
              "NCJOULE_DISABLE", "NCJOULE_FILTER_PASSTHROUGH", "NCJOULE_TIMEOUT"):
        full_env.pop(k, None)
    full_env.update(env or {})
    return subprocess.run(["sh", "-c", "%s %s" % (program, q(file))], stdin=subprocess.DEVNULL,
                          close_fds=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          env=full_env, preexec_fn=lambda: os.close(0))


def progress_values(stderr):
    return [int(m) for m in re.findall(r"^FILTER_PROGRESS=(\d+)$", stderr.decode(), re.M)]


def annotated(text):
    return re.search(rb"[(;]NCJ SEAL LINES=", text, re.I) is not None


def strip(data, folder):
    path = os.path.join(folder, "strip-me.ngc")
    with open(path, "wb") as f:
        f.write(data)
    r = subprocess.run([NCJOULE, "strip", path], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    check(r.returncode == 0, "ncjoule strip failed: %s" % r.stderr.decode())
    return r.stdout


def case(name):
    print("--- " + name)


def main():
    folder = tempfile.mkdtemp(prefix="ncjoule-filter-")
    program_file = os.path.join(folder, "part with space's.ngc")  # quoting must survive
    shutil.copyfile(SAMPLE, program_file)
    with open(program_file, "rb") as f:
        original = f.read()
    base = "%s --ncjoule %s --machine %s --stock %s" % (q(FILTER), q(NCJOULE), q(MACHINE), q(STOCK))

    case("annotates: G-code on stdout, progress on stderr, exit 0, file untouched")
    r = run_filter(base, program_file)
    check(r.returncode == 0, "exit %d: %s" % (r.returncode, r.stderr.decode()))
    check(annotated(r.stdout), "stdout is not annotated:\n%s" % r.stdout[:300].decode())
    check(strip(r.stdout, folder) == original, "strip(stdout) is not the original program")
    p = progress_values(r.stderr)
    check(len(p) >= 2 and p[0] == 0 and p[-1] == 100 and p == sorted(p),
          "FILTER_PROGRESS lines: %s" % p)
    check(all(line.startswith("FILTER_PROGRESS=") for line in r.stderr.decode().splitlines()),
          "stderr holds more than progress on success: %r" % r.stderr.decode())
    with open(program_file, "rb") as f:
        check(f.read() == original, "the original file was modified")

    case("settings from the INI's [NCJOULE] section (INI_FILE_NAME), relative to the INI")
    ini_dir = os.path.join(folder, "config")
    os.makedirs(ini_dir)
    shutil.copyfile(MACHINE, os.path.join(ini_dir, "mill.toml"))
    ini = os.path.join(ini_dir, "mill.ini")
    with open(ini, "w") as f:
        f.write("[FILTER]\nPROGRAM_EXTENSION = .ngc G-code\nngc = ncjoule-filter\n\n"
                "[NCJOULE]\nMACHINE = mill.toml\nPROGRAM = %s\nSTOCK = %s\n" % (NCJOULE, STOCK))
    r = run_filter(q(FILTER), program_file, {"INI_FILE_NAME": ini})
    check(r.returncode == 0, "INI: exit %d: %s" % (r.returncode, r.stderr.decode()))
    check(annotated(r.stdout), "INI: stdout not annotated")

    case("an error in the program: annotated all the same, the reason on stderr, exit 0")
    bad = os.path.join(folder, "bad.ngc")
    with open(bad, "wb") as f:
        f.write(b"(T1 D=6. CR=0. - ZMIN=-5. - FLAT END MILL)\nT1 M6\nG1 X10 F\nM30\n")
    with open(bad, "rb") as f:
        bad_original = f.read()
    r = run_filter(base, bad)
    check(r.returncode == 0, "bad program: exit %d" % r.returncode)
    check(annotated(r.stdout) and strip(r.stdout, folder) == bad_original,
          "bad program: not annotated: %r" % r.stdout[:200])
    check("error" in r.stderr.decode(), "bad program: stderr %r" % r.stderr.decode())
    with open(bad, "rb") as f:
        check(f.read() == bad_original, "bad program: the file was modified")

    case("a tool no comment describes: annotated, the tool named on stderr")
    notool = os.path.join(folder, "notool.ngc")
    with open(notool, "wb") as f:
        f.write(b"G21 G90\nT7 M6\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X50\nM30\n")
    r = run_filter(base, notool)
    check(r.returncode == 0 and annotated(r.stdout), "no tool: exit %d" % r.returncode)
    check("T7" in r.stderr.decode(), "no tool: T7 not named: %r" % r.stderr.decode())

    case("the INI's [EMCIO] TOOL_TABLE describes the tools (in [TRAJ] LINEAR_UNITS)")
    with open(os.path.join(ini_dir, "tool.tbl"), "w") as f:
        f.write("T7 P7 Z1 D0.25 ;1/4 ball end mill\n")
    with open(ini, "a") as f:
        f.write("\n[EMCIO]\nTOOL_TABLE = tool.tbl\n\n[TRAJ]\nLINEAR_UNITS = inch\n")
    r = run_filter(q(FILTER), notool, {"INI_FILE_NAME": ini})
    check(r.returncode == 0 and annotated(r.stdout), "tool table: exit %d" % r.returncode)
    check("T7" not in r.stderr.decode(), "tool table: T7 still undescribed: %r" % r.stderr.decode())

    case("ncjoule cannot run: the program unannotated, the reason on stderr, exit 0")
    r = run_filter("%s --ncjoule %s --machine %s" % (q(FILTER), q(NCJOULE), q(os.path.join(folder, "no.toml"))),
                   program_file)
    check(r.returncode == 0 and r.stdout == original, "bad profile: not shown as it is")
    check("showing the program without annotations" in r.stderr.decode(), "bad profile: no reason given")

    case("missing ncjoule: the program as it is, and why")
    r = run_filter("%s --ncjoule %s --machine %s" % (q(FILTER), q(os.path.join(folder, "none")), q(MACHINE)),
                   program_file)
    check(r.returncode == 0 and "not found" in r.stderr.decode(), "missing ncjoule: %d %r" % (
        r.returncode, r.stderr.decode()))
    check(r.stdout == original, "missing ncjoule: the program is not shown")

    case("no machine profile: ncjoule's generic one, and a note saying so")
    r = run_filter("%s --ncjoule %s" % (q(FILTER), q(NCJOULE)), program_file)
    check(r.returncode == 0 and annotated(r.stdout), "no profile: not annotated: %r" % r.stderr.decode())
    check("no machine profile given" in r.stderr.decode(), "no profile: no note: %r" % r.stderr.decode())

    case("a program's own stock file wins over the INI's one STOCK")
    own = os.path.join(folder, "own.ngc")
    shutil.copyfile(SAMPLE, own)
    with open(os.path.join(folder, "own.stock"), "w") as f:
        f.write("box:0,0,-20,200,40,-1\n")  # its top 1 mm lower: less is cut
    r = run_filter(q(FILTER), own, {"INI_FILE_NAME": ini})
    check(r.returncode == 0 and annotated(r.stdout), "own stock: exit %d" % r.returncode)
    versions = {}
    for name, args in (("own", []), ("ini", ["--stock", STOCK])):
        e = subprocess.run([NCJOULE, "annotate", own, "--machine", os.path.join(ini_dir, "mill.toml")]
                           + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        versions[name] = e.stdout
    def volume(text):
        m = re.search(rb"VOL_MM3=([0-9.]+)", text)
        return float(m.group(1)) if m else None
    check(volume(versions["own"]) != volume(versions["ini"]),
          "own stock: the two stocks cut the same volume")
    check(volume(r.stdout) == volume(versions["own"]), "own stock: the filter used the INI's STOCK "
          "(%r, own %r)" % (volume(r.stdout), volume(versions["own"])))
    os.remove(os.path.join(folder, "own.stock"))

    case("file names that look like options are files")
    for name in ("-h", "-", "-o.ngc", "--help"):
        odd = os.path.join(folder, name)
        shutil.copyfile(SAMPLE, odd)
        r = subprocess.run(["sh", "-c", "cd %s && %s %s" % (q(folder), base, q(name))],
                           stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        check(r.returncode == 0 and annotated(r.stdout) and strip(r.stdout, folder) == original,
              "file %r: exit %d %r" % (name, r.returncode, r.stderr.decode()[:200]))
        os.remove(odd)

    case("a failing ncjoule with PASSTHROUGH = 0: the program is still shown, exit 0")
    bad_ini = os.path.join(ini_dir, "bad.ini")
    with open(os.path.join(ini_dir, "bad.toml"), "w") as f:
        f.write("not = [ a profile\n")
    with open(bad_ini, "w") as f:
        f.write("[NCJOULE]\nMACHINE = bad.toml\nPROGRAM = %s\nPASSTHROUGH = 0\n" % NCJOULE)
    r = run_filter(q(FILTER), program_file, {"INI_FILE_NAME": bad_ini})
    check(r.returncode == 0 and r.stdout == original, "PASSTHROUGH = 0: exit %d, shown %s" % (
        r.returncode, r.stdout == original))
    check("showing the program without annotations" in r.stderr.decode() and "exit 2" in r.stderr.decode(),
          "PASSTHROUGH = 0: no reason: %r" % r.stderr.decode())

    case("NCJOULE_ARGS is split into words, never run by a shell; an unclosed quote is a failure")
    r = run_filter(base, program_file, {"NCJOULE_ARGS": "--no-removal; touch X $(touch X)"})
    check(not os.path.exists("X") and not os.path.exists(os.path.join(folder, "X")),
          "NCJOULE_ARGS ran a command")
    check(r.returncode == 0 and r.stdout == original and "exit 1" in r.stderr.decode(),
          "stray words: exit %d %r" % (r.returncode, r.stderr.decode()))
    r = run_filter(base, program_file, {"NCJOULE_ARGS": "--dialect 'fanuc"})
    check(r.returncode == 0 and r.stdout == original and "cannot be split" in r.stderr.decode(),
          "unclosed quote: exit %d %r" % (r.returncode, r.stderr.decode()))
    r = run_filter(base, program_file, {"NCJOULE_ARGS": "--dialect 'linuxcnc'"})
    check(r.returncode == 0 and annotated(r.stdout), "quoted word: %r" % r.stderr.decode())

    case("the filter's own arguments wrong: the usage, exit 1")
    r = run_filter("%s --bogus" % q(FILTER), program_file)
    check(r.returncode == 1 and "unknown option --bogus" in r.stderr.decode() and not r.stdout,
          "unknown option: exit %d %r" % (r.returncode, r.stderr.decode()))
    r = run_filter("%s --machine" % q(FILTER), program_file)
    check(r.returncode == 1 and "needs a value" in r.stderr.decode(), "no value: %r" % r.stderr.decode())

    case("an argument that would write a file (--in-place, -o) is refused: the file never changes")
    for args in ("--in-place", "-i", "-vi", "--output=x.ngc", "-o x.ngc", "--in-place=yes"):
        r = run_filter(base, program_file, {"NCJOULE_ARGS": args})
        check(r.returncode == 0 and r.stdout == original and "write a file" in r.stderr.decode(),
              "ARGS %r: exit %d %r" % (args, r.returncode, r.stderr.decode()))
    with open(os.path.join(ini_dir, "inplace.ini"), "w") as f:
        f.write("[NCJOULE]\nMACHINE = mill.toml\nPROGRAM = %s\nARGS = --in-place\n" % NCJOULE)
    r = run_filter(q(FILTER), program_file, {"INI_FILE_NAME": os.path.join(ini_dir, "inplace.ini")})
    check(r.returncode == 0 and r.stdout == original and "write a file" in r.stderr.decode(),
          "INI ARGS --in-place: %r" % r.stderr.decode())
    r = run_filter("%s -- --in-place" % base, program_file)
    check(r.returncode == 0 and r.stdout == original, "-- --in-place: %r" % r.stderr.decode())
    # A value that holds an i or an o is no option: "-m" takes the rest of its word.
    r = run_filter("%s --ncjoule %s --stock %s" % (q(FILTER), q(NCJOULE), q(STOCK)), program_file,
                   {"NCJOULE_ARGS": "-m" + MACHINE})
    check(r.returncode == 0 and annotated(r.stdout), "-mPROFILE: %r" % r.stderr.decode())
    with open(program_file, "rb") as f:
        check(f.read() == original, "ARGS --in-place: the original file was modified")

    case("a time limit: an ncjoule that takes too long is stopped, the program shown as it is")
    slow = os.path.join(folder, "slow-ncjoule")
    with open(slow, "w") as f:
        f.write("#!/bin/sh\nexec sleep 30\n")
    os.chmod(slow, 0o755)
    import time
    started = time.monotonic()
    r = run_filter("%s --ncjoule %s --machine %s" % (q(FILTER), q(slow), q(MACHINE)), program_file,
                   {"NCJOULE_TIMEOUT": "1"})
    took = time.monotonic() - started
    check(r.returncode == 0 and r.stdout == original and "was stopped" in r.stderr.decode(),
          "timeout: exit %d %r" % (r.returncode, r.stderr.decode()))
    check(took < 10, "timeout: took %.1f s" % took)
    r = run_filter(base, program_file, {"NCJOULE_TIMEOUT": "soon"})
    check(r.returncode == 0 and r.stdout == original and "TIMEOUT" in r.stderr.decode(),
          "bad timeout: %r" % r.stderr.decode())

    case("unreadable file: non-zero exit")
    r = run_filter(base, os.path.join(folder, "does-not-exist.ngc"))
    check(r.returncode != 0 and "cannot read" in r.stderr.decode(), "missing file: %r" % r.stderr.decode())

    case("NCJOULE_DISABLE=1 passes the program through unchanged")
    r = run_filter(base, program_file, {"NCJOULE_DISABLE": "1"})
    check(r.returncode == 0 and r.stdout == original, "disabled: not passed through")

    with open(program_file, "rb") as f:
        check(f.read() == original, "the original file was modified")
    shutil.rmtree(folder, ignore_errors=True)
    if failures:
        print("%d failure(s)" % len(failures))
        return 1
    print("all filter contract checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
