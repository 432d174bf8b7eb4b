#!/usr/bin/python3
"""setup.sh installs everything the build and the tests use: the fast guard of the fresh-machine
check (.ci/fresh_machine_check.sh), which a used machine would pass with a package that someone
installed by hand.

Checked, each one to exist and to belong to a package that setup.sh installs (its PACKAGES and
the npm it adds), one of their dependencies (apt-cache depends --recurse, no recommends: setup.sh
installs none), or a package every minimal Debian 12 install has (Essential or Priority
required; mmdebstrap's minbase), git and ca-certificates (needed for the clone):
  - every file the imported targets of the CMake package configs the build found reference
    (their _IMPORT_CHECK_FILES lists: what find_package checks, and stops on when one is missing),
  - every file and folder the build's CMake cache found (compilers, libraries, the configs),
  - every program the tests' commands start (ctest --show-only) and the programs the project and
    its tests call by name (PROGRAMS below), looked up on a fresh root's PATH.
Exit status 1, one line a problem, naming the package to add to setup.sh where the file has one.
The check runs first on a copy of setup.sh without openimageio-tools and must find it missing.

usage: setup_packages_check.py SOURCE_DIR BUILD_DIR [--setup SETUP_SH]
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

# The PATH of a fresh root's login shell: a program found only in a folder outside it is missing.
FRESH_PATH = "/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin"
# What the fresh-machine check adds to mmdebstrap's minbase to get the clone.
CLONE_PACKAGES = ["git", "ca-certificates"]
# Programs the project and its tests call by name (an absolute path where they name one), and who.
PROGRAMS = {
    "/usr/bin/python3": "the report, the paper tables and the Python tests",
    "/usr/bin/node": "the viewer's tests",
    "npm": "setup.sh --tests (the browser test's npm packages)",
    "chromium": "the viewer's browser test (tests/report/viewer)",
    "povray": "the Whitted reference's POV-Ray cross-check (tests/raytrace)",
    "oiiotool": "the image fixtures' scripts (tests/fixtures/image_formats)",
    "git": "the program's version and ReadmeWalkthrough's clone",
    "glslc": "the shaders' build",
    "cmake": "the build",
    "ctest": "the test command",
    "ninja": "the build",
    "clang++-14": "the sanitizer build and the fuzz targets (tests/sanitize, tests/fuzz)",
    "ldd": "the bundle (the libraries it copies)",
    "xz": "the bundle and the GPU campaign",
    "tar": "the bundle and the GPU campaign",
    "timeout": "the tests' time limits",
    "sbatch": "experiments/slurm_array.sh and SlurmEndToEnd",
    "scontrol": "SlurmEndToEnd",
    "sinfo": "SlurmEndToEnd",
    "squeue": "SlurmEndToEnd",
    "scancel": "SlurmEndToEnd",
    "slurmctld": "SlurmEndToEnd",
    "slurmd": "SlurmEndToEnd",
    "munged": "SlurmEndToEnd",
    "mungekey": "SlurmEndToEnd",
}
# CMake cache entries that name no dependency: CTest's optional tools (memory checker, coverage),
# which the project never runs, and the install prefix.
IGNORED_CACHE = re.compile(r"^(MEMORYCHECK_COMMAND|MEMORYCHECK_SUPPRESSIONS_FILE|COVERAGE_COMMAND|CMAKE_INSTALL_.*)$")
IMPORT_CHECK = re.compile(r"list\(APPEND\s+_(?:cmake_)?import_check_files_for_(\S+)\s+(.*)\)", re.IGNORECASE)
PREFIX_UP = '(_IMPORT_PREFIX "${_IMPORT_PREFIX}" PATH)'
FATAL_CHECK = re.compile(r'message\(FATAL_ERROR "The imported target')


def setup_packages(setup_sh):
    """The packages setup.sh installs: its PACKAGES array and what it adds to `missing` by hand."""
    with open(setup_sh) as f:
        text = f.read()
    block = re.search(r"^PACKAGES=\((.*?)^\)", text, re.MULTILINE | re.DOTALL)
    if not block:
        raise ValueError("%s has no PACKAGES=( ... ) array" % setup_sh)
    words = " ".join(re.sub(r"#.*", "", line) for line in block.group(1).splitlines()).split()
    for extra in re.findall(r"missing\+=\(([^)$]*)\)", text):
        words += extra.split()
    return words


def closure(packages):
    """The packages with every package they depend on, recursively (no recommends, no suggests),
    and the named packages apt does not know."""
    out = subprocess.run(["apt-cache", "depends", "--recurse", "--no-recommends", "--no-suggests", "--no-conflicts",
                          "--no-breaks", "--no-replaces", "--no-enhances"] + packages,
                         capture_output=True, text=True, check=True).stdout
    names, known = set(packages), set()
    for line in out.splitlines():
        # "pkg", "  Depends: pkg", "  PreDepends: <virtual>", "    provider": every name counts.
        dependency = line.lstrip().startswith(("Depends:", "PreDepends:", "|Depends:", "|PreDepends:"))
        name = (line.split(":", 1)[1] if dependency else line).strip().strip("<>").split(":")[0]
        names.add(name)
        if not line.startswith(" "):
            known.add(name)
    return names, [p for p in packages if p not in known]


def minimal_install():
    """The installed packages that every minimal Debian 12 install has."""
    out = subprocess.run(["dpkg-query", "-W", "-f", "${Package}\t${Essential}\t${Priority}\n"],
                         capture_output=True, text=True, check=True).stdout
    return {p for p, essential, priority in (l.split("\t") for l in out.splitlines()) if essential == "yes" or priority == "required"}


def owners(paths):
    """{path: [packages]} for the paths dpkg knows; a path is looked up as given, resolved, and under
    the merged /usr's other name (dpkg may know /bin/x as the file /usr/bin/x)."""
    aliases = {}
    for p in paths:
        real = os.path.realpath(p)
        names = {p, real}
        for n in list(names):
            if n.startswith("/usr/"):
                names.add(n[4:])
            elif n.startswith(("/bin/", "/sbin/", "/lib")):
                names.add("/usr" + n)
        aliases[p] = names
    out = subprocess.run(["dpkg-query", "-S"] + sorted(set().union(*aliases.values())), capture_output=True, text=True).stdout
    known = {}
    for line in out.splitlines():
        if line.startswith("diversion ") or ": " not in line:
            continue
        pkgs, path = line.split(": ", 1)
        known.setdefault(path, set()).update(p.strip().split(":")[0] for p in pkgs.split(","))
    return {p: sorted(set().union(*(known.get(n, set()) for n in names))) for p, names in aliases.items()}


def cmake_cache(build_dir):
    """{entry: path} for the cache's FILEPATH and PATH entries that name a place outside the project."""
    entries = {}
    with open(os.path.join(build_dir, "CMakeCache.txt")) as f:
        for line in f:
            m = re.match(r"^([A-Za-z_][\w.+-]*):(FILEPATH|PATH)=(/.*)$", line.rstrip("\n"))
            if m and not IGNORED_CACHE.match(m.group(1)):
                entries[m.group(1)] = m.group(3)
    return entries


def imported_files(config_dir):
    """{file: target} for every file an imported target of the CMake package config in
    `config_dir` references, as its *Targets*.cmake list them for find_package to check, where a
    missing one stops find_package (Debian turns the check of some into a status message)."""
    files = {}
    scripts = sorted(f for f in os.listdir(config_dir) if f.endswith(".cmake"))
    for main in scripts:
        with open(os.path.join(config_dir, main), errors="replace") as f:
            text = f.read()
        if '(_IMPORT_PREFIX "${CMAKE_CURRENT_LIST_FILE}" PATH)' not in text or not FATAL_CHECK.search(text):
            continue
        prefix = config_dir
        for _ in range(text.count(PREFIX_UP)):
            prefix = os.path.dirname(prefix)
        # The file itself and the per-configuration files it includes (NAME-none.cmake, NAME-release.cmake).
        for name in [main] + [s for s in scripts if s.startswith(main[:-len(".cmake")] + "-")]:
            with open(os.path.join(config_dir, name), errors="replace") as f:
                for target, listed in IMPORT_CHECK.findall(f.read()):
                    for path in re.findall(r'"([^"]+)"', listed):
                        files[path.replace("${_IMPORT_PREFIX}", "" if prefix == "/" else prefix)] = target
    return files


def test_programs(build_dir, project_dirs):
    """{program: test} for the programs the tests' commands start, outside the project."""
    out = subprocess.run(["ctest", "--show-only=json-v1", "--test-dir", build_dir], capture_output=True, text=True, check=True).stdout
    programs = {}
    for test in json.loads(out).get("tests", []):
        command = test.get("command") or []
        if command and not any(command[0].startswith(d + os.sep) for d in project_dirs):
            programs.setdefault(command[0], "the test " + test["name"])
    return programs


def what_is_used(source_dir, build_dir):
    """{path or program name: who uses it}."""
    project_dirs = [os.path.realpath(source_dir), os.path.realpath(build_dir)]
    used = {}
    for entry, path in cmake_cache(build_dir).items():
        if any(os.path.realpath(path).startswith(d) for d in project_dirs):
            continue
        used[path] = "the CMake cache's " + entry
        if entry.endswith("_DIR") and os.path.isdir(path):
            for file, target in imported_files(path).items():
                used.setdefault(file, "the imported target %s of %s's CMake config" % (target, entry[:-4]))
    used.update(test_programs(build_dir, project_dirs))
    for program, who in PROGRAMS.items():
        used.setdefault(program, who)
    return used


def problems(setup_sh, used, minimal):
    """One line for each thing in `used` that is missing or comes from a package setup.sh lacks."""
    allowed, unknown = closure(setup_packages(setup_sh) + CLONE_PACKAGES)
    allowed |= minimal
    found = ["%s names the package %s, which apt does not know" % (setup_sh, p) for p in unknown]
    paths = {}
    for thing, who in sorted(used.items()):
        path = thing if thing.startswith("/") else shutil.which(thing, path=FRESH_PATH)
        if path is None or not os.path.exists(path):
            found.append("%s (%s) is not on this machine: ./setup.sh installs everything the build and the tests use, so it "
                         "lacks the Debian package that holds it" % (thing, who))
        else:
            paths[path] = (thing, who)
    for path, pkgs in sorted(owners(list(paths)).items()):
        thing, who = paths[path]
        shown = thing if thing == path else "%s (%s)" % (thing, path)
        if not pkgs:
            found.append("%s, used by %s, belongs to no Debian package (installed by hand?): use a Debian package "
                         "and add it to setup.sh's PACKAGES" % (shown, who))
        elif not allowed.intersection(pkgs):
            found.append("%s, used by %s, belongs to %s, which setup.sh does not install (nor does anything it installs "
                         "depend on it): add %s to setup.sh's PACKAGES" % (shown, who, " and ".join(pkgs), pkgs[0]))
    return found


def self_test(source_dir, used, minimal):
    """A setup.sh without openimageio-tools must fail on OpenImageIO's imported tools."""
    with open(os.path.join(source_dir, "setup.sh")) as f:
        text = f.read()
    if not re.search(r"^\s*openimageio-tools\s*$", text, re.MULTILINE):
        return  # nothing to take out: the real check says what is missing
    with tempfile.TemporaryDirectory() as scratch:
        lacking = os.path.join(scratch, "setup.sh")
        with open(lacking, "w") as f:
            f.write(re.sub(r"^\s*openimageio-tools\s*$", "", text, flags=re.MULTILINE))
        found = problems(lacking, used, minimal)
    if not any("iconvert" in p and "add openimageio-tools to setup.sh's PACKAGES" in p for p in found):
        sys.exit("FAILED: the check passes a setup.sh without openimageio-tools; it found:\n" + "\n".join(found))


def main():
    args = sys.argv[1:]
    setup_sh = None
    if "--setup" in args:
        i = args.index("--setup")
        if i + 1 >= len(args):
            print("setup_packages_check: --setup needs a path to a setup.sh", file=sys.stderr)
            sys.exit(2)
        setup_sh = args[i + 1]
        del args[i:i + 2]
    if len(args) != 2 or not os.path.isfile(os.path.join(args[1], "CMakeCache.txt")):
        print("usage: setup_packages_check.py SOURCE_DIR BUILD_DIR [--setup SETUP_SH] (BUILD_DIR: a configured build)", file=sys.stderr)
        sys.exit(2)
    source_dir, build_dir = args
    setup_sh = setup_sh or os.path.join(source_dir, "setup.sh")
    if not os.path.isfile(setup_sh):
        print("setup_packages_check: no setup.sh at %s" % setup_sh, file=sys.stderr)
        sys.exit(2)
    used = what_is_used(source_dir, build_dir)
    minimal = minimal_install()
    self_test(source_dir, used, minimal)  # the check first, on a setup.sh known to lack a package
    try:
        found = problems(setup_sh, used, minimal)
    except ValueError as e:
        print("setup_packages_check: %s" % e, file=sys.stderr)
        sys.exit(2)
    for line in found:
        print(line)
    if found:
        sys.exit("FAILED: %d thing(s) the build or the tests use that %s does not install" % (len(found), setup_sh))
    print("%d files and programs the build and the tests use, each from a package %s installs or depends on"
          % (len(used), setup_sh))


if __name__ == "__main__":
    main()
