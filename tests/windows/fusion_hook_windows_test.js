// The Fusion 360 hook (postprocessor-templates/fusion360/ncjoule-hook.cps.js) as it runs on
// Windows: the post engine stand-in (tests/hooks/fusion_engine.js) on the WIN64 platform, with
// Windows paths everywhere (Z:\... is Wine's drive of the Linux root), execute() starting the
// real ncjoule.exe under Wine with the arguments as the MS C runtime splits the hook's line.
// - ncjoule.exe is found by the property (a full path), on the PATH, in
//   %LOCALAPPDATA%\Programs\ncjoule\bin and in %ProgramFiles%\ncjoule\bin;
// - paths with spaces, non-ASCII letters, & and parentheses reach ncjoule as one argument each;
// - nothing fails the post: ncjoule not found, a property naming a missing program, a profile
//   that does not load give a warning and leave the program as the post wrote it.
// Environment: as tests/windows/wine_common.py (NCJOULE_EXE, NCJOULE_LINUX, NCJOULE_SOURCE_DIR,
// NCJOULE_WIN_WORK).
"use strict";
const assert = require("assert");
const childProcess = require("child_process");
const fs = require("fs");
const path = require("path");
const vm = require("vm");

const ROOT = process.env.NCJOULE_SOURCE_DIR;
const {makeEngine, splitWindows} = require(path.join(ROOT, "tests", "hooks", "fusion_engine.js"));
const EXE = process.env.NCJOULE_EXE;
const LINUX = process.env.NCJOULE_LINUX;
const WORK = path.join(process.env.NCJOULE_WIN_WORK, "fusion hook");
const HOOK = fs.readFileSync(path.join(ROOT, "postprocessor-templates", "fusion360", "ncjoule-hook.cps.js"), "utf8");
const MACHINE = path.join(ROOT, "samples", "machines", "zhou2017-anziani2025.toml");
const PROGRAM = path.join(ROOT, "samples", "programs", "anziani-table2-2.ngc");
const STOCK = fs.readFileSync(path.join(ROOT, "samples", "programs", "anziani-table2-2.stock"), "utf8").trim();
const INSTALL_BIN = path.dirname(EXE);

// Windows path of a Linux path, and back (Z: is the Linux root).
const win = (p) => "Z:" + path.resolve(p).split("/").join("\\");
function unix(p) {
  const m = /^([A-Za-z]):[\\\/](.*)$/.exec(p);
  if (!m) return p.split("\\").join("/");
  if (m[1].toUpperCase() !== "Z") throw new Error("not on Wine's Z: drive: " + p);
  return "/" + m[2].split("\\").join("/");
}

const POST = `
description = "Stand-in vendor post";
extension = "nc";
properties = {writeMachine: {title: "Write machine", type: "boolean", value: true, scope: "post"}};
function onOpen() {}
function onClose() {}
`;

// A WIN64 engine whose file functions take Windows paths, execute() runs Windows programs under
// Wine (a program that is not a file cannot start: it throws, as the engine's does), and
// getEnvironmentVariable() gives `environment`.
function windowsEngine(outputWin, properties, environment, configurationFolderWin) {
  const engine = makeEngine(outputWin, properties, "WIN64", PROGRAM);
  engine.FileSystem = {
    isFile: (p) => { try { return fs.statSync(unix(p)).isFile(); } catch (e) { return false; } },
    getFolderPath: (p) => path.win32.dirname(p),
    getFilename: (p) => path.win32.basename(p),
    getCombinedPath: (a, b) => path.win32.join(a, b),
  };
  const StandIn = engine.TextFile;
  engine.TextFile = function (p, write) { return new StandIn(unix(p), write); };
  engine.getConfigurationFolder = () => configurationFolderWin || path.win32.dirname(outputWin);
  if (environment) engine.getEnvironmentVariable = (name) => environment[name] || "";
  engine.execute = (program, args, hide, folder) => {
    const argv = splitWindows(args);
    engine.record.executed.push([program, args, argv]);
    if (!engine.FileSystem.isFile(program)) throw new Error("cannot run " + program + ": not found");
    const r = childProcess.spawnSync("wine", [program, ...argv],
                                     {cwd: folder ? unix(folder) : undefined, encoding: "utf8",
                                      env: Object.assign({}, process.env, {WINEDEBUG: "-all"})});
    if (r.error) throw r.error;
    return r.status;
  };
  return engine;
}

function post(outputWin, properties, environment, configurationFolderWin) {
  const engine = windowsEngine(outputWin, properties, environment, configurationFolderWin);
  const context = vm.createContext(engine);
  vm.runInContext(POST + "\n" + HOOK, context, {filename: "windows.cps"});
  context.onOpen();
  context.onClose();
  context.onTerminate(); // throws if the hook ever lets an error out
  return context;
}

function posted(name) {
  const dir = path.join(WORK, "Posts été", String(++posted.count));
  fs.mkdirSync(dir, {recursive: true});
  const out = path.join(dir, name);
  fs.copyFileSync(PROGRAM, out);
  return out;
}
posted.count = 0;

const original = fs.readFileSync(PROGRAM, "latin1");
const annotated = (p) => /[(;]NCJ SEAL LINES=/.test(fs.readFileSync(p, "latin1"));
function strip(p) {
  const r = childProcess.spawnSync(LINUX, ["strip", p], {encoding: "latin1"});
  assert.strictEqual(r.status, 0, r.stderr);
  return r.stdout;
}

// Install folders the hook looks in, each a link to the unpacked zip's folder.
function installedAt(folder) {
  fs.mkdirSync(path.dirname(folder), {recursive: true});
  if (!fs.existsSync(folder)) fs.symlinkSync(path.dirname(INSTALL_BIN), folder);
  return path.join(folder, "bin", "ncjoule.exe");
}

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

fs.rmSync(WORK, {recursive: true, force: true});

test("ncjoulePath names ncjoule.exe by its Windows path; a name with blanks, é, &, ( ) is one argument", () => {
  const out = posted("1001 pièce & co (v2).nc");
  const ctx = post(win(out), {ncjoulePath: win(EXE), ncjouleMachine: win(MACHINE), ncjouleStock: STOCK});
  assert.deepStrictEqual(ctx.record.warnings, []);
  assert.ok(annotated(out), "not annotated");
  assert.strictEqual(strip(out), original);
  const [program, , argv] = ctx.record.executed[0];
  assert.strictEqual(program, win(EXE));
  assert.deepStrictEqual(argv, ["annotate", "--machine=" + win(MACHINE), "--in-place",
                                "--stock=" + STOCK, "--", win(out)]);
});

test("the default 'ncjoule' is found as ncjoule.exe on the PATH", () => {
  const out = posted("1002.nc");
  const ctx = post(win(out), {ncjouleMachine: win(MACHINE), ncjouleStock: STOCK},
                   {PATH: "C:\\windows\\system32;\"" + win(INSTALL_BIN) + "\\\";C:\\windows"});
  assert.deepStrictEqual(ctx.record.warnings, []);
  assert.strictEqual(ctx.record.executed[0][0], win(INSTALL_BIN) + "\\ncjoule.exe");
  assert.ok(annotated(out));
});

test("... else in %LOCALAPPDATA%\\Programs\\ncjoule\\bin", () => {
  const local = path.join(WORK, "Local AppData é");
  const exe = installedAt(path.join(local, "Programs", "ncjoule"));
  const out = posted("1003.nc");
  const ctx = post(win(out), {ncjouleMachine: win(MACHINE), ncjouleStock: STOCK},
                   {PATH: "C:\\windows\\system32", LOCALAPPDATA: win(local)});
  assert.deepStrictEqual(ctx.record.warnings, []);
  assert.strictEqual(ctx.record.executed[0][0], win(exe));
  assert.ok(annotated(out));
});

test("... else in %ProgramFiles%\\ncjoule\\bin", () => {
  const programFiles = path.join(WORK, "Program Files");
  const exe = installedAt(path.join(programFiles, "ncjoule"));
  const out = posted("1004.nc");
  const ctx = post(win(out), {ncjouleMachine: win(MACHINE), ncjouleStock: STOCK},
                   {PATH: "", LOCALAPPDATA: win(path.join(WORK, "empty")), ProgramFiles: win(programFiles)});
  assert.deepStrictEqual(ctx.record.warnings, []);
  assert.strictEqual(ctx.record.executed[0][0], win(exe));
  assert.ok(annotated(out));
});

test("a profile named without a folder is taken next to the post", () => {
  const posts = path.join(WORK, "My Posts");
  fs.mkdirSync(posts, {recursive: true});
  fs.copyFileSync(MACHINE, path.join(posts, "mill é.toml"));
  const out = posted("1005.nc");
  const ctx = post(win(out), {ncjoulePath: win(EXE), ncjouleMachine: "mill é.toml", ncjouleStock: STOCK},
                   undefined, win(posts));
  assert.deepStrictEqual(ctx.record.warnings, []);
  assert.strictEqual(ctx.record.executed[0][2][1], "--machine=" + win(path.join(posts, "mill é.toml")));
  assert.ok(annotated(out));
});

test("ncjoule found nowhere: a warning, the post goes on, the file is as posted", () => {
  const out = posted("1006.nc");
  const ctx = post(win(out), {ncjouleMachine: win(MACHINE)},
                   {PATH: "C:\\windows", LOCALAPPDATA: win(path.join(WORK, "empty")), ProgramFiles: win(path.join(WORK, "empty"))});
  assert.strictEqual(ctx.record.warnings.length, 1, JSON.stringify(ctx.record.warnings));
  assert.match(ctx.record.warnings[0], /could not run 'ncjoule'/);
  assert.strictEqual(fs.readFileSync(out, "latin1"), original);
});

test("ncjoulePath naming a missing ncjoule.exe: a warning, the file is as posted", () => {
  const out = posted("1007.nc");
  const ctx = post(win(out), {ncjoulePath: "C:\\Program Files\\nowhere\\ncjoule.exe", ncjouleMachine: win(MACHINE)});
  assert.strictEqual(ctx.record.executed.length, 0);
  assert.match(ctx.record.warnings.join("\n"), /ncjoule not found at/);
  assert.strictEqual(fs.readFileSync(out, "latin1"), original);
});

test("a profile that does not load: ncjoule's exit 2 is a warning, the file is as posted", () => {
  const out = posted("1008.nc");
  const ctx = post(win(out), {ncjoulePath: win(EXE), ncjouleMachine: win(PROGRAM)});
  assert.match(ctx.record.warnings.join("\n"), /exited with 2/);
  assert.strictEqual(fs.readFileSync(out, "latin1"), original);
});

console.log(failures ? failures + " test(s) failed" : "fusion_hook_windows: all passed");
process.exit(failures ? 1 : 0);
