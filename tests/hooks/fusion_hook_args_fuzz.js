// Randomized property test of the Fusion hook's command line
// (postprocessor-templates/fusion360/ncjoule-hook.cps.js), the sibling of hook_args_fuzz.py.
//
// Each run posts a file with a hostile name (shell and cmd.exe metacharacters, quotes, blanks,
// newlines, a leading '-', unicode, long names) with hostile property values (profile, stock,
// extra arguments), on macOS/Linux (execute() through a shell) or Windows (the MS C runtime's
// parse; now and then through a .cmd, as cmd.exe would run it). The ncjoule it runs is a stub
// that records its arguments as JSON. Properties:
//   - either ncjoule gets exactly ["annotate", "--machine=P", "--in-place", "--stock=S", EXTRA...,
//     "--", FILE], every value one argument, the extra arguments split at blanks less "--" and
//     --follow-symlinks, or the hook refuses (a warning, nothing run) and only when an argument
//     holds a control character, or ", % or ! through cmd.exe;
//   - no command in a name or a value runs, and no other file changes (the same name without
//     its quotes, beside it, above all).
//
// Usage: NCJOULE_SOURCE_DIR=repo node fusion_hook_args_fuzz.js [--runs N] [--seed S]
"use strict";
const fs = require("fs");
const os = require("os");
const path = require("path");
const vm = require("vm");
const {makeEngine} = require("./fusion_engine");

const ROOT = process.env.NCJOULE_SOURCE_DIR || path.resolve(__dirname, "..", "..");
const HOOK = fs.readFileSync(path.join(ROOT, "postprocessor-templates", "fusion360", "ncjoule-hook.cps.js"), "utf8");

const PAYLOADS = ["$(touch PWNED)", "`touch PWNED`", "; touch PWNED", "| touch PWNED", "& touch PWNED",
                  "' ; touch PWNED ; '", "\" & touch PWNED & \"", "\\\" & touch PWNED & \\\"", "$HOME", "%PATH%",
                  "!PATH!", "^", "*", "?", "~", "\\", "\\\\\"", "\"\"", "''"];
// Characters no command line carries safely: rarer, so that most runs get as far as ncjoule.
const CONTROLS = ["\n", "\r", "\t", "\x1b[31m", "\x7f"];
const PIECES = ["a", "part", "v2", " ", "'", "\"", "-", "--", "=", ",", ":", "$", "%", "&", "!", "(", ")",
                "é", "漢字", "Ω", "🙂", "\u00a0", "\u202e", "e\u0301"];
const LEADS = ["-", "--", "-x", "--stock=", "-h"];

// mulberry32: a small seeded generator, so that a failing run can be replayed.
function generator(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

function pick(random, list) {
  return list[Math.floor(random() * list.length)];
}

function hostileText(random, most) {
  let out = "";
  const count = 1 + Math.floor(random() * most);
  for (let i = 0; i < count; ++i) out += pick(random, random() < 0.04 ? CONTROLS : PAYLOADS.concat(PIECES));
  return out;
}

function hostileName(random, ext) {
  let stem = hostileText(random, 6).replace(/\//g, "_");
  if (random() < 0.4) stem = pick(random, LEADS) + stem;
  if (random() < 0.1) stem += "x".repeat(100 + Math.floor(random() * 100));
  while (Buffer.byteLength(stem + "." + ext) > 250) stem = stem.slice(0, -1);
  if (stem.startsWith(".")) stem = "_" + stem;
  return stem + "." + ext;
}

function hostileWords(random) {
  let out = "";
  const count = Math.floor(random() * 6);
  for (let i = 0; i < count; ++i) {
    out += pick(random, PAYLOADS.concat(PIECES, ["--", "--follow-symlinks", "--follow-symlinks=true", "--compact"]));
    out += pick(random, [" ", "\t", "\n", "\r\n", "  "]);
  }
  return out;
}

// What the hook must pass: the extra arguments split at spaces, tabs, CRs and newlines only.
function expectedWords(machine, stock, extra, file) {
  const words = ["annotate", "--machine=" + machine, "--in-place"];
  if (stock) words.push("--stock=" + stock);
  for (const w of extra.split(/[ \t\r\n]+/)) {
    if (w && w !== "--" && w !== "--follow-symlinks" && !w.startsWith("--follow-symlinks=")) words.push(w);
  }
  return words.concat(["--", file]);
}

function refused(words, throughCmd) {
  return words.some((w) => /[\x00-\x1f\x7f]/.test(w) || (throughCmd && /["%!]/.test(w)));
}

// Every file under a folder with its bytes, so that a change anywhere shows.
function snapshot(top, skip) {
  const out = {};
  for (const name of fs.readdirSync(top)) {
    const p = path.join(top, name);
    if (p === skip) continue;
    const st = fs.lstatSync(p);
    if (st.isDirectory()) Object.assign(out, snapshot(p, skip));
    else out[p] = st.isSymbolicLink() ? "->" + fs.readlinkSync(p) : fs.readFileSync(p, "latin1");
  }
  return out;
}

function stub(folder) {
  const file = path.join(folder, "ncjoule-stub");
  fs.writeFileSync(file, "#!" + process.execPath + "\n" +
    "const args = process.argv.slice(2);\n" +
    "require('fs').appendFileSync(process.env.STUB_LOG, JSON.stringify(args) + '\\n');\n" +
    "process.stderr.write('ncjoule: annotated ' + args[args.length - 1] + '\\n');\n", {mode: 0o755});
  fs.copyFileSync(file, file + ".cmd"); // stands for a .cmd that cmd.exe would run
  fs.chmodSync(file + ".cmd", 0o755);
  return file;
}

function oneRun(random, work, program) {
  const folder = path.join(work, random() < 0.5 ? hostileName(random, "d") : "out");
  const logs = path.join(work, "logs");
  fs.mkdirSync(folder);
  fs.mkdirSync(logs);
  const out = path.join(folder, hostileName(random, "nc"));
  fs.writeFileSync(out, "G0 X0\nG1 X1 F100\nM30\n");
  const bystander = path.join(folder, path.basename(out).replace(/["'\\]/g, ""));
  if (bystander !== out) fs.writeFileSync(bystander, "the other file\n");
  const machine = path.join(folder, hostileName(random, "toml"));
  if (machine !== out && machine !== bystander) fs.writeFileSync(machine, "profile\n");
  const stock = random() < 0.7 ? hostileText(random, 4) : "";
  const extra = hostileWords(random);
  const platform = random() < 0.5 ? "LINUX" : "WIN64";
  const throughCmd = platform === "WIN64" && random() < 0.3;
  const exe = throughCmd ? program + ".cmd" : program;

  const before = snapshot(work, logs);
  process.env.STUB_LOG = path.join(logs, "calls.jsonl");
  const engine = makeEngine(out, {ncjoulePath: exe, ncjouleMachine: machine, ncjouleStock: stock,
                                  ncjouleArguments: extra}, platform, out);
  const context = vm.createContext(engine);
  vm.runInContext("properties = {};\n" + HOOK, context, {filename: "post.cps"});
  context.onTerminate();

  const words = expectedWords(machine, stock, extra, out);
  const calls = fs.existsSync(process.env.STUB_LOG)
    ? fs.readFileSync(process.env.STUB_LOG, "utf8").trim().split("\n").map((l) => JSON.parse(l)) : [];
  const problems = [];
  if (refused(words, throughCmd)) {
    if (calls.length) problems.push("ran although it had to refuse: " + JSON.stringify(calls));
    if (!engine.record.warnings.some((w) => /is not annotated: /.test(w))) {
      problems.push("refused without saying why: " + JSON.stringify(engine.record.warnings));
    }
  } else if (JSON.stringify(calls) !== JSON.stringify([words])) {
    problems.push("ncjoule got " + JSON.stringify(calls) + ", expected " + JSON.stringify([words]) +
                  "; warnings " + JSON.stringify(engine.record.warnings));
  }
  const after = snapshot(work, logs);
  for (const p of new Set(Object.keys(before).concat(Object.keys(after)))) {
    if (before[p] !== after[p]) problems.push("changed or appeared: " + JSON.stringify(p));
  }
  return problems;
}

function main() {
  const argv = process.argv.slice(2);
  const option = (name, fallback) => (argv.indexOf(name) >= 0 ? Number(argv[argv.indexOf(name) + 1]) : fallback);
  const runs = option("--runs", 40);
  const seed = option("--seed", Math.floor(Math.random() * 4294967296));
  console.log("seed " + seed + " (replay: fusion_hook_args_fuzz.js --seed " + seed + " --runs " + runs + ")");
  const random = generator(seed);
  const base = fs.mkdtempSync(path.join(os.tmpdir(), "ncjoule-fusion-fuzz-"));
  const program = stub(base);
  let failures = 0;
  for (let run = 0; run < runs; ++run) {
    const work = path.join(base, "run" + run);
    fs.mkdirSync(work);
    const problems = oneRun(random, work, program);
    if (problems.length) {
      failures++;
      console.log("FAIL run " + run + " (kept in " + work + "): " + problems.join("; "));
    } else {
      fs.rmSync(work, {recursive: true});
    }
  }
  if (failures) {
    console.log(failures + " of " + runs + " runs failed (seed " + seed + ")");
    process.exit(1);
  }
  fs.rmSync(base, {recursive: true});
  console.log("all " + runs + " runs held");
}

main();
