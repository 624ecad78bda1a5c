#!/usr/bin/env python3
"""Set once, use everywhere: the user config (NCJOULE_CONFIG / ~/.config/ncjoule/config.toml),
the job and stock files next to a program (PROGRAM.ncjoule.toml, PROGRAM.stock), the default
machine profile when none is named, and which source wins. Also `ncjoule doctor` and
`ncjoule --version`."""
import json
import os
import shutil
import subprocess
import sys
import tempfile

NCJOULE = os.environ["NCJOULE"]
ROOT = os.environ["NCJOULE_SOURCE_DIR"]
MACHINES = os.path.join(ROOT, "samples/machines")
GENERIC = os.path.join(MACHINES, "generic-3axis.toml")
HAAS = os.path.join(MACHINES, "haas-vf0-pavanaskar2014.toml")
failures = []

# A side cut with a 12 mm end mill that no comment describes: the tool must come from somewhere.
PROGRAM = """G21 G90 G17
T1 M6
S3000 M3
G0 X-10 Y10 Z5
G1 Z-2 F300
G1 X110
G0 Z5
M30
"""


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def run(*args, config=None, **kw):
    env = dict(os.environ)
    env["NCJOULE_CONFIG"] = config or os.path.join(work, "no-config.toml")
    return subprocess.run([NCJOULE, *args], capture_output=True, text=True, env=env, **kw)


def estimate(program, *args, config=None):
    r = run("estimate", program, "--json", *args, config=config)
    return r, (json.loads(r.stdout) if r.returncode in (0, 2) and r.stdout.lstrip().startswith("{") else None)


def write(path, text):
    with open(path, "w") as f:
        f.write(text)
    return path


work = tempfile.mkdtemp(prefix="ncjoule-config-")
try:
    part = write(os.path.join(work, "part.nc"), PROGRAM)

    # No machine named anywhere: the generic profile, with a note saying so.
    r, doc = estimate(part)
    check(r.returncode == 0 and doc is not None, f"estimate runs without --machine ({r.stderr[-200:]!r})")
    if doc:
        check(doc["machine"]["name"] == "Generic 3-axis VMC", "the generic profile is the default")
        check("no machine profile given" in r.stderr, "a note says the generic profile is used")
        check(doc["unsimulated_tools"] == [1], "T1 is described nowhere yet")
    r_m, doc_m = estimate(part, "--machine", GENERIC)
    check(doc and doc_m and doc["energy_j"] == doc_m["energy_j"], "same result as --machine generic")

    # The user config: machine (relative to the config's folder), material, stock.
    os.mkdir(os.path.join(work, "cfg"))
    shutil.copy(HAAS, os.path.join(work, "cfg", "mill.toml"))
    config = write(os.path.join(work, "cfg", "config.toml"),
                   'machine = "mill.toml"\nmaterial = "mild-steel"\nstock = "box:0,0,-10,100,20,0"\n')
    r, doc = estimate(part, config=config)
    check(r.returncode == 0 and doc is not None, f"estimate with a user config ({r.stderr[-200:]!r})")
    if doc:
        check(doc["machine"]["name"].startswith("Haas VF-0"), "the config's machine is used")
        check("no machine profile given" not in r.stderr, "no note when the config names one")
        check("-10.000" in doc["stock"] and "(given)" in doc["stock"], f"the config's stock ({doc['stock']})")
    # A shipped profile named by its name, as -m takes it, and not a file beside the config.
    by_name = write(os.path.join(work, "cfg", "by-name.toml"), 'machine = "haas-vf0-pavanaskar2014"\n')
    r, doc = estimate(part, config=by_name)
    check(r.returncode == 0 and doc is not None and doc["machine"]["name"].startswith("Haas VF-0"),
          f"machine = a shipped profile's name finds it ({r.stderr[-200:]!r})")
    # A job file beside the program names its machine: it wins over the user config's, and
    # --machine wins over it. A name finds a shipped profile, a .toml is a file beside the job.
    jobdir = os.path.join(work, "job")
    os.mkdir(jobdir)
    jpart = write(os.path.join(jobdir, "jpart.nc"), PROGRAM)
    job = write(os.path.join(jobdir, "jpart.ncjoule.toml"), 'machine = "haas-vf0-pavanaskar2014"\n')
    r, doc = estimate(jpart, config=by_name.replace("by-name", "no-such"))
    check(r.returncode == 0 and doc and doc["machine"]["name"].startswith("Haas VF-0")
          and "no machine profile given" not in r.stderr,
          f"the job file's machine (a name) is used ({r.stderr[-200:]!r})")
    shutil.copy(GENERIC, os.path.join(jobdir, "shop-mill.toml"))
    write(job, 'machine = "shop-mill.toml"\n')
    r, doc = estimate(jpart, config=by_name)
    check(r.returncode == 0 and doc and doc["machine"]["name"] == "Generic 3-axis VMC",
          f"the job file's machine (a file beside it) wins over the config's ({r.stderr[-200:]!r})")
    r, doc = estimate(jpart, "--machine", HAAS, config=by_name)
    check(doc and doc["machine"]["name"].startswith("Haas VF-0"), "--machine wins over the job's")
    write(job, 'machine = 3\n')
    r, doc = estimate(jpart)
    check(r.returncode == 2 and "machine" in r.stderr and "jpart.ncjoule.toml:1" in r.stderr,
          f"a job's machine that is no name is an error at its line ({r.stderr[-200:]!r})")
    r2, doc2 = estimate(part, "--machine", GENERIC, config=config)
    check(doc2 and doc2["machine"]["name"] == "Generic 3-axis VMC", "--machine wins over the config")

    # A job file next to the program: its tool and stock, over the config's.
    write(os.path.join(work, "part.ncjoule.toml"),
          'stock = "box:0,0,-5,100,20,0"\n[[tool]]\nnumber = 1\ntype = "flat"\ndiameter_mm = 12\n')
    r, doc = estimate(part, config=config)
    if doc:
        check(doc["unsimulated_tools"] == [], "PROGRAM.ncjoule.toml describes T1")
        check("-5.000" in doc["stock"], f"the job file's stock wins over the config's ({doc['stock']})")
        # The 12 mm cutter at Y10 sweeps Y 4..16 across the whole 100 mm of stock, 2 mm deep.
        check(abs(doc["removed_mm3"] - 100 * 12 * 2) < 0.03 * 2400,
              f"the job's tool removes 2400 mm^3 ({doc['removed_mm3']:.0f})")
    r, doc = estimate(part, "--stock", "box:0,0,-8,100,20,0", config=config)
    check(doc and "-8.000" in doc["stock"], "--stock wins over the job file")

    # PROGRAM.stock, when the job file gives no stock.
    write(os.path.join(work, "part.ncjoule.toml"),
          '[[tool]]\nnumber = 1\ntype = "flat"\ndiameter_mm = 12\n')
    write(os.path.join(work, "part.stock"), "box:0,0,-3,100,20,0\n")
    r, doc = estimate(part, config=config)
    check(doc and "-3.000" in doc["stock"], "PROGRAM.stock wins over the config's stock")
    r, doc = estimate(part, "--job", write(os.path.join(work, "other.toml"),
                                           'stock = "box:0,0,-4,100,20,0"\n'), config=config)
    check(doc and "-4.000" in doc["stock"] and doc["unsimulated_tools"] == [1],
          "--job replaces the program's job file")

    # compare: each program with its own files.
    other = write(os.path.join(work, "other-part.nc"), PROGRAM.replace("Z-2", "Z-1"))
    write(os.path.join(work, "other-part.stock"), "box:0,0,-3,100,20,0\n")
    r = run("compare", part, other, "--json", config=config)
    check(r.returncode == 0, f"compare with program files ({r.stderr[-200:]!r})")
    if r.returncode == 0:
        by = {os.path.basename(p["file"]): p for p in json.loads(r.stdout)["programs"]}
        check(by["part.nc"]["removed_mm3"] > 1000 and by["other-part.nc"]["removed_mm3"] == 0,
              "compare reads each program's own job file (only part.nc has one: its T1 cuts)")

    # A broken config: file, line and column, and nothing runs.
    bad = write(os.path.join(work, "bad.toml"), 'machine = "mill.toml"\ntool_units = "feet"\n')
    r = run("estimate", part, config=bad)
    check(r.returncode == 2 and "bad.toml:2:" in r.stderr and "tool_units" in r.stderr,
          f"a bad config is refused with its line ({r.stderr[-200:]!r})")
    # A bad stock in the config or in PROGRAM.stock: the file, line and column of the bad number.
    bad_stock = write(os.path.join(work, "bad-stock.toml"), '# shop\nstock = "box:0,0,a,1,1,1"\n')
    lone = write(os.path.join(work, "lone.nc"), PROGRAM)
    r = run("estimate", lone, config=bad_stock)
    check(r.returncode == 2 and "bad-stock.toml:2:18: error: stock box value 'a'" in r.stderr,
          f"a bad stock in the config is placed at its value ({r.stderr[-200:]!r})")
    write(os.path.join(work, "lone.stock"), "  box:0,0,0,1,1,x\n")
    r = run("estimate", lone, config=config)
    check(r.returncode == 2 and "lone.stock:1:17: error: stock box value 'x'" in r.stderr,
          f"a bad PROGRAM.stock is placed at its value ({r.stderr[-200:]!r})")
    r = run("estimate", lone, "--stock", "box:1,2", "--tool", "1:flat:6", config=config)
    check(r.returncode == 1 and "--stock 'box:1,2': error: stock box needs six numbers" in r.stderr,
          f"a bad --stock is named by the option ({r.stderr[-200:]!r})")
    unknown = write(os.path.join(work, "unknown.toml"), 'machin = "x.toml"\n')
    r = run("estimate", part, "--json", config=unknown)
    check(r.returncode == 0 and "machin: unknown key" in r.stderr, "an unknown key is a warning")

    # The shop's costs: price, machine-hour rate, currency and CO2 factor, over the profile's;
    # the command line's options over them.
    shop = write(os.path.join(work, "shop.toml"),
                 'machine = "generic-3axis"\nprice_per_kwh = 0.5\nmachine_rate_per_hour = 60\n'
                 'currency = "USD"\nco2_kg_per_kwh = 0.1\n')
    r, doc = estimate(lone, "--tool", "1:flat:6", "--stock", "box:0,0,-10,100,20,0", config=shop)
    kwh = doc["energy_j"] / 3.6e6 if doc else 0
    check(doc is not None and doc["currency"] == "USD"
          and abs(doc["electricity_cost"] - 0.5 * kwh) < 1e-9
          and abs(doc["machine_cost"] - 60 * doc["time_s"] / 3600) < 1e-9
          and abs(doc["co2_kg"] - 0.1 * kwh) < 1e-9,
          f"the config's price, rate, currency and CO2 factor are used ({doc and doc['cost']})")
    r, doc = estimate(lone, "--tool", "1:flat:6", "--stock", "box:0,0,-10,100,20,0",
                      "--price", "0.25", "--machine-rate", "0", config=shop)
    check(doc is not None and abs(doc["electricity_cost"] - 0.25 * doc["energy_j"] / 3.6e6) < 1e-9
          and doc["machine_cost"] == 0, "--price and --machine-rate win over the config's")
    bad_rate = write(os.path.join(work, "bad-rate.toml"), 'machine_rate_per_hour = -5\n')
    r = run("estimate", part, config=bad_rate)
    check(r.returncode == 2 and "bad-rate.toml:1:" in r.stderr and "machine_rate_per_hour" in r.stderr,
          f"a negative rate in the config is refused with its line ({r.stderr[-200:]!r})")

    # Settings where they belong (issue 42). A router profile that says mdf is not costed as
    # aluminium by the config's shop-wide material; a copied router profile with its own rate is
    # costed at its rate, not the config's; the config's section for a machine wins over the
    # profile; override_profiles puts the shop-wide values first; the command line wins over all.
    router = os.path.join(MACHINES, "router-2.2kw-vfd.toml")
    shop_wide = write(os.path.join(work, "shop-wide.toml"),
                      'material = "aluminium-alloy"\nmachine_rate_per_hour = 85\n')
    r, doc = estimate(lone, "-m", router, "--tool", "1:flat:6", "--stock", "box:0,0,-10,100,20,0",
                      config=shop_wide)
    check(doc is not None and doc["machine"]["material"] == "mdf",
          f"the router's own mdf wins over the config's aluminium ({doc and doc['machine']['material']})")
    check(doc is not None and abs(doc["machine_cost"] - 85 * doc["time_s"] / 3600) < 1e-9,
          "a profile without a rate takes the config's shop-wide one")
    copied = write(os.path.join(work, "my-router.toml"),
                   'base = "router-2.2kw-vfd"\nname = "Our router"\n[power]\nmachine_rate_per_hour = 30\n')
    r, doc = estimate(lone, "-m", copied, "--tool", "1:flat:6", "--stock", "box:0,0,-10,100,20,0",
                      config=shop_wide)
    check(doc is not None and doc["machine"]["name"] == "Our router"
          and abs(doc["machine_cost"] - 30 * doc["time_s"] / 3600) < 1e-9
          and doc["machine"]["material"] == "mdf",
          f"a router profile on a shipped base is costed at its own rate ({r.stderr[-300:]!r})")
    sections = write(os.path.join(work, "sections.toml"),
                     'material = "aluminium-alloy"\nmachine_rate_per_hour = 85\n'
                     '[machines."my-router"]\nmachine_rate_per_hour = 45\nmaterial = "softwood"\n'
                     '[machines."haas-vf2"]\nmachine_rate_per_hour = 95\n')
    r, doc = estimate(lone, "-m", copied, "--tool", "1:flat:6", "--stock", "box:0,0,-10,100,20,0",
                      config=sections)
    check(doc is not None and abs(doc["machine_cost"] - 45 * doc["time_s"] / 3600) < 1e-9
          and doc["machine"]["material"] == "softwood",
          "the config's section for the machine wins over the profile's own values")
    r, doc = estimate(lone, "-m", copied, "--tool", "1:flat:6", "--stock", "box:0,0,-10,100,20,0",
                      "--machine-rate", "12", "--material", "plastic", config=sections)
    check(doc is not None and abs(doc["machine_cost"] - 12 * doc["time_s"] / 3600) < 1e-9
          and doc["machine"]["material"] == "plastic", "the command line wins over the section")
    r, doc = estimate(lone, "-m", "haas-vf2", "--tool", "1:flat:6", "--stock", "box:0,0,-10,100,20,0",
                      config=sections)
    check(doc is not None and abs(doc["machine_cost"] - 95 * doc["time_s"] / 3600) < 1e-9,
          "a shipped profile's section by its name")
    overriding = write(os.path.join(work, "overriding.toml"),
                       'override_profiles = true\nmaterial = "aluminium-alloy"\nmachine_rate_per_hour = 85\n')
    r, doc = estimate(lone, "-m", copied, "--tool", "1:flat:6", "--stock", "box:0,0,-10,100,20,0",
                      config=overriding)
    check(doc is not None and doc["machine"]["material"] == "aluminium-alloy"
          and abs(doc["machine_cost"] - 85 * doc["time_s"] / 3600) < 1e-9,
          "override_profiles: the config's shop-wide values win over the profile's")
    # --show-settings: every setting with where it came from, and no estimate.
    r = run("estimate", lone, "-m", copied, "--show-settings", "--price", "0.3", config=sections)
    out = r.stdout
    check(r.returncode == 0, f"--show-settings runs ({r.stderr[-300:]!r})")
    check('[machines."my-router"]' in out and "machine_rate_per_hour" in out
          and "command line (--price)" in out and "command line (--machine)" in out,
          f"--show-settings names the section and the command line ({out[:600]!r})")
    check("base profile" in out and "router-2.2kw-vfd.toml" in out
          and "power.material" in out and "energy" not in out,
          "--show-settings names the base profile's values and estimates nothing")
    line = [l for l in out.splitlines() if l.strip().startswith("currency")]
    check(line and "base profile" in line[0], f"the currency is the base profile's ({line})")
    # A section that is not a table, and a machine key given as a table, are refused.
    bad_section = write(os.path.join(work, "bad-section.toml"), '[machine."haas-vf2"]\nmachine_rate_per_hour = 9\n')
    r = run("estimate", part, config=bad_section)
    check(r.returncode == 2 and "bad-section.toml:" in r.stderr and '[machines.' in r.stderr,
          f"[machine.NAME] points to [machines.NAME] ({r.stderr[-300:]!r})")

    # doctor and --version.
    r = run("--version")
    check(r.returncode == 0 and r.stdout.startswith("ncjoule 0."), f"--version ({r.stdout!r})")
    r = run("doctor", config=config)
    check(r.returncode == 0 and "ok    user config" in r.stdout and "Haas" in r.stdout
          and "ncjoule is ready" in r.stdout, f"doctor with a good config ({r.stdout[-300:]!r})")
    r = run("doctor", config=bad)
    check(r.returncode == 2 and "FAIL" in r.stdout, "doctor reports a bad config")
    broken_machine = write(os.path.join(work, "cfg", "broken.toml"), 'machine = "nope.toml"\n')
    r = run("doctor", config=broken_machine)
    check(r.returncode == 2 and "nope.toml does not load" in r.stdout, "doctor reports a missing profile")
finally:
    shutil.rmtree(work, ignore_errors=True)

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("all checks passed")
