// The Fusion 360 / Inventor CAM / HSM hook (postprocessor-templates/fusion360/ncjoule-hook.cps.js)
// run under node, appended to small vendor-style posts, with a stand-in for the post engine's
// global functions the hook calls: execute() runs the real ncjoule, getOutputPath(),
// getProperty(), warning(), log(), redirectToFile(), FileSystem.*.
//
// Usage: NCJOULE=path/to/ncjoule NCJOULE_SOURCE_DIR=repo node fusion_hook_test.js
"use strict";
const assert = require("assert");
const childProcess = require("child_process");
const fs = require("fs");
const os = require("os");
const path = require("path");
const vm = require("vm");

const ROOT = process.env.NCJOULE_SOURCE_DIR || path.resolve(__dirname, "..", "..");
const NCJOULE = process.env.NCJOULE || "ncjoule";
const HOOK = fs.readFileSync(path.join(ROOT, "postprocessor-templates", "fusion360", "ncjoule-hook.cps.js"), "utf8");
const MACHINE = path.join(ROOT, "samples", "machines", "zhou2017-anziani2025.toml");
// Programs posted the way a Fusion post writes them, with their stock.
const PROGRAM_A = path.join(ROOT, "samples", "programs", "anziani-table2-2.ngc");
const PROGRAM_B = path.join(ROOT, "samples", "programs", "anziani-table2-9.ngc");
const STOCK = fs.readFileSync(path.join(ROOT, "samples", "programs", "anziani-table2-2.stock"), "utf8").trim();

// Splits execute()'s argument string the way a command line does (double quotes group).
function splitArguments(text) {
  const out = [];
  const re = /"([^"]*)"|(\S+)/g;
  let m;
  while ((m = re.exec(text)) !== null) out.push(m[1] !== undefined ? m[1] : m[2]);
  return out;
}

// A post engine: the globals a post (and the hook) sees, recording what happened.
function makeEngine(outputPath, propertyOverrides) {
  const record = {warnings: [], logs: [], executed: [], events: []};
  const engine = {
    record,
    console,
    extension: "ngc",
    getOutputPath: () => outputPath,
    getConfigurationFolder: () => path.dirname(outputPath),
    getProperty(name) {
      if (propertyOverrides && name in propertyOverrides) return propertyOverrides[name];
      const p = engine.properties[name];
      if (p === undefined) return undefined;
      return p !== null && typeof p === "object" && "value" in p ? p.value : p;
    },
    warning: (m) => record.warnings.push(m),
    log: (m) => record.logs.push(m),
    execute(program, args, hide, folder) {
      record.executed.push([program, args]);
      const r = childProcess.spawnSync(program, splitArguments(args), {cwd: folder || undefined, encoding: "utf8"});
      if (r.error) throw new Error("cannot run " + program + ": " + r.error.code);
      return r.status;
    },
    // Output redirection: the stand-in copies a real posted program into the file.
    redirectToFile(p) {
      record.events.push("redirect " + p);
      fs.copyFileSync(PROGRAM_B, p);
    },
    closeRedirection() {},
    FileSystem: {
      isFile: (p) => fs.existsSync(p) && fs.statSync(p).isFile(),
      getFolderPath: (p) => path.dirname(p),
      getFilename: (p) => path.basename(p),
      getCombinedPath: (a, b) => path.join(a, b),
    },
  };
  return engine;
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
  return /[(;]NCJ [^\n]* CK=/i.test(text);
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

function modernPost(out, overrides) {
  const engine = makeEngine(out, overrides);
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
  const args = ctx.record.executed[0][1];
  assert.ok(args.includes("--in-place") && args.includes("--machine") && args.includes("--stock \"" + STOCK + "\""), args);
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

test("no machine profile set: a warning, nothing run", () => {
  const dir = tempDir();
  const out = path.join(dir, "1002.ngc");
  fs.copyFileSync(PROGRAM_A, out);
  const ctx = modernPost(out, {ncjoulePath: NCJOULE});
  assert.strictEqual(ctx.record.executed.length, 0);
  assert.ok(/no machine profile/.test(ctx.record.warnings[0]));
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
  const annotatedFiles = engine.record.executed.map((e) => splitArguments(e[1]).slice(-1)[0]);
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
  assert.ok(ctx.record.executed[0][1].includes(path.join(dir, "mill.toml")));
});

if (failures) {
  console.log(failures + " failure(s)");
  process.exit(1);
}
console.log("all Fusion hook tests passed");
