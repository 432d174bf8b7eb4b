#!/usr/bin/python3
"""The tests mirror the source tree (tests/README.md): every test sits in tests/AREA/.

AREA is the source folder of the code a test exercises, found as tests/AREA -> AREA, common/AREA
or experiments/AREA in the source tree (tests/scene -> common/scene, tests/runner ->
experiments/runner, tests/techniques/layered_em -> techniques/layered_em). Besides the areas,
tests/ holds only CMakeLists.txt, README.md and the folders that are not areas: support/ (helpers,
no test cases), repository/ (checks of the tree as a whole), fixtures/, fuzz/, sanitize/ and
technique_template/. Exit status 1, one line a problem, when
  - a file sits at the top of tests/ (say tests/test_foo.cpp, a test added in the old layout),
  - a folder of tests/ is neither an area nor one of those folders,
  - a file in support/ defines a test case (TEST, TEST_F, TEST_P),
  - a C++ source in an area, support/ or repository/ is not compiled by tests/CMakeLists.txt.
The check runs first on a scratch tree with known problems and must find exactly those.

usage: test_layout_check.py SOURCE_DIR
"""
import os
import re
import sys
import tempfile

TOP_FILES = {"CMakeLists.txt", "README.md"}
NOT_AREAS = {"support", "repository", "fixtures", "fuzz", "sanitize", "technique_template"}
# Folders whose C++ files the test executable compiles (fuzz/, sanitize/ and technique_template/
# are built by their own CMake).
COMPILED = NOT_AREAS - {"fixtures", "fuzz", "sanitize", "technique_template"}
SKIPPED_DIRS = {"node_modules", "__pycache__"}
TEST_CASE = re.compile(r"^\s*TEST(_F|_P)?\s*\(", re.MULTILINE)
HOW_TO_PLACE = "AREA = the source folder it exercises (tests/README.md)"


def source_folder(root, area):
    """The source folder that tests/AREA mirrors, or None."""
    for candidate in (area, os.path.join("common", area), os.path.join("experiments", area)):
        if os.path.isdir(os.path.join(root, candidate)):
            return candidate
    return None


def compiled_sources(tests):
    """The sources of add_executable(hybridlab_tests ...) in tests/CMakeLists.txt."""
    text = open(os.path.join(tests, "CMakeLists.txt")).read()
    found = re.search(r"add_executable\(hybridlab_tests\s([^)]*)\)", text)
    return set(found.group(1).split()) if found else set()


def problems(root):
    tests = os.path.join(root, "tests")
    compiled = compiled_sources(tests)
    found = []
    for entry in sorted(os.listdir(tests)):
        if os.path.isfile(os.path.join(tests, entry)) and entry not in TOP_FILES:
            found.append(f"tests/{entry}: a file at the top of tests/; move it to tests/AREA/, {HOW_TO_PLACE}")
    for folder, dirs, files in os.walk(tests):
        dirs[:] = sorted(d for d in dirs if d not in SKIPPED_DIRS and not d.startswith("."))
        rel = os.path.relpath(folder, tests).replace(os.sep, "/")
        if rel == ".":
            continue
        top = rel.split("/")[0]
        if top in NOT_AREAS:
            if top not in COMPILED:
                dirs[:] = []
                continue
        elif files and source_folder(root, rel) is None:
            found.append(f"tests/{rel}/: no source folder {rel}, common/{rel} or experiments/{rel} for it to mirror; "
                         f"{HOW_TO_PLACE}")
        for name in sorted(files):
            path = f"{rel}/{name}"
            if top == "support" and name.endswith((".cpp", ".h")) and TEST_CASE.search(open(os.path.join(folder, name)).read()):
                found.append(f"tests/{path}: defines a test case, and support/ holds helpers only; move it to "
                             f"tests/AREA/, {HOW_TO_PLACE}")
            if name.endswith(".cpp") and path not in compiled:
                found.append(f"tests/{path}: not compiled: add it to add_executable(hybridlab_tests ...) in tests/CMakeLists.txt")
    return found


def self_test():
    """A scratch tree with one problem of each kind, and files in their right places around them."""
    with tempfile.TemporaryDirectory() as root:
        def write(path, text=""):
            os.makedirs(os.path.dirname(os.path.join(root, path)), exist_ok=True)
            open(os.path.join(root, path), "w").write(text)
        for folder in ("common/scene", "experiments/runner", "techniques/whitted", "metrics"):
            os.makedirs(os.path.join(root, folder))
        write("tests/CMakeLists.txt", "add_executable(hybridlab_tests\n  support/test_main.cpp\n  scene/test_mesh.cpp\n"
              "  runner/test_store.cpp\n  techniques/whitted/test_tree.cpp\n  metrics/test_ssim.cpp\n  support/misplaced.cpp)\n")
        for path in ("tests/README.md", "tests/support/test_main.cpp", "tests/support/helper.h", "tests/scene/test_mesh.cpp",
                     "tests/runner/test_store.cpp", "tests/runner/end_to_end.sh", "tests/techniques/whitted/test_tree.cpp",
                     "tests/metrics/test_ssim.cpp", "tests/fuzz/fuzz_scene.cpp", "tests/fixtures/bad/scene.toml",
                     "tests/report/viewer/node_modules/x/test_x.cpp"):
            write(path, "int x;\n")
        write("tests/test_orphan.cpp")
        write("tests/shadows/test_pcf.cpp")
        write("tests/support/misplaced.cpp", "TEST(Misplaced, Case) {}\n")
        write("tests/metrics/test_unlisted.cpp")
        got = [line.split(":")[0] for line in problems(root)]
    expected = ["tests/test_orphan.cpp", "tests/metrics/test_unlisted.cpp", "tests/shadows/",
                "tests/shadows/test_pcf.cpp", "tests/support/misplaced.cpp"]
    if got != expected:
        sys.exit(f"self-test: expected {expected}, found {got}")
    print("self-test passed:", len(expected), "problems found in the scratch tree")


def main():
    if len(sys.argv) != 2 or not os.path.isdir(os.path.join(sys.argv[1], "tests")):
        sys.exit("usage: test_layout_check.py SOURCE_DIR (the folder holding tests/)")
    self_test()  # the check first, on a tree whose problems are known in advance
    found = problems(sys.argv[1])
    for line in found:
        print(line)
    if found:
        sys.exit(f"FAILED: {len(found)} file(s) out of the tests' layout")
    print("every test sits in the area folder of the source it exercises")


if __name__ == "__main__":
    main()
