#!/usr/bin/python3
"""The README's "Your own scene", run as written on a fresh clone: every command of its `sh` blocks
(the lines starting with "$ ") runs in a clone of the repository with nothing beside it but the
program already built (`build` links to the build folder, nothing is rebuilt), and prints each
line the README shows under it, in order (a number shown matches any number: times and scores vary
with the machine; spaces, with the numbers' widths). The walkthrough's TOML blocks are the shipped files' own lines (its config is
examples/mirror-bunny/experiment.toml less its comment), and the set-up block's commands name what
exists: setup.sh's --tests, and a config that `hybridlab run --dry-run` accepts.

usage: readme_walkthrough_test.py SOURCE_DIR BUILD_DIR SCRATCH_DIR     (exit 77: skipped, saying why)
"""
import os
import re
import shutil
import subprocess
import sys

NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def section(text, title):
    """The lines of the README's `## title` section."""
    lines = text.splitlines()
    start = lines.index("## " + title) + 1
    end = next((i for i in range(start, len(lines)) if lines[i].startswith("## ")), len(lines))
    return lines[start:end]


def blocks(lines, language):
    """The fenced code blocks of `language` in `lines`, each as its lines."""
    found, current = [], None
    for line in lines:
        if current is None and line == "```" + language:
            current = []
        elif current is not None and line == "```":
            found.append(current)
            current = None
        elif current is not None:
            current.append(line)
    return found


def steps(sh_blocks):
    """(command, [expected output lines]) for each "$ " line of the blocks."""
    out = []
    for block in sh_blocks:
        for line in block:
            if line.startswith("$ "):
                out.append((line[2:], []))
            elif out and line.strip() and line.strip() != "...":
                out[-1][1].append(line)
    return out


def pattern(shown):
    """A shown line as a regular expression: its words as they are, any number for a number, and
    any run of spaces for a run of spaces (columns align to the widest number); a line ending in
    " ..." is the start of the line printed (a path that depends on the machine follows)."""
    prefix = shown.endswith(" ...")
    if prefix:
        shown = shown[:-len(" ...")]
    parts = re.split("(%s| +)" % NUMBER, shown)
    return re.compile("^" + "".join((" +" if p.startswith(" ") else NUMBER) if i % 2 else re.escape(p) for i, p in enumerate(parts))
                      + ("" if prefix else "$"))


def check_output(command, expected, output, failures):
    """Each expected line matches a line of `output`, in order."""
    lines = output.splitlines()
    at = 0
    for shown in expected:
        p = pattern(shown)
        while at < len(lines) and not p.match(lines[at]):
            at += 1
        if at == len(lines):
            failures.append("`%s` did not print, in order, the README's line\n    %s\nIt printed:\n%s" % (command, shown, output))
            return
        at += 1


def check_files(clone, lines, failures):
    """The README's TOML blocks are the shipped files' lines."""
    scene = open(os.path.join(clone, "examples", "mirror-bunny", "mirror-bunny.toml")).read().splitlines()
    config = [l for l in open(os.path.join(clone, "examples", "mirror-bunny", "experiment.toml")).read().splitlines()
              if not l.startswith("#")]
    toml = blocks(lines, "toml")
    if len(toml) != 2:
        failures.append("expected two TOML blocks in \"Your own scene\" (the scene's object, the config), found %d" % len(toml))
        return
    snippet = toml[0]
    if not any(scene[i:i + len(snippet)] == snippet for i in range(len(scene))):
        failures.append("the README's scene lines are not examples/mirror-bunny/mirror-bunny.toml's:\n" + "\n".join(snippet))
    if toml[1] != config:
        failures.append("the README's config is not examples/mirror-bunny/experiment.toml (less its comment):\n" + "\n".join(toml[1]))


def check_setup(clone, hybridlab, readme, env, failures):
    """The set-up commands name what exists."""
    commands = [l for b in blocks(section(readme, "Quick start"), "sh") for l in b if l and not l.startswith("#")]
    if len(commands) != 2 or not commands[0].startswith("./setup.sh && ") or not commands[1].startswith("./setup.sh --tests && ctest "):
        failures.append("expected the two set-up commands, ./setup.sh ... and ./setup.sh --tests && ctest ..., got %s" % commands)
        return
    if "--tests)" not in open(os.path.join(clone, "setup.sh")).read():
        failures.append("setup.sh takes no --tests")
    for config in re.findall(r"hybridlab run (\S+)", commands[0]):
        done = subprocess.run([hybridlab, "run", config, "--dry-run"], cwd=clone, env=env, capture_output=True, text=True, timeout=300)
        if done.returncode != 0:
            failures.append("`hybridlab run %s --dry-run` in the clone: exit %d\n%s" % (config, done.returncode, done.stderr))


def main(argv):
    if len(argv) != 4:
        sys.exit(__doc__)
    source, build, scratch = (os.path.abspath(a) for a in argv[1:])
    if not os.path.isdir(os.path.join(source, ".git")) and not os.path.isfile(os.path.join(source, ".git")):
        print("Skipped\nthe source tree is not a git checkout: there is nothing to clone")
        return 77
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    clone = os.path.join(scratch, "hybridlab")
    subprocess.run(["git", "clone", "--quiet", source, clone], check=True)
    os.symlink(build, os.path.join(clone, "build"))
    env = dict(os.environ, HYBRIDLAB_CACHE=os.path.join(scratch, "cache"))
    env.pop("HYBRIDLAB_ASSETS", None)
    env.pop("HYBRIDLAB_SCENES", None)
    readme = open(os.path.join(clone, "README.md")).read()
    lines = section(readme, "Your own scene")
    failures = []
    check_files(clone, lines, failures)
    check_setup(clone, os.path.join(build, "hybridlab"), readme, env, failures)
    walkthrough = steps(blocks(lines, "sh"))
    if len(walkthrough) < 5:
        failures.append("expected the walkthrough's commands (scene-info, render, compare, run, report), found %d" % len(walkthrough))
    for command, expected in walkthrough:
        print("$ " + command, flush=True)
        done = subprocess.run(["bash", "-c", command], cwd=clone, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              text=True, timeout=900)
        if done.returncode != 0:
            failures.append("`%s` exited with %d:\n%s%s" % (command, done.returncode, done.stdout, done.stderr))
            break
        check_output(command, expected, done.stdout, failures)
    for f in failures:
        print("FAILED: " + f)
    if not failures:
        print("the README's %d walkthrough commands ran as written and printed what it shows" % len(walkthrough))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
