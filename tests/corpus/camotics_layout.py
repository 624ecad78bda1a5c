#!/usr/bin/env python3
"""Lays CAMotics' example programs beside their .camotics projects, as CAMotics keeps them: one
folder per project, holding the project and each program its "files" name (the programs only:
CAMotics' .tpl templates are JavaScript, not G-code), read from a clone of
CauldronDevelopmentLLC/CAMotics (a bare one too: files are read with git show).

    tests/corpus/camotics_layout.py REPO OUT [--manual-only]

REPO: the CAMotics repository (working tree or bare .git); OUT: the folder to fill (made). With
--manual-only, only projects whose workpiece is set by hand ("automatic": false). Prints one
line per project laid out: its folder, its workpiece mode and its programs. Used by
bench/camotics_projects.py; other checks that want real programs with a known stock can use it.
"""
import json
import os
import subprocess
import sys

PROGRAM_EXTENSIONS = (".nc", ".ngc", ".gcode", ".gc", ".tap", ".cnc")


def git(repo, *args):
    return subprocess.run(["git", "--git-dir", repo] + list(args), check=True,
                          stdout=subprocess.PIPE, stderr=subprocess.DEVNULL).stdout


def git_dir(repo):
    dot_git = os.path.join(repo, ".git")
    return dot_git if os.path.isdir(dot_git) else repo


def lay_out(repo, out, manual_only=False):
    """[(folder, project path, automatic, [program paths])] for every project laid out."""
    repo = git_dir(repo)
    names = git(repo, "ls-tree", "-r", "--name-only", "HEAD").decode().splitlines()
    laid = []
    for name in sorted(n for n in names if n.endswith(".camotics")):
        project = json.loads(git(repo, "show", "HEAD:" + name))
        automatic = bool(project.get("workpiece", {}).get("automatic", True))
        if manual_only and automatic:
            continue
        folder = os.path.dirname(name)
        programs = [f for f in project.get("files", [])
                    if f.lower().endswith(PROGRAM_EXTENSIONS) and
                    (folder + "/" + f if folder else f) in names]
        if not programs:
            continue
        # A mirror may list its largest files without holding them: those are left out.
        texts = {}
        for program in programs:
            try:
                texts[program] = git(repo, "show", "HEAD:" + (folder + "/" + program if folder
                                                              else program))
            except subprocess.CalledProcessError:
                print("%s: not in the clone, left out" % program, file=sys.stderr)
        if not texts:
            continue
        target = os.path.join(out, os.path.splitext(os.path.basename(name))[0])
        os.makedirs(target, exist_ok=True)
        with open(os.path.join(target, os.path.basename(name)), "wb") as f:
            f.write(git(repo, "show", "HEAD:" + name))
        paths = []
        for program, text in texts.items():
            with open(os.path.join(target, program), "wb") as f:
                f.write(text)
            paths.append(os.path.join(target, program))
        laid.append((target, os.path.join(target, os.path.basename(name)), automatic, paths))
    return laid


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 2:
        sys.exit(__doc__)
    for folder, _, automatic, programs in lay_out(args[0], args[1], "--manual-only" in sys.argv):
        print("%s\t%s\t%s" % (folder, "automatic" if automatic else "manual",
                              " ".join(os.path.basename(p) for p in programs)))


if __name__ == "__main__":
    main()
