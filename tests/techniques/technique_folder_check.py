#!/usr/bin/python3
"""Adding a technique is one folder and one registry line, nothing else (README "Techniques").

Builds a scratch copy of the source tree with exactly those two edits: tests/technique_template/
copied to techniques/throwaway/, and its include and entry added to techniques/registry.cpp. Then
configures that tree and builds only the new technique's objects, its shader and the registry: the
folder's CMakeLists.txt must be found without any other CMake edit, its shader compiled and embedded.
The rest of the source tree is linked, not copied, so nothing else can differ.

usage: technique_folder_check.py SOURCE_DIR SCRATCH_DIR
"""
import os
import re
import shutil
import subprocess
import sys


def run(cmd, cwd=None):
    print("$", " ".join(cmd), flush=True)
    done = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        print(done.stdout)
        sys.exit(f"FAILED ({done.returncode}): {' '.join(cmd)}")
    return done.stdout


def make_tree(source, tree):
    """The scratch source tree: every top-level entry linked except techniques/, which is copied."""
    os.makedirs(tree)
    for entry in sorted(os.listdir(source)):
        if entry in (".git", "techniques") or entry.startswith("build"):
            continue
        os.symlink(os.path.join(source, entry), os.path.join(tree, entry))
    shutil.copytree(os.path.join(source, "techniques"), os.path.join(tree, "techniques"), symlinks=True)


def add_technique(source, tree):
    """The two edits a new technique makes; returns the files they touched, relative to the tree."""
    shutil.copytree(os.path.join(source, "tests", "technique_template"), os.path.join(tree, "techniques", "throwaway"))
    registry = os.path.join(tree, "techniques", "registry.cpp")
    text = open(registry).read()
    text, includes = re.subn(r'(#include "techniques/technique\.h"\n)',
                             r'\1#include "techniques/throwaway/throwaway_technique.h"\n', text)
    text, entries = re.subn(r"(registry = \{\n)", r"\1        ThrowawayTechnique::info(),\n", text)
    if includes != 1 or entries != 1:
        sys.exit(f"{registry}: expected one '#include \"techniques/technique.h\"' and one 'registry = {{' line")
    open(registry, "w").write(text)
    return ["techniques/throwaway/", "techniques/registry.cpp"]


def main():
    source, scratch = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    shutil.rmtree(scratch, ignore_errors=True)
    tree, build = os.path.join(scratch, "src"), os.path.join(scratch, "build")
    make_tree(source, tree)
    print("edits:", ", ".join(add_technique(source, tree)))

    configure = ["cmake", "-S", tree, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release", "-DBUILD_TESTING=OFF"]
    if shutil.which("ccache"):
        configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
    run(configure)
    # Only what the new technique adds: its object library, its shader and the registry's object.
    targets = run(["ninja", "-C", build, "-t", "targets", "all"])
    wanted = ["hybridlab_technique_throwaway", "shaders/throwaway_fill.comp.inc"]
    registry_object = [line.split(":")[0] for line in targets.splitlines() if line.split(":")[0].endswith("registry.cpp.o")]
    if len(registry_object) != 1:
        sys.exit("no registry.cpp object in the scratch build")
    for target in wanted[:1]:
        if not re.search(rf"^{re.escape(target)}:", targets, re.M):
            sys.exit(f"the scratch build has no target {target}: the technique folder was not found")
    run(["ninja", "-C", build] + wanted + registry_object)

    embedded = open(os.path.join(build, "embedded_shaders.cpp")).read()
    if '{"throwaway_fill.comp", ' not in embedded:
        sys.exit("throwaway_fill.comp is not in the embedded shader table")
    print("OK: techniques/throwaway/ and one registry line built; its shader is embedded")
    shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
