// The Fusion 360 / Inventor CAM / HSM hook (postprocessor-templates/fusion360/ncjoule-hook.cps.js)
// run under node, appended to small vendor-style posts, with a stand-in for the post engine's
// global functions the hook calls (fusion_engine.js): execute() runs the real ncjoule through a
// shell or the MS C runtime's parse, getOutputPath(), getProperty(), warning(), log(),
// redirectToFile(), TextFile, FileSystem.*.
//
// Usage: NCJOULE=path/to/ncjoule NCJOULE_SOURCE_DIR=repo node fusion_hook_test.js
"use strict";
const assert = require("assert");
const childProcess = require("child_process");
const fs = require("fs");
const os = require("os");
const path = require("path");
const vm = require("vm");
const {makeEngine: makeEngineFor} = require("./fusion_engine");

const ROOT = process.env.NCJOULE_SOURCE_DIR || path.resolve(__dirname, "..", "..");
const NCJOULE = process.env.NCJOULE || "ncjoule";
const HOOK = fs.readFileSync(path.join(ROOT, "postprocessor-templates", "fusion360", "ncjoule-hook.cps.js"), "utf8");
const MACHINE = path.join(ROOT, "samples", "machines", "zhou2017-anziani2025.toml");
// Programs posted the way a Fusion post writes them, with their stock.
const PROGRAM_A = path.join(ROOT, "samples", "programs", "anziani-table2-2.ngc");
const PROGRAM_B = path.join(ROOT, "samples", "programs", "anziani-table2-9.ngc");
const STOCK = fs.readFileSync(path.join(ROOT, "samples", "programs", "anziani-table2-2.stock"), "utf8").trim();

// The engine stand-in, its redirectToFile() copying a real posted program into the file.
function makeEngine(outputPath, propertyOverrides, platform) {
  return makeEngineFor(outputPath, propertyOverrides, platform, PROGRAM_B);
}

function tempDir() {
  return fs.mkdtempSync(path.join(os.tmpdir(), "ncjoule-fusion-"));
}

function strip(file) {
  const r = childProcess.spawnSync(NCJOULE, ["strip", file], {encoding: "latin1"});
  assert.strictEqual(r.status, 0, "ncjoule strip failed: " + r.stderr);
  return r.stdout;
}

function annotated(text) {
  return /[(;]NCJ SEAL LINES=/i.test(text);
}

// A modern vendor post: property objects, its own onTerminate.
const MODERN_POST = `
description = "Stand-in vendor post";
extension = "ngc";
properties = {
  writeMachine: {title: "Write machine", type: "boolean", value: true, scope: "post"},
  ncjouleStock: {title: "vendor's own stock setting", type: "string", value: ${JSON.stringify(STOCK)}, scope: "post"}
};
groupDefinitions = {};
var vendorTerminated = false;
var vendorSawAnnotated = null;
function onOpen() {}
function onClose() {}
function onTerminate() {
  vendorTerminated = true;
  vendorSawAnnotated = /NCJ /.test(require_read(getOutputPath()));
}
`;

// An old-style vendor post: plain property values and propertyDefinitions, no onTerminate, and
// one subprogram written to a file of its own through redirectToFile().
const LEGACY_POST = `
extension = "ngc";
properties = {writeMachine: true};
propertyDefinitions = {writeMachine: {title: "Write machine", type: "boolean"}};
function onOpen() {}
function onClose() {
  redirectToFile(subprogramPath);
  closeRedirection();
  redirectToFile(setupSheetPath); // not a program: must be left alone
  closeRedirection();
}
`;

let failures = 0;
function test(name, body) {
  try {
    body();
    console.log("ok   " + name);
  } catch (e) {
    failures++;
    console.log("FAIL " + name + ": " + (e && e.stack || e));
  }
}

function withReader(source) {
  // the vendor post above reads files through this stand-in helper
  return "function require_read(p) { return readText(p); }\n" + source;
}

function modernPost(out, overrides, platform) {
  const engine = makeEngine(out, overrides, platform);
  engine.readText = (p) => fs.readFileSync(p, "latin1");
  const context = vm.createContext(engine);
  vm.runInContext(withReader(MODERN_POST) + "\n" + HOOK, context, {filename: "modern.cps"});
  context.onOpen();
  context.onClose();
  context.onTerminate();
  return context;
}

test("a real posted program is annotated in place, after the post's own onTerminate", () => {
  const dir = tempDir();
  const out = path.join(dir, "1002.ngc");
  fs.copyFileSync(PROGRAM_A, out);
  const original = fs.readFileSync(out, "latin1");
  const ctx = modernPost(out, {ncjoulePath: NCJOULE, ncjouleMachine: MACHINE});
  const text = fs.readFileSync(out, "latin1");
  assert.ok(annotated(text), "no annotations in the output:\n" + text.slice(0, 400));
  assert.notStrictEqual(text, original);
  assert.strictEqual(strip(out), original, "strip does not give the posted program back");
  assert.strictEqual(ctx.vendorTerminated, true, "the post's own onTerminate did not run");
  assert.strictEqual(ctx.vendorSawAnnotated, false, "the post's onTerminate ran after annotation");
  assert.deepStrictEqual(ctx.record.warnings, []);
  assert.strictEqual(ctx.record.executed.length, 1);
  const argv = ctx.record.executed[0][2];
  assert.deepStrictEqual(argv, ["annotate", "--machine=" + MACHINE, "--in-place", "--stock=" + STOCK, "--", out]);
});

test("without a stock property the setup's workpiece is the stock, with the program's unit", () => {
  const dir = tempDir();
  const out = path.join(dir, "1002.ngc");
  fs.copyFileSync(PROGRAM_A, out);
  const engine = makeEngine(out, {ncjoulePath: NCJOULE, ncjouleMachine: MACHINE, ncjouleStock: ""});
  engine.readText = (p) => fs.readFileSync(p, "latin1");
  // The post engine's workpiece: a box 4 x 3 x 1 in, Z0 on its top (unit is IN).
  engine.IN = 1;
  engine.MM = 0;
  engine.unit = 1;
  engine.getWorkpiece = () => ({lower: {x: -0.25, y: 0, z: -1}, upper: {x: 3.75, y: 3.0000001, z: 0}});
  const ctx = vm.createContext(engine);
  vm.runInContext(withReader(MODERN_POST) + "\n" + HOOK, ctx, {filename: "modern.cps"});
  ctx.onOpen();
  ctx.onClose();
  ctx.onTerminate();
  assert.deepStrictEqual(ctx.record.warnings, []);
  const argv = ctx.record.executed[0][2];
  assert.ok(argv.includes("--stock=box:-0.25in,0in,-1in,3.75in,3in,0in"), argv.join(" "));
  assert.ok(argv.includes("--stock-from=fusion360"), argv.join(" "));
  // The same workpiece in a metric post, and an empty workpiece (none set) gives no --stock.
  engine.unit = 0;
  ctx.record.executed.length = 0;
  fs.copyFileSync(PROGRAM_A, out);
  ctx.onTerminate();
  assert.ok(ctx.record.executed[0][2].includes("--stock=box:-0.25mm,0mm,-1mm,3.75mm,3mm,0mm"));
  engine.getWorkpiece = () => ({lower: {x: 0, y: 0, z: 0}, upper: {x: 0, y: 0, z: 0}});
  ctx.record.executed.length = 0;
  fs.copyFileSync(PROGRAM_A, out);
  ctx.onTerminate();
  assert.ok(!ctx.record.executed[0][2].some((a) => a.startsWith("--stock")));
});

// The engine's workpiece through the real ncjoule: the annotated header's stock is the
// workpiece, in the program's units, named as the hook's.
function postWithWorkpiece(out, inch, workpiece) {
  const engine = makeEngine(out, {ncjoulePath: NCJOULE, ncjouleMachine: MACHINE, ncjouleStock: ""});
  engine.readText = (p) => fs.readFileSync(p, "latin1");
  engine.IN = 1;
  engine.MM = 0;
  engine.unit = inch ? 1 : 0;
  engine.getWorkpiece = () => workpiece;
  const ctx = vm.createContext(engine);
  vm.runInContext(withReader(MODERN_POST) + "\n" + HOOK, ctx, {filename: "modern.cps"});
  ctx.onOpen();
  ctx.onClose();
  ctx.onTerminate();
  assert.deepStrictEqual(ctx.record.warnings, []);
  return fs.readFileSync(out, "latin1");
}

test("the workpiece reaches ncjoule as the stock, named hook-fusion360, in inch and mm programs", () => {
  const dir = tempDir();
  // An inch program (a Fusion-style header) and the workpiece 4 x 3 x 1 in around its cuts.
  const inch = path.join(dir, "1003.ngc");
  fs.writeFileSync(inch, "%\nO1003 (POCKET)\n(T1 D=0.25 CR=0. - FLAT END MILL)\nN10 G90 G94 G17\n" +
    "N15 G20\nN20 T1 M6\nN25 S10000 M3\nN30 G54\nN35 G0 X0.5 Y0.5\nN40 G43 Z0.2 H1\n" +
    "N45 G1 Z-0.1 F10.\nN50 X3. F40.\nN55 Y2.5\nN60 G0 Z0.2\nN65 M5\nN70 M30\n%\n");
  let text = postWithWorkpiece(inch, true, {lower: {x: -0.25, y: 0, z: -1}, upper: {x: 3.75, y: 3, z: 0}});
  assert.ok(annotated(text), text.slice(0, 400));
  let stock = text.split("\n").find((l) => /NCJ STOCK/.test(l)) || "";
  assert.ok(/BOX_IN=-0\.25(00)?,0(\.0+)?,-1(\.0+)?,3\.75(00)?,3(\.0+)?,0(\.0+)?\b/.test(stock), stock);
  assert.ok(/BOX_MM=-6\.35(0)?,/.test(stock), stock);
  assert.ok(/FROM=hook-fusion360/i.test(stock), stock);
  assert.ok(/GIVEN/.test(stock), stock);
  // A metric program and its workpiece in mm.
  const mm = path.join(dir, "1002.ngc");
  fs.copyFileSync(PROGRAM_A, mm);
  text = postWithWorkpiece(mm, false, {lower: {x: 0, y: 0, z: -20}, upper: {x: 200, y: 40, z: 0}});
  stock = text.split("\n").find((l) => /NCJ STOCK/.test(l)) || "";
  assert.ok(/BOX_MM=0(\.0+)?,0(\.0+)?,-20(\.0+)?,200(\.0+)?,40(\.0+)?,0(\.0+)?\b/.test(stock), stock);
  assert.ok(/FROM=hook-fusion360/i.test(stock), stock);
  // The same program with the stock typed in the hook's property: the user's own, not the hook's.
  fs.copyFileSync(PROGRAM_A, mm);
  modernPost(mm, {ncjoulePath: NCJOULE, ncjouleMachine: MACHINE});
  stock = fs.readFileSync(mm, "latin1").split("\n").find((l) => /NCJ STOCK/.test(l)) || "";
  assert.ok(/FROM=option/i.test(stock), stock);
});

test("the post's properties are kept and the hook's added beside them", () => {
  const dir = tempDir();
  const out = path.join(dir, "p.ngc");
  fs.copyFileSync(PROGRAM_A, out);
  const ctx = modernPost(out, {ncjouleEnable: false});
  assert.strictEqual(ctx.properties.writeMachine.value, true);
  assert.strictEqual(ctx.properties.ncjouleStock.value, STOCK, "the vendor's own ncjouleStock was replaced");
  assert.strictEqual(ctx.properties.ncjouleStock.title, "vendor's own stock setting");
  for (const name of ["ncjouleEnable", "ncjoulePath", "ncjouleMachine", "ncjouleArguments"]) {
    assert.ok(ctx.properties[name] && "value" in ctx.properties[name], "missing property " + name);
    assert.strictEqual(ctx.properties[name].group, "ncjoule");
  }
  assert.ok(ctx.groupDefinitions.ncjoule, "no ncjoule property group");
});

test("a missing ncjoule only warns; the post's file is untouched", () => {
  const dir = tempDir();
  const out = path.join(dir, "1002.ngc");
  fs.copyFileSync(PROGRAM_A, out);
  const original = fs.readFileSync(out, "latin1");
  const ctx = modernPost(out, {ncjoulePath: path.join(dir, "no-such-ncjoule"), ncjouleMachine: MACHINE});
  assert.strictEqual(fs.readFileSync(out, "latin1"), original);
  assert.strictEqual(ctx.record.warnings.length, 1, JSON.stringify(ctx.record.warnings));
  assert.ok(/not found/.test(ctx.record.warnings[0]), ctx.record.warnings[0]);
  assert.strictEqual(ctx.vendorTerminated, true);
});

test("ncjoule not on the PATH: execute() fails, the hook warns and the post goes on", () => {
  const dir = tempDir();
  const out = path.join(dir, "1002.ngc");
  fs.copyFileSync(PROGRAM_A, out);
  const original = fs.readFileSync(out, "latin1");
  const ctx = modernPost(out, {ncjoulePath: "ncjoule-not-installed-anywhere", ncjouleMachine: MACHINE});
  assert.strictEqual(fs.readFileSync(out, "latin1"), original);
  assert.strictEqual(ctx.record.warnings.length, 1);
  assert.ok(/could not run/.test(ctx.record.warnings[0]), ctx.record.warnings[0]);
});

test("ncjoule failing (a profile with errors) only warns, with the exit code's meaning", () => {
  const dir = tempDir();
  const out = path.join(dir, "1002.ngc");
  fs.copyFileSync(PROGRAM_A, out);
  const badProfile = path.join(dir, "bad.toml");
  fs.writeFileSync(badProfile, "this is = not [ a profile\n");
  const original = fs.readFileSync(out, "latin1");
  const ctx = modernPost(out, {ncjoulePath: NCJOULE, ncjouleMachine: badProfile});
  assert.strictEqual(fs.readFileSync(out, "latin1"), original);
  assert.strictEqual(ctx.record.warnings.length, 1);
  assert.ok(/exited with 2 \(bad input/.test(ctx.record.warnings[0]), ctx.record.warnings[0]);
});

test("no machine profile set: ncjoule takes the user config's machine", () => {
  const dir = tempDir();
  const out = path.join(dir, "1002.ngc");
  fs.copyFileSync(PROGRAM_A, out);
  // The user config (the file NCJOULE_CONFIG names) names a shipped profile; the hook passes no
  // --machine, so ncjoule takes it.
  const config = path.join(dir, "config.toml");
  fs.writeFileSync(config, 'machine = "haas-vf2"\n');
  const saved = process.env.NCJOULE_CONFIG;
  process.env.NCJOULE_CONFIG = config;
  let ctx;
  try {
    ctx = modernPost(out, {ncjoulePath: NCJOULE});
  } finally {
    if (saved === undefined) delete process.env.NCJOULE_CONFIG;
    else process.env.NCJOULE_CONFIG = saved;
  }
  assert.strictEqual(ctx.record.executed.length, 1);
  const argv = ctx.record.executed[0][2];
  assert.ok(!argv.some((a) => a.startsWith("--machine")), argv.join(" "));
  assert.strictEqual(ctx.record.warnings.length, 0, ctx.record.warnings.join("; "));
  const text = fs.readFileSync(out, "latin1");
  assert.ok(/\(NCJ SEAL /.test(text), "annotated");
  assert.ok(/NCJ MACHINE NAME=\S+ PROFILE=haas-vf2\.toml/i.test(text), "with the config's machine");
});

test("turned off: nothing runs and the file is untouched", () => {
  const dir = tempDir();
  const out = path.join(dir, "1002.ngc");
  fs.copyFileSync(PROGRAM_A, out);
  const original = fs.readFileSync(out, "latin1");
  const ctx = modernPost(out, {ncjouleEnable: false, ncjoulePath: NCJOULE, ncjouleMachine: MACHINE});
  assert.strictEqual(ctx.record.executed.length, 0);
  assert.deepStrictEqual(ctx.record.warnings, []);
  assert.strictEqual(fs.readFileSync(out, "latin1"), original);
  assert.strictEqual(ctx.vendorTerminated, true, "the post's own onTerminate must still run");
});

test("a post writing two programs (main + subprogram via redirectToFile) gets both annotated", () => {
  const dir = tempDir();
  const out = path.join(dir, "1002.ngc");
  fs.copyFileSync(PROGRAM_A, out);
  const sub = path.join(dir, "1003.ngc");
  const sheet = path.join(dir, "1002-setup.txt");
  const mainOriginal = fs.readFileSync(out, "latin1");
  const engine = makeEngine(out, {ncjoulePath: NCJOULE, ncjouleMachine: MACHINE, ncjouleStock: STOCK});
  const context = vm.createContext(engine);
  context.subprogramPath = sub;
  context.setupSheetPath = sheet;
  vm.runInContext(LEGACY_POST + "\n" + HOOK, context, {filename: "legacy.cps"});
  // old-style properties: plain values, definitions beside them
  assert.strictEqual(context.properties.writeMachine, true);
  assert.strictEqual(context.properties.ncjouleEnable, true);
  assert.strictEqual(context.propertyDefinitions.ncjouleMachine.type, "string");
  context.onOpen();
  context.onClose();
  context.onTerminate();
  assert.deepStrictEqual(engine.record.warnings, []);
  const mainText = fs.readFileSync(out, "latin1");
  const subText = fs.readFileSync(sub, "latin1");
  assert.ok(annotated(mainText), "main program not annotated");
  assert.ok(annotated(subText), "subprogram not annotated");
  assert.strictEqual(strip(out), mainOriginal);
  assert.strictEqual(strip(sub), fs.readFileSync(PROGRAM_B, "latin1"));
  // the setup sheet (.txt) is not a program and is not handed to ncjoule
  const annotatedFiles = engine.record.executed.map((e) => e[2].slice(-1)[0]);
  assert.deepStrictEqual(annotatedFiles, [out, sub], "annotated: " + annotatedFiles.join(", "));
});

test("a relative machine profile is found next to the post", () => {
  const dir = tempDir();
  const out = path.join(dir, "1002.ngc");
  fs.copyFileSync(PROGRAM_A, out);
  fs.copyFileSync(MACHINE, path.join(dir, "mill.toml"));
  const ctx = modernPost(out, {ncjoulePath: NCJOULE, ncjouleMachine: "mill.toml"});
  assert.deepStrictEqual(ctx.record.warnings, []);
  assert.ok(annotated(fs.readFileSync(out, "latin1")));
  assert.ok(ctx.record.executed[0][2].includes("--machine=" + path.join(dir, "mill.toml")));
});

// File names a post writes that the command line must carry as they are (part"v2.nc was passed
// as partv2.nc, and another file was rewritten).
const ODD_NAMES = ['part"v2.nc', "two words.nc", "it's.nc", "$HOME.nc", "$(touch PWNED).nc", "`touch PWNED`.nc",
                   "100%.nc", "%PATH%.nc", "a&b.nc", "a;b|c.nc", "back\\slash.nc", "trailing\\.nc", "Grüße 漢字.nc",
                   "!bang.nc", "-x.nc", "*.nc"];

for (const platform of ["LINUX", "WIN64"]) {
  test(platform + ": names with quotes, blanks, $, %, &, backslashes and unicode are passed as they are", () => {
    const dir = tempDir();
    const bystander = path.join(dir, "partv2.nc"); // what the quote-dropping hook rewrote
    fs.copyFileSync(PROGRAM_B, bystander);
    const bystanderText = fs.readFileSync(bystander, "latin1");
    for (const name of ODD_NAMES) {
      const out = path.join(dir, name);
      fs.copyFileSync(PROGRAM_A, out);
      const original = fs.readFileSync(out, "latin1");
      const ctx = modernPost(out, {ncjoulePath: NCJOULE, ncjouleMachine: MACHINE}, platform);
      assert.deepStrictEqual(ctx.record.warnings, [], name);
      assert.deepStrictEqual(ctx.record.executed[0][2].slice(-2), ["--", out], name);
      assert.ok(annotated(fs.readFileSync(out, "latin1")), name + " not annotated");
      assert.strictEqual(strip(out), original, name);
    }
    assert.strictEqual(fs.readFileSync(bystander, "latin1"), bystanderText, "another file was rewritten");
    assert.ok(!fs.existsSync(path.join(dir, "PWNED")), "a name ran a command");
  });
}

test("a name with a newline is refused: a warning, nothing run, the file untouched", () => {
  for (const platform of ["LINUX", "WIN64"]) {
    const dir = tempDir();
    const out = path.join(dir, "new\nline.nc");
    fs.copyFileSync(PROGRAM_A, out);
    const original = fs.readFileSync(out, "latin1");
    const ctx = modernPost(out, {ncjoulePath: NCJOULE, ncjouleMachine: MACHINE}, platform);
    assert.strictEqual(ctx.record.executed.length, 0, platform);
    assert.strictEqual(ctx.record.warnings.length, 1, platform);
    assert.ok(/not annotated: .*control character/.test(ctx.record.warnings[0]), ctx.record.warnings[0]);
    assert.strictEqual(fs.readFileSync(out, "latin1"), original);
  }
});

test("Windows, ncjoule run through a .cmd: names with \", % or ! are refused, others pass", () => {
  const dir = tempDir();
  const wrapper = path.join(dir, "ncjoule.cmd"); // stands for cmd.exe: a script that runs ncjoule
  fs.writeFileSync(wrapper, "#!/bin/sh\nexec " + JSON.stringify(NCJOULE) + ' "$@"\n', {mode: 0o755});
  for (const name of ['part"v2.nc', "100%.nc", "!bang.nc"]) {
    const out = path.join(dir, name);
    fs.copyFileSync(PROGRAM_A, out);
    const ctx = modernPost(out, {ncjoulePath: wrapper, ncjouleMachine: MACHINE}, "WIN64");
    assert.strictEqual(ctx.record.executed.length, 0, name);
    assert.ok(/cmd\.exe/.test(ctx.record.warnings[0]), ctx.record.warnings[0]);
    assert.ok(!annotated(fs.readFileSync(out, "latin1")), name);
  }
  const out = path.join(dir, "a&b (1).nc");
  fs.copyFileSync(PROGRAM_A, out);
  const ctx = modernPost(out, {ncjoulePath: wrapper, ncjouleMachine: MACHINE}, "WIN64");
  assert.deepStrictEqual(ctx.record.warnings, []);
  assert.ok(annotated(fs.readFileSync(out, "latin1")));
});

test("ncjouleArguments is split at blanks and never evaluated", () => {
  const dir = tempDir();
  const out = path.join(dir, "1002.ngc");
  fs.copyFileSync(PROGRAM_A, out);
  const original = fs.readFileSync(out, "latin1");
  for (const extra of ["--no-removal; touch PWNED", "--no-removal $(touch PWNED)", "`touch PWNED`", "&& touch PWNED"]) {
    const ctx = modernPost(out, {ncjoulePath: NCJOULE, ncjouleMachine: MACHINE, ncjouleArguments: extra});
    assert.ok(!fs.existsSync(path.join(dir, "PWNED")), extra + " ran a command");
    // the stray words reach ncjoule as words, which it refuses: the file stays as it was
    assert.deepStrictEqual(ctx.record.executed[0][2].slice(-2), ["--", out]);
    assert.ok(/exited with 1/.test(ctx.record.warnings[0]), ctx.record.warnings[0]);
    assert.strictEqual(fs.readFileSync(out, "latin1"), original);
  }
  const ctx = modernPost(out, {ncjoulePath: NCJOULE, ncjouleMachine: MACHINE, ncjouleArguments: " --no-removal\t--compact -- --follow-symlinks "});
  assert.deepStrictEqual(ctx.record.executed[0][2].slice(3), ["--stock=" + STOCK, "--no-removal", "--compact", "--", out]);
  assert.ok(annotated(fs.readFileSync(out, "latin1")));
});

test("what ncjoule did is read from its exit status and whether the file changed", () => {
  const dir = tempDir();
  const out = path.join(dir, "1002.ngc");
  fs.copyFileSync(PROGRAM_A, out);
  let ctx = modernPost(out, {ncjoulePath: NCJOULE, ncjouleMachine: MACHINE});
  assert.ok(ctx.record.logs.some((m) => m === "ncjoule: annotated " + out), ctx.record.logs.join("\n"));
  // again: ncjoule writes nothing (new CLI), and the log says so
  const once = fs.readFileSync(out, "latin1");
  ctx = modernPost(out, {ncjoulePath: NCJOULE, ncjouleMachine: MACHINE});
  assert.strictEqual(fs.readFileSync(out, "latin1"), once);
  assert.ok(ctx.record.logs.some((m) => /unchanged: already annotated this way/.test(m)), ctx.record.logs.join("\n"));
  // a program with an error a controller refuses: exit 2, annotated all the same
  const bad = path.join(dir, "bad.ngc");
  fs.writeFileSync(bad, "(T1 D=6. CR=0. - ZMIN=-5. - FLAT END MILL)\nT1 M6\nG1 X10 F\nM30\n");
  ctx = modernPost(bad, {ncjoulePath: NCJOULE, ncjouleMachine: MACHINE, ncjouleStock: ""});
  assert.ok(/was annotated; it has errors/.test(ctx.record.warnings[0]), ctx.record.warnings.join("\n"));
  // a comment that looks like ncjoule's header does not make a failure look like success
  const fake = path.join(dir, "fake.ngc");
  fs.writeFileSync(fake, "(NCJ TOTAL T=1s CK=ABC123)\n" + fs.readFileSync(PROGRAM_A, "latin1"));
  const badProfile = path.join(dir, "bad.toml");
  fs.writeFileSync(badProfile, "this is = not [ a profile\n");
  ctx = modernPost(fake, {ncjoulePath: NCJOULE, ncjouleMachine: badProfile});
  assert.ok(/exited with 2 \(bad input/.test(ctx.record.warnings[0]), ctx.record.warnings.join("\n"));
});

test("an output that is a symbolic link is not followed (new CLI: exit 3)", () => {
  const dir = tempDir();
  const target = path.join(dir, "elsewhere.ngc");
  fs.copyFileSync(PROGRAM_A, target);
  const original = fs.readFileSync(target, "latin1");
  const out = path.join(dir, "1002.ngc");
  fs.symlinkSync(target, out);
  const ctx = modernPost(out, {ncjoulePath: NCJOULE, ncjouleMachine: MACHINE});
  assert.strictEqual(fs.readFileSync(target, "latin1"), original);
  assert.ok(fs.lstatSync(out).isSymbolicLink());
  assert.ok(/exited with 3/.test(ctx.record.warnings[0]), ctx.record.warnings.join("\n"));
});

if (failures) {
  console.log(failures + " failure(s)");
  process.exit(1);
}
console.log("all Fusion hook tests passed");
