// A stand-in for the Autodesk post engine's globals that the Fusion hook
// (postprocessor-templates/fusion360/ncjoule-hook.cps.js) calls, for the tests under node.
// execute() runs the program as the engine would: on macOS and Linux the argument string is
// parsed by a shell (/bin/sh here, so anything the hook failed to quote really runs), on Windows
// ("WIN64") by the program's C runtime (modelled by splitWindows()).
"use strict";
const childProcess = require("child_process");
const fs = require("fs");
const path = require("path");

// How execute() turns its argument string into argv on macOS and Linux: a shell parses it (the
// stand-in runs it through /bin/sh, so anything the hook failed to quote would really run).
function runPosix(program, args, folder) {
  return childProcess.spawnSync("/bin/sh", ["-c", 'exec "$0" ' + args, program],
                                {cwd: folder || undefined, encoding: "utf8"});
}

// The words a shell makes of an argument string, as runPosix() passes them to the program (in
// the same folder: a command a broken hook let through runs where the test looks for it).
function splitPosix(args, folder) {
  const r = childProcess.spawnSync("/bin/sh", ["-c", 'printf "%s\\0" ' + args], {cwd: folder || undefined, encoding: "utf8"});
  return r.stdout.split("\0").slice(0, -1);
}

// How the MS C runtime splits a command line (CommandLineToArgvW, msvcrt 2008 and later): blanks
// separate arguments outside double quotes; 2n backslashes before a quote are n backslashes and
// the quote toggles quoting, 2n+1 are n and a literal quote; other backslashes are literal; ""
// inside quotes is a literal quote.
function splitWindows(line) {
  const out = [];
  let i = 0;
  for (;;) {
    while (line[i] === " " || line[i] === "\t") i++;
    if (i >= line.length) return out;
    let arg = "";
    let quoted = false;
    while (i < line.length && (quoted || (line[i] !== " " && line[i] !== "\t"))) {
      if (line[i] === "\\") {
        let n = 0;
        while (line[i] === "\\") { n++; i++; }
        if (line[i] === '"') {
          arg += "\\".repeat(n >> 1);
          if (n % 2) { arg += '"'; i++; }
        } else {
          arg += "\\".repeat(n);
        }
      } else if (line[i] === '"') {
        if (quoted && line[i + 1] === '"') { arg += '"'; i += 2; } else { quoted = !quoted; i++; }
      } else {
        arg += line[i++];
      }
    }
    out.push(arg);
  }
}

// A TextFile for the hook's reading (readln throws at the end, as the engine's does).
class StandInTextFile {
  constructor(p, write) {
    this.lines = write ? [] : fs.readFileSync(p, "latin1").split("\n");
    if (!write && this.lines[this.lines.length - 1] === "") this.lines.pop();
    this.next = 0;
  }
  readln() {
    if (this.next >= this.lines.length) throw new Error("end of file");
    return this.lines[this.next++];
  }
  close() {}
}

// A post engine: the globals a post (and the hook) sees, recording what happened.
function makeEngine(outputPath, propertyOverrides, platform, redirectSource) {
  const record = {warnings: [], logs: [], executed: [], events: []};
  const windows = platform === "WIN64";
  const engine = {
    record,
    console,
    extension: "ngc",
    getPlatform: () => platform || "LINUX",
    TextFile: StandInTextFile,
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
      record.executed.push([program, args, windows ? splitWindows(args) : splitPosix(args, folder)]);
      const r = windows ? childProcess.spawnSync(program, splitWindows(args), {cwd: folder || undefined, encoding: "utf8"})
                        : runPosix(program, args, folder);
      if (r.error) throw new Error("cannot run " + program + ": " + r.error.code);
      if (!windows && r.status === 127) throw new Error("cannot run " + program + ": ENOENT");
      return r.status;
    },
    // Output redirection: the stand-in copies a posted program into the file.
    redirectToFile(p) {
      record.events.push("redirect " + p);
      fs.copyFileSync(redirectSource, p);
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

module.exports = {makeEngine, splitWindows, splitPosix};
