#!/usr/bin/env python3
"""`ncjoule doctor`: what it reports and when it fails. It passes (exit 0, "ncjoule is ready") on
a good set-up and names what it found; a user config that does not parse, a config naming a
profile that does not exist, and a broken installed profile make it fail (exit 2) with a message
that says which file and why; a profile folder that is not there is reported. A copy of the
program in a folder laid out as an installation (bin/, share/ncjoule/machines, share/ncjoule/hooks)
finds the profiles there by name: doctor, `profiles` and `estimate -m NAME`."""
import os
import shutil
import subprocess
import sys
import tempfile

NCJOULE = os.path.abspath(os.environ["NCJOULE"])
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
MACHINES = os.path.join(ROOT, "samples/machines")
failures = []

PROGRAM = """G21 G90 G17
T1 M6
S3000 M3
G0 X0 Y0 Z5
G1 Z-1 F300
G1 X50
G0 Z5
M30
"""


def check(condition, what, output=""):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)
        if output:
            print("     " + output[-1500:].replace("\n", "\n     "))


def write(path, text):
    with open(path, "w") as f:
        f.write(text)
    return path


def run(*args, program=NCJOULE, config=None, env_extra=None, cwd=None):
    env = {k: v for k, v in os.environ.items() if k not in ("NCJOULE_DATA_DIR", "XDG_CONFIG_HOME")}
    env["NCJOULE_CONFIG"] = config or os.path.join(work, "no-config.toml")
    env.update(env_extra or {})
    return subprocess.run([program, *args], capture_output=True, text=True, env=env,
                          cwd=cwd or work)


work = tempfile.mkdtemp(prefix="ncjoule-doctor-")
try:
    # A good set-up: everything it looks at is named, and it passes.
    r = run("doctor")
    out = r.stdout
    check(r.returncode == 0 and out.rstrip().endswith("ncjoule is ready"),
          f"doctor passes on a good set-up (exit {r.returncode})", out + r.stderr)
    check("ok    ncjoule " in out and " at " in out.splitlines()[0],
          "the version and where the program is", out)
    check("C library (libncjoule) " in out and "libncjoule.so" in out,
          "the C library and its file", out)
    check("with TBB " in out and "calibrate with Ceres " in out, "TBB and Ceres built in", out)
    check(f"machine profile folder {MACHINES}: " in out, "the source tree's profile folder", out)
    names = [l for l in out.splitlines() if "profiles by name" in l]
    check(len(names) == 1 and all(n in names[0] for n in ("generic-3axis", "haas-vf2",
                                                           "router-2.2kw-vfd")),
          "the profiles -m takes, by name", out)
    check("atomically in the current folder " + os.path.realpath(work) in out,
          "a file written and replaced in the current folder", out)
    check("NCJOULE_CONFIG names" in out and "no user config is used" in out,
          "a named user config that does not exist is said, not a failure", out)
    check(not any(n.startswith(".ncjoule-doctor") for n in os.listdir(work)),
          "the probe file is removed")

    # A profile folder that is not there is reported; the others still serve.
    nowhere = os.path.join(work, "nowhere")
    r = run("doctor", env_extra={"NCJOULE_DATA_DIR": nowhere})
    check(r.returncode == 0 and f"machine profile folder {nowhere}/machines: not there" in r.stdout,
          "a missing profile folder is reported", r.stdout)

    # A user config that does not parse: FAIL, naming the file, the line and why.
    broken = write(os.path.join(work, "broken.toml"), 'material = "brass"\nmachine = [\n')
    r = run("doctor", config=broken)
    check(r.returncode == 2 and f"FAIL  the user config {broken} cannot be used:" in r.stdout
          and f"{broken}:2:" in r.stdout and "not valid TOML" in r.stdout
          and "ncjoule cannot work as set up" in r.stdout,
          f"a broken user config fails with where and why (exit {r.returncode})", r.stdout)
    wrong_type = write(os.path.join(work, "wrong-type.toml"), "tool_units = \"furlongs\"\n")
    r = run("doctor", config=wrong_type)
    check(r.returncode == 2 and "tool_units: must be" in r.stdout,
          "a config with a bad value fails and says which key", r.stdout)

    # A config naming a profile that does not exist, by name or by file.
    unknown = write(os.path.join(work, "unknown.toml"), 'machine = "no-such-mill.toml"\n')
    r = run("doctor", config=unknown)
    check(r.returncode == 2 and "its machine profile" in r.stdout and "does not load" in r.stdout,
          "a config naming a missing profile fails", r.stdout)
    # A config naming a shipped profile by its file: it passes and says which machine it is.
    good = write(os.path.join(work, "good.toml"),
                 f'machine = "{os.path.join(MACHINES, "haas-vf2.toml")}"\n')
    r = run("doctor", config=good)
    check(r.returncode == 0 and f"ok    user config {good}" in r.stdout
          and "its machine profile: " in r.stdout, "a good user config passes", r.stdout)

    # The program laid out as installed: profiles and hooks next to its bin folder.
    prefix = os.path.join(work, "prefix")
    os.makedirs(os.path.join(prefix, "bin"))
    installed_machines = os.path.join(prefix, "share", "ncjoule", "machines")
    os.makedirs(installed_machines)
    os.makedirs(os.path.join(prefix, "share", "ncjoule", "hooks", "generic"))
    installed = os.path.join(prefix, "bin", "ncjoule")
    shutil.copy2(NCJOULE, installed)
    shutil.copy(os.path.join(MACHINES, "router-desktop-grbl.toml"),
                os.path.join(installed_machines, "test-installed-mill.toml"))
    r = run("doctor", program=installed)
    check(r.returncode == 0 and f"machine profile folder {installed_machines}: 1 profile" in r.stdout
          and "test-installed-mill" in r.stdout
          and "post-processor hooks in " + os.path.join(prefix, "share", "ncjoule", "hooks")
          in r.stdout,
          "installed: doctor finds the profiles and hooks next to its bin folder", r.stdout)
    r = run("profiles", program=installed)
    check(r.returncode == 0 and any(l.startswith("test-installed-mill ") for l in r.stdout.splitlines()),
          "installed: `ncjoule profiles` lists them by name", r.stdout + r.stderr)
    part = write(os.path.join(work, "part.nc"), PROGRAM)
    r = run("estimate", part, "-m", "test-installed-mill", "--no-removal", "--json",
            program=installed)
    check(r.returncode == 0 and "test-installed-mill.toml" in r.stdout,
          "installed: estimate -m NAME takes the installed profile", r.stdout[-600:] + r.stderr)

    # A broken installed profile: FAIL, naming it.
    write(os.path.join(installed_machines, "broken-mill.toml"), "[machine\nname = 3\n")
    r = run("doctor", program=installed)
    check(r.returncode == 2 and "broken-mill.toml does not load" in r.stdout,
          "a broken installed profile fails doctor and is named", r.stdout)

    # Writing here: a folder it cannot write in is said (root may write anywhere: skipped).
    if os.geteuid() != 0:
        locked = os.path.join(work, "locked")
        os.makedirs(locked)
        os.chmod(locked, 0o555)
        r = run("doctor", cwd=locked)
        check("cannot write a file in the current folder" in r.stdout,
              "a folder that cannot be written in is said", r.stdout)
        os.chmod(locked, 0o755)
finally:
    shutil.rmtree(work, ignore_errors=True)

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("all doctor checks passed")
