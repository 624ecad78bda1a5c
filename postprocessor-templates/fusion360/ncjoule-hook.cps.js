/*
  ncjoule hook for Autodesk post processors (Fusion, Inventor CAM, HSM): append this whole file
  to the end of a vendor .cps post. After the post has written its program(s), the hook runs

      ncjoule annotate [--machine=<profile>] --in-place --stock=<the post's workpiece> --stock-from=fusion360 [<extra arguments>] -- <file>

  on every NC file the post wrote, so each block carries its predicted time, MRR, power and
  energy as a comment. See README.md next to this file.

  The hook never makes a post fail: when ncjoule is missing, turned off, not configured or fails,
  the post's own files stay exactly as the post wrote them and the post log says why (warning()).

  What it adds to the post:
  - five properties (kept if the post already has properties of the same names):
      ncjouleEnable     annotate the output (on/off)
      ncjoulePath       the ncjoule program ("ncjoule" finds it on the PATH; on Windows also
                        in the install folders, as ncjoule.exe)
      ncjouleMachine    the machine profile: a .toml file (a relative path is looked up next to
                        the post) or a shipped profile's name (haas-vf2); empty: the user
                        config's machine, else ncjoule's generic profile, as on the command line
      ncjouleStock      a stock in place of the setup's workpiece, as ncjoule's --stock text
                        (box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX or an .stl file); empty: the
                        workpiece the post engine knows (getWorkpiece(), in the program's units),
                        and without one the box of the cutting moves
      ncjouleArguments  further arguments for `ncjoule annotate` (e.g. --dialect fanuc), split at
                        blanks and never evaluated
  - an onTerminate() that first runs the post's own onTerminate() (if it has one) and then
    annotates the main output (getOutputPath()) and every other file of the same extension the
    post opened with redirectToFile() or new TextFile(path, true, ...) (subprograms, one file per
    operation or tool). A post that writes files some other way can name them with
    ncjouleAddOutputFile(path).

  Every argument is quoted for the command line execute() runs (the MS C runtime's rules on
  Windows, a shell's on macOS and Linux); a value that cannot be passed safely (a newline; on
  Windows through a .bat or .cmd, a quote, % or !) is refused with a warning and the file is left
  as the post wrote it.
*/

var ncjouleHookVersion = "1";

// The properties the hook adds, in the post engine's property-object form.
var ncjouleHookPropertyDefinitions = {
  ncjouleEnable: {
    title: "ncjoule: annotate output",
    description: "Annotate the posted program with ncjoule's predicted time, MRR, power and energy per block.",
    type: "boolean",
    value: true,
    scope: "post"
  },
  ncjoulePath: {
    title: "ncjoule: program",
    description: "Path of the ncjoule program; 'ncjoule' runs the one on the PATH.",
    type: "string",
    value: "ncjoule",
    scope: "post"
  },
  ncjouleMachine: {
    title: "ncjoule: machine profile",
    description: "Machine profile to predict with: a .toml file (a relative path is looked up in the post's folder) or a shipped profile's name (haas-vf2); empty: the user config's machine, else ncjoule's generic profile.",
    type: "string",
    value: "",
    scope: "post"
  },
  ncjouleStock: {
    title: "ncjoule: stock",
    description: "A stock in place of the setup's workpiece, as ncjoule's --stock text: box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX or an .stl file. Empty: the setup's workpiece.",
    type: "string",
    value: "",
    scope: "post"
  },
  ncjouleArguments: {
    title: "ncjoule: extra arguments",
    description: "Further arguments for 'ncjoule annotate', e.g. --dialect fanuc.",
    type: "string",
    value: "",
    scope: "post"
  }
};

// Adds the hook's properties to the post's, in whichever of the two property styles the post
// uses, never replacing one the post already has.
function ncjouleInstallProperties() {
  if (typeof properties != "object" || properties == null) {
    properties = {};
  }
  var modern = true; // property objects with a value field
  var anyProperty = false;
  for (var existing in properties) {
    anyProperty = true;
    var p = properties[existing];
    modern = (p != null && typeof p == "object" && ("value" in p));
    break;
  }
  if (!anyProperty && typeof propertyDefinitions == "object" && propertyDefinitions != null) {
    modern = false;
  }
  var grouped = (typeof groupDefinitions == "object" && groupDefinitions != null);
  if (grouped && !("ncjoule" in groupDefinitions)) {
    groupDefinitions.ncjoule = {title: "ncjoule", description: "Energy and time annotation", collapsed: true, order: 90};
  }
  for (var name in ncjouleHookPropertyDefinitions) {
    if (name in properties) {
      continue; // the post's own setting wins
    }
    var d = ncjouleHookPropertyDefinitions[name];
    if (modern) {
      var copy = {};
      for (var key in d) {
        copy[key] = d[key];
      }
      if (grouped) {
        copy.group = "ncjoule";
      }
      properties[name] = copy;
    } else {
      properties[name] = d.value;
      if (typeof propertyDefinitions == "object" && propertyDefinitions != null && !(name in propertyDefinitions)) {
        propertyDefinitions[name] = {title: d.title, description: d.description, type: d.type};
      }
    }
  }
}
ncjouleInstallProperties();

// The current value of a property, whichever way the post engine keeps it.
function ncjouleProperty(name) {
  var value;
  if (typeof getProperty == "function") {
    try {
      value = getProperty(name);
    } catch (e) {
      value = undefined;
    }
  }
  if (value === undefined && typeof properties == "object" && properties != null && (name in properties)) {
    value = properties[name];
  }
  if (value != null && typeof value == "object" && ("value" in value)) {
    value = value.value;
  }
  if (value === undefined) {
    value = ncjouleHookPropertyDefinitions[name].value;
  }
  return value;
}

function ncjouleWarning(message) {
  if (typeof warning == "function") {
    warning("ncjoule: " + message);
  } else if (typeof log == "function") {
    log("ncjoule: " + message);
  }
}

function ncjouleLog(message) {
  if (typeof log == "function") {
    log("ncjoule: " + message);
  }
}

// ---------------------------------------------------------------------------------------------
// The files the post writes
// ---------------------------------------------------------------------------------------------

var ncjouleOutputFiles = [];

function ncjouleAddOutputFile(path) {
  if (!path) {
    return;
  }
  path = String(path);
  for (var i = 0; i < ncjouleOutputFiles.length; ++i) {
    if (ncjouleOutputFiles[i] == path) {
      return;
    }
  }
  ncjouleOutputFiles.push(path);
}

// Every redirectToFile(path) the post makes is recorded, then done as before.
if (typeof redirectToFile == "function" && !redirectToFile.ncjouleWrapped) {
  var ncjouleOriginalRedirectToFile = redirectToFile;
  try {
    redirectToFile = function (path) {
      ncjouleAddOutputFile(path);
      return ncjouleOriginalRedirectToFile.apply(this, arguments);
    };
    redirectToFile.ncjouleWrapped = true;
  } catch (e) {
    ncjouleLog("cannot follow redirectToFile(); only the main output is annotated");
  }
}

// Every TextFile the post opens for writing is recorded (posts that write subprograms to files
// of their own), then opened as before.
if (typeof TextFile == "function" && !TextFile.ncjouleWrapped) {
  var ncjouleOriginalTextFile = TextFile;
  try {
    TextFile = function (path, write) {
      if (write) {
        ncjouleAddOutputFile(path);
      }
      var args = Array.prototype.slice.call(arguments);
      return new (Function.prototype.bind.apply(ncjouleOriginalTextFile, [null].concat(args)))();
    };
    TextFile.prototype = ncjouleOriginalTextFile.prototype;
    TextFile.ncjouleWrapped = true;
  } catch (e) {
    ncjouleLog("cannot follow TextFile; files the post writes that way are not annotated");
  }
}

// ---------------------------------------------------------------------------------------------
// Running ncjoule
// ---------------------------------------------------------------------------------------------

function ncjouleExtensionOf(path) {
  var name = String(path).replace(/^.*[\\\/]/, "");
  var dot = name.lastIndexOf(".");
  return dot > 0 ? name.substring(dot + 1).toLowerCase() : "";
}

function ncjouleIsFile(path) {
  try {
    if (typeof FileSystem != "undefined" && FileSystem && typeof FileSystem.isFile == "function") {
      return FileSystem.isFile(path);
    }
  } catch (e) {
    return false;
  }
  return true; // cannot tell: let ncjoule say
}

function ncjouleHasFolder(path) {
  return /[\\\/]/.test(path);
}

// A value of the environment, where the post engine gives it (getEnvironmentVariable()); "" else.
function ncjouleEnvironment(name) {
  try {
    if (typeof getEnvironmentVariable == "function") {
      return String(getEnvironmentVariable(name) || "");
    }
  } catch (e) {
    // not available: as if unset
  }
  return "";
}

// The ncjoule program to run. A path (with a folder) is used as given. A bare name (the default
// "ncjoule") on Windows is looked for as NAME.exe in the folders of the PATH, then in the install
// folders the Windows README names (%LOCALAPPDATA%\Programs\ncjoule\bin, then
// %ProgramFiles%\ncjoule\bin): a program that starts ncjoule by name need not search for it the
// way a command prompt does. Elsewhere, and when none is found, the name is given to execute()
// as it is.
function ncjouleFindProgram(program) {
  if (ncjouleHasFolder(program) || !ncjouleOnWindows() ||
      typeof FileSystem == "undefined" || !FileSystem || typeof FileSystem.isFile != "function") {
    return program;
  }
  var name = /\.[A-Za-z0-9]+$/.test(program) ? program : program + ".exe";
  var folders = ncjouleEnvironment("PATH").split(";");
  var local = ncjouleEnvironment("LOCALAPPDATA");
  if (local) {
    folders.push(local + "\\Programs\\ncjoule\\bin");
  }
  folders.push((ncjouleEnvironment("ProgramFiles") || "C:\\Program Files") + "\\ncjoule\\bin");
  for (var i = 0; i < folders.length; ++i) {
    var folder = folders[i].replace(/"/g, "").replace(/[\\\/]+$/, "");
    if (!folder) {
      continue;
    }
    var candidate = folder + "\\" + name;
    try {
      if (FileSystem.isFile(candidate)) {
        return candidate;
      }
    } catch (e) {
      // an unreadable folder: the next one
    }
  }
  return program;
}

// The profile as given, or next to the post when the given path is relative and found there.
function ncjouleResolveProfile(profile) {
  if (/^([A-Za-z]:)?[\\\/]/.test(profile) || ncjouleIsFile(profile) && ncjouleHasFolder(profile)) {
    return profile;
  }
  try {
    if (typeof getConfigurationFolder == "function" && typeof FileSystem != "undefined" &&
        typeof FileSystem.getCombinedPath == "function") {
      var nextToPost = FileSystem.getCombinedPath(getConfigurationFolder(), profile);
      if (FileSystem.isFile(nextToPost)) {
        return nextToPost;
      }
    }
  } catch (e) {
    // keep the path as given
  }
  return profile;
}

var ncjouleExitReasons = {
  1: "bad command line (check the extra arguments)",
  2: "bad input: the program, the machine profile or the stock could not be read",
  3: "the annotated file could not be written",
  4: "internal error"
};

// ---------------------------------------------------------------------------------------------
// The command line: execute() takes the arguments as one string, which the program's C runtime
// splits on Windows (CommandLineToArgvW rules) and a shell-like parse splits on macOS and Linux.
// Every argument is quoted for the one that applies, so that a name with spaces, quotes, $, `,
// %, & or backslashes reaches ncjoule as one argument and runs nothing; what cannot be passed
// safely is refused.
// ---------------------------------------------------------------------------------------------

function ncjouleOnWindows() {
  try {
    if (typeof getPlatform == "function") {
      return /^win/i.test(String(getPlatform()));
    }
  } catch (e) {
    // fall back to the look of the output path
  }
  var main = (typeof getOutputPath == "function") ? String(getOutputPath() || "") : "";
  return /^([A-Za-z]:[\\\/]|\\\\)/.test(main);
}

function ncjouleRepeat(text, count) {
  var out = "";
  for (var i = 0; i < count; ++i) {
    out += text;
  }
  return out;
}

// One argument for the MS C runtime: in double quotes, a quote as \", and backslashes doubled
// only where they come before a quote (the closing one included), as the runtime halves them.
function ncjouleQuoteWindows(text) {
  var out = "\"";
  var backslashes = 0;
  for (var i = 0; i < text.length; ++i) {
    var c = text.charAt(i);
    if (c == "\\") {
      ++backslashes;
      continue;
    }
    if (c == "\"") {
      out += ncjouleRepeat("\\", 2 * backslashes + 1) + "\"";
    } else {
      out += ncjouleRepeat("\\", backslashes) + c;
    }
    backslashes = 0;
  }
  return out + ncjouleRepeat("\\", 2 * backslashes) + "\"";
}

// One argument for a shell: in single quotes nothing is special; a quote ends them, is given
// escaped, and they start again.
function ncjouleQuotePosix(text) {
  return "'" + text.replace(/'/g, "'\\''") + "'";
}

// Why an argument cannot be passed safely, or "". A control character (a newline above all)
// would end the command line or the word under one parse or another; through cmd.exe (a .bat or
// .cmd as the program) a quote ends the quoting and % and ! expand variables.
function ncjouleUnsafe(argument, throughCmd) {
  if (/[\x00-\x1f\x7f]/.test(argument)) {
    return "a control character (a newline, a tab, ...)";
  }
  if (throughCmd && /["%!]/.test(argument)) {
    return "\", % or !, which cmd.exe would act on";
  }
  return "";
}

// The argument string for execute(), or {refused: why}.
function ncjouleCommandLine(program, words) {
  var windows = ncjouleOnWindows();
  var throughCmd = windows && /\.(bat|cmd)$/i.test(program);
  var quoted = [];
  for (var i = 0; i < words.length; ++i) {
    var why = ncjouleUnsafe(words[i], throughCmd);
    if (why) {
      return {refused: "'" + words[i].replace(/[\x00-\x1f\x7f]/g, "?") + "' holds " + why};
    }
    quoted.push(windows ? ncjouleQuoteWindows(words[i]) : ncjouleQuotePosix(words[i]));
  }
  return {line: quoted.join(" ")};
}

// The extra arguments (property ncjouleArguments): split at blanks, never evaluated. "--" and
// --follow-symlinks are left out: the file must be the one argument after the hook's own "--",
// and the hook never replaces what a link points to.
function ncjouleExtraArguments() {
  var words = String(ncjouleProperty("ncjouleArguments") || "").split(/[ \t\r\n]+/);
  var out = [];
  for (var i = 0; i < words.length; ++i) {
    if (!words[i]) {
      continue;
    }
    if (words[i] == "--" || words[i] == "--follow-symlinks" || /^--follow-symlinks=/.test(words[i])) {
      ncjouleWarning("'" + words[i] + "' in ncjouleArguments is not passed on");
      continue;
    }
    out.push(words[i]);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// What ncjoule did. execute() gives back the exit status only, not ncjoule's status line; the
// file itself tells whether it was rewritten: a fingerprint (lines and a hash of their text)
// taken before and after. Never the look of its comments, which the post's own text may mimic.
// ---------------------------------------------------------------------------------------------

// "LINES:HASH" of a file, or "" when it cannot be read. Never throws.
function ncjouleFingerprint(file) {
  try {
    if (typeof TextFile == "undefined") {
      return "";
    }
    var f = new TextFile(file, false, "ansi");
    var hash = 0; // a polynomial hash of every character, exact in a double
    var lines = 0;
    for (;;) {
      var line;
      try {
        line = f.readln();
      } catch (e) {
        break; // the end of the file
      }
      if (line === undefined || line === null) {
        break;
      }
      line = String(line) + "\n";
      for (var i = 0; i < line.length; ++i) {
        hash = (hash * 31 + line.charCodeAt(i)) % 4294967291;
      }
      ++lines;
    }
    f.close();
    return lines + ":" + hash;
  } catch (e) {
    return "";
  }
}

var ncjouleExitReasons = {
  1: "bad command line (check the extra arguments)",
  2: "bad input: the program, the machine profile or the stock could not be read",
  3: "nothing could be written (the file is a symbolic link, or was still being written or changed)",
  4: "internal error"
};

// A number as ncjoule reads it: fixed point (never an exponent), no trailing zeros.
function ncjouleNumber(value) {
  var text = value.toFixed(6).replace(/0+$/, "").replace(/\.$/, "");
  return text == "-0" ? "0" : text;
}

// The setup's workpiece (the stock the post engine knows) as ncjoule's --stock text, each value
// with its unit: the post engine gives it in the program's units (the post's `unit`, IN or MM).
// "" when the engine has none, or it is empty or not finite.
function ncjouleWorkpieceStock() {
  try {
    if (typeof getWorkpiece != "function") {
      return "";
    }
    var box = getWorkpiece();
    if (!box || !box.lower || !box.upper) {
      return "";
    }
    var values = [box.lower.x, box.lower.y, box.lower.z, box.upper.x, box.upper.y, box.upper.z];
    for (var i = 0; i < values.length; ++i) {
      if (typeof values[i] != "number" || !isFinite(values[i])) {
        return "";
      }
    }
    if (!(values[3] > values[0] && values[4] > values[1] && values[5] > values[2])) {
      return "";
    }
    var inch = typeof unit != "undefined" && typeof IN != "undefined" && unit == IN;
    var words = [];
    for (var k = 0; k < values.length; ++k) {
      words.push(ncjouleNumber(values[k]) + (inch ? "in" : "mm"));
    }
    return "box:" + words.join(",");
  } catch (e) {
    return "";
  }
}

// Annotates one file in place; true when it was annotated. Never throws.
function ncjouleAnnotateFile(program, profile, file) {
  var words = ["annotate"].concat(profile ? ["--machine=" + profile] : [], ["--in-place"]);
  // The user's own stock setting, else the setup's workpiece, named as the hook's (docs/stock.md).
  var stock = String(ncjouleProperty("ncjouleStock") || "");
  if (stock) {
    words.push("--stock=" + stock);
  } else if ((stock = ncjouleWorkpieceStock())) {
    words.push("--stock=" + stock, "--stock-from=fusion360");
  }
  // "--" before the file: a file named like an option stays a file.
  words = words.concat(ncjouleExtraArguments(), ["--", file]);
  var command = ncjouleCommandLine(program, words);
  if (command.refused) {
    ncjouleWarning(file + " is not annotated: " + command.refused +
      ", which cannot be passed to ncjoule safely here; the file is as the post wrote it");
    return false;
  }
  var before = ncjouleFingerprint(file);
  var code;
  try {
    var folder = "";
    if (typeof FileSystem != "undefined" && typeof FileSystem.getFolderPath == "function") {
      folder = FileSystem.getFolderPath(file);
    }
    code = execute(program, command.line, true, folder);
  } catch (e) {
    ncjouleWarning("could not run '" + program + "' (" + e + "); " + file + " is as the post wrote it");
    return false;
  }
  var after = ncjouleFingerprint(file);
  var rewritten = before === "" || after === "" ? undefined : before != after;
  if (code === 2 && rewritten) {
    // Errors the controller would refuse: annotated all the same, the header lists them.
    ncjouleWarning(file + " was annotated; it has errors its controller would refuse (see its NCJ WARN lines)");
    return true;
  }
  if (code !== 0 && code !== undefined && code !== null) {
    ncjouleWarning("'" + program + " " + command.line + "' exited with " + code +
      (ncjouleExitReasons[code] ? " (" + ncjouleExitReasons[code] + ")" : "") +
      "; " + file + " is as the post wrote it");
    return false;
  }
  ncjouleLog(rewritten === false ? file + " unchanged: already annotated this way" : "annotated " + file);
  return true;
}

function ncjouleAnnotateOutputs() {
  if (!ncjouleProperty("ncjouleEnable")) {
    ncjouleLog("annotation is off (property ncjouleEnable)");
    return;
  }
  try {
    var program = ncjouleFindProgram(String(ncjouleProperty("ncjoulePath") || "ncjoule"));
    var profile = String(ncjouleProperty("ncjouleMachine") || "");
    if (!profile) {
      // As on the command line: the user config's machine, else ncjoule's generic profile.
      ncjouleLog("no machine profile set (property ncjouleMachine): ncjoule takes the user config's, else its generic one");
    }
    if (typeof execute != "function") {
      ncjouleWarning("this post engine cannot run programs (no execute()); the output is not annotated");
      return;
    }
    if (ncjouleHasFolder(program) && !ncjouleIsFile(program)) {
      ncjouleWarning("ncjoule not found at '" + program + "' (property ncjoulePath); the output is not annotated");
      return;
    }
    profile = profile ? ncjouleResolveProfile(profile) : "";
    if (profile && ncjouleHasFolder(profile) && !ncjouleIsFile(profile)) {
      ncjouleWarning("machine profile '" + profile + "' not found (property ncjouleMachine); the output is not annotated");
      return;
    }
    var files = [];
    var main = (typeof getOutputPath == "function") ? getOutputPath() : "";
    if (main) {
      files.push(String(main));
    }
    var wanted = main ? ncjouleExtensionOf(main) : ((typeof extension == "string") ? extension.toLowerCase() : "");
    for (var i = 0; i < ncjouleOutputFiles.length; ++i) {
      var f = ncjouleOutputFiles[i];
      if (f == main) {
        continue;
      }
      if (wanted && ncjouleExtensionOf(f) != wanted) {
        continue; // a log, a setup sheet, a tool list: not a program
      }
      files.push(f);
    }
    for (var j = 0; j < files.length; ++j) {
      if (!ncjouleIsFile(files[j])) {
        ncjouleWarning(files[j] + " does not exist (anymore); not annotated");
        continue;
      }
      ncjouleAnnotateFile(program, profile, files[j]);
    }
  } catch (e) {
    ncjouleWarning("annotation skipped: " + e);
  }
}

// onTerminate runs once the post has closed its output files: the post's own first, then ncjoule.
var ncjoulePreviousOnTerminate = (typeof onTerminate == "function") ? onTerminate : undefined;
onTerminate = function () {
  if (ncjoulePreviousOnTerminate) {
    ncjoulePreviousOnTerminate.apply(this, arguments);
  }
  ncjouleAnnotateOutputs();
};
