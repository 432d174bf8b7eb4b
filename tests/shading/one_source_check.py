#!/usr/bin/python3
"""The physics in common/shading is written once (common/shading/shading_language.h): no copy of it.

A function or struct that a shared header defines (SHARED_FUNCTION, BACKEND_FUNCTION, struct) has
that one definition, and the Whitted ray tree's walk (common/shading/whitted_tree.h) is the one walk
of both ray backends. The shared headers: those of common/shading, and any other header with a
SHARED_FUNCTION or BACKEND_FUNCTION (a technique's per-texel shading, written once for its Embree
path and its ray-generation shader). Exit status 1, one line a problem, when
  - a shader (GLSL: .glsl, .vert, .frag, .comp, .rgen, .rchit, .rmiss, .rahit, .rint) defines a
    function or struct of that name,
  - a C++ source outside common/shading defines a function of that name whose body calls neither
    shading_language::NAME nor another overload of NAME (an overload that hands the one definition
    the scene's C++ records is fine; a second body of the physics is not).
The check runs first on a scratch tree with known problems and must find exactly those.

usage: one_source_check.py SOURCE_DIR
"""
import os
import re
import sys
import tempfile

SHARED_DIR = os.path.join("common", "shading")
SHADER_EXTENSIONS = {".glsl", ".vert", ".frag", ".comp", ".rgen", ".rchit", ".rmiss", ".rahit", ".rint"}
CPP_EXTENSIONS = {".h", ".hpp", ".cpp"}
SKIPPED_DIRS = {".git", "node_modules", "__pycache__"}
SHARED_FUNCTION = re.compile(r"\b(?:SHARED|BACKEND)_FUNCTION\s+(?:\w+\s+)+(\w+)\s*\(")
# A header outside common/shading written in the shared language: one that defines a function so.
SHARED_HEADER = re.compile(r"^(?:SHARED|BACKEND)_FUNCTION\b", re.MULTILINE)
# The files that give the walk of whitted_tree.h a backend: the Embree one (the walk's caller, then
# the backend's class) and the device's.
BACKENDS = [["common/raytrace/whitted_tracer.cpp", "common/raytrace/embree_tree_backend.h"],
            ["common/device_rays/shaders/device_whitted_tree.glsl"]]
# A radiance ray traced: Embree's closest hit, the device's radiance ray type.
RADIANCE_RAY = re.compile(r"\.intersect\w*\s*\(|traceRayEXT\s*\([^;]*kRadianceRay")
STRUCT = re.compile(r"^\s*struct\s+(\w+)\s*\{", re.MULTILINE)
# A definition: a return type (a word, possibly qualified or templated), the name, a parameter list
# without braces or semicolons, then optional qualifiers and the body's brace.
DEFINITION = re.compile(r"^[ \t]*(?:(?:inline|static|constexpr|\[\[[^\]]*\]\])\s+)*[\w:<>]+[ \t]*[&*]?[ \t]+(?:\w+::)*(\w+)\s*"
                        r"\(([^;{}()]*(?:\([^;{}()]*\)[^;{}()]*)*)\)\s*(?:const\s*)?(?:noexcept\s*)?\{", re.MULTILINE)


def shared_headers(root):
    """The shared headers (relative paths): common/shading's, and the others written in its language."""
    headers = []
    for path in source_files(root):
        relative = os.path.relpath(path, root)
        if not relative.endswith(".h"):
            continue
        if relative.startswith(SHARED_DIR + os.sep) or SHARED_HEADER.search(open(path, encoding="utf-8", errors="replace").read()):
            headers.append(relative)
    return headers


def shared_names(root):
    """The functions and structs the shared headers define: name -> the header."""
    functions, structs = {}, {}
    for relative in shared_headers(root):
        text = open(os.path.join(root, relative), encoding="utf-8").read()
        for name in SHARED_FUNCTION.findall(text):
            functions.setdefault(name, relative)
        for name in STRUCT.findall(text):
            structs.setdefault(name, relative)
    return functions, structs


def body_at(text, open_brace):
    """The text of the braced block that starts at open_brace."""
    depth = 0
    for i in range(open_brace, len(text)):
        if text[i] == "{":
            depth += 1
        elif text[i] == "}":
            depth -= 1
            if depth == 0:
                return text[open_brace:i + 1]
    return text[open_brace:]


def source_files(root):
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in SKIPPED_DIRS and not d.startswith("build")
                         and not os.path.exists(os.path.join(folder, d, "CMakeCache.txt")))
        for name in sorted(files):
            yield os.path.join(folder, name)


def problems(root):
    functions, structs = shared_names(root)
    shared = set(shared_headers(root))
    found = []
    if not functions:
        return [f"{SHARED_DIR}: no SHARED_FUNCTION found (has the convention changed?)"]
    for path in source_files(root):
        relative = os.path.relpath(path, root)
        extension = os.path.splitext(path)[1]
        if relative in shared or extension not in SHADER_EXTENSIONS | CPP_EXTENSIONS:
            continue
        text = open(path, encoding="utf-8", errors="replace").read()
        line_of = lambda offset: text.count("\n", 0, offset) + 1
        for match in DEFINITION.finditer(text):
            name = match.group(1)
            if name not in functions:
                continue
            if extension in SHADER_EXTENSIONS:
                found.append(f"{relative}:{line_of(match.start(1))}: defines {name}(), which {functions[name]} defines once for "
                             "C++ and GLSL: include it instead")
            elif not re.search(rf"\b{name}\s*\(", body_at(text, match.end() - 1)):
                found.append(f"{relative}:{line_of(match.start(1))}: defines {name}() without calling shading_language::{name}() "
                             f"(the one definition in {functions[name]}) or an overload that does")
        if extension in SHADER_EXTENSIONS:
            for match in STRUCT.finditer(text):
                if match.group(1) in structs:
                    found.append(f"{relative}:{line_of(match.start(1))}: defines struct {match.group(1)}, which "
                                 f"{structs[match.group(1)]} defines once for C++ and GLSL")
    for files in BACKENDS:
        texts = {}
        for relative in files:
            path = os.path.join(root, relative)
            if not os.path.exists(path):
                found.append(f"{relative}: missing (a ray backend of {SHARED_DIR}/whitted_tree.h)")
                continue
            texts[relative] = open(path, encoding="utf-8", errors="replace").read()
        if texts and not any(re.search(r"\btraceTree\s*\(", text) for text in texts.values()):
            found.append(f"{files[0]}: does not call traceTree() ({SHARED_DIR}/whitted_tree.h, the one walk of the ray tree)")
        for relative, text in texts.items():
            found += backend_problems(relative, text)
    return found


def backend_problems(relative, text):
    """A backend leaves the walking to the one walk: it spawns no secondary ray, and only its traceRay() traces a radiance ray."""
    line_of = lambda offset: text.count("\n", 0, offset) + 1
    found = []
    for match in DEFINITION.finditer(text):
        body = body_at(text, match.end() - 1)
        if re.search(r"\boffsetRayOrigin\s*\(", body):
            found.append(f"{relative}:{line_of(match.start(1))}: {match.group(1)}() spawns a secondary ray: the walk of "
                         f"{SHARED_DIR}/whitted_tree.h does that for both backends")
        if match.group(1) != "traceRay" and RADIANCE_RAY.search(body):
            found.append(f"{relative}:{line_of(match.start(1))}: {match.group(1)}() traces a radiance ray: only the backend's "
                         f"traceRay() may, for the walk of {SHARED_DIR}/whitted_tree.h")
    return found


def self_check():
    """The check on a scratch tree: it must find exactly the planted copies."""
    files = {
        "common/shading/shading_language.h": "#define SHARED_FUNCTION inline\n",
        "common/shading/physics.h": ("struct Sample {\n    vec3 v;\n};\n"
                                     "SHARED_FUNCTION vec3 twice(vec3 v) { return 2.0f * v; }\n"
                                     "SHARED_FUNCTION float half(float x,\n                         float y) { return 0.5f * x; }\n"),
        "common/raster/shaders/copy.glsl": "vec3 twice(vec3 v) {\n    return v + v;\n}\nvec3 other(vec3 v) { return v; }\n",
        "common/raster/shaders/struct_copy.rgen": "struct Sample {\n    vec3 v;\n};\nvoid main() { twice(vec3(1.0)); }\n",
        "common/raytrace/adapter.h": ("inline glm::vec3 twice(const Thing& t) { return shading_language::twice(t.v); }\n"
                                      "glm::vec3 twice(const Other& o) { return twice(o.thing); }\n"),
        "common/raytrace/copy.cpp": "float half(float x, float y) {\n    return x * 0.5f;\n}\nfloat g() { return half(1.0f, 2.0f); }\n",
        "common/shading/walk.h": "BACKEND_FUNCTION vec3 traceTree(BACKEND_PARAM PendingRay root) { return vec3(0.0f); }\n",
        "common/device_rays/shaders/walk_copy.glsl": "vec3 traceTree(PendingRay root) {\n    return vec3(0.0);\n}\n",
        # A technique's shared header, and copies of its rule in a shader and in C++.
        "techniques/t/shaders/texel.h": "BACKEND_FUNCTION vec3 shadeTexel(BACKEND_PARAM vec3 c) { return c; }\nSHARED_FUNCTION bool rule(vec4 o) { return o.x > 0.0f; }\n",
        "techniques/t/shaders/t.rgen": "bool rule(vec4 o) {\n    return o.x > 0.0;\n}\nvoid main() { shadeTexel(vec3(rule(vec4(1.0)))); }\n",
        "techniques/t/t.cpp": "bool other() { return true; }\nbool rule(const glm::vec4& o) { return o.x > 0.0f; }\n",
        BACKENDS[0][1]: "    float traceRay(glm::vec3 o, glm::vec3 d) { return rays.intersect({o, d}, hit) ? hit.t : -1.0f; }\n",
        BACKENDS[0][0]: ("glm::vec3 Tracer::radiance(const Ray& r) { return traceTree(backend, r); }\n"
                         "glm::vec3 Tracer::shade(const Hit& h) {\n    return radiance({offsetRayOrigin(h.p, h.n), h.d});\n}\n"),
        BACKENDS[1][0]: ("float traceRay(vec3 o, vec3 d) {\n    traceRayEXT(topLevel, 0u, 0xFF, kRadianceRay, 0, kRadianceRay, o, 0.0, d, 1e38, 0);\n"
                           "    return hit.t;\n}\n"
                           "vec3 walk(vec3 o, vec3 d) {\n    traceRayEXT(topLevel, 0u, 0xFF, kRadianceRay, 0, kRadianceRay, o, 0.0, d, 1e38, 0);\n"
                           "    return vec3(hit.t);\n}\n"),
    }
    expected = ["common/device_rays/shaders/device_whitted_tree.glsl: does not call traceTree()",
                "common/device_rays/shaders/device_whitted_tree.glsl:5: walk() traces a radiance ray",
                "common/device_rays/shaders/walk_copy.glsl:1: defines traceTree()",
                "common/raster/shaders/copy.glsl:1: defines twice()",
                "common/raster/shaders/struct_copy.rgen:1: defines struct Sample",
                "common/raytrace/copy.cpp:1: defines half() without",
                "common/raytrace/whitted_tracer.cpp:2: shade() spawns a secondary ray",
                "techniques/t/shaders/t.rgen:1: defines rule()",
                "techniques/t/t.cpp:2: defines rule() without"]
    with tempfile.TemporaryDirectory() as root:
        for relative, text in files.items():
            path = os.path.join(root, relative)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
        found = sorted(problems(root))
    if len(found) != len(expected) or not all(f.startswith(e) for f, e in zip(found, expected)):
        print("one_source_check.py: the self-check on a scratch tree found", found, "expected", expected, file=sys.stderr)
        return False
    return True


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    if not self_check():
        return 1
    root = sys.argv[1]
    found = problems(root)
    for line in found:
        print(line)
    functions, structs = shared_names(root)
    print(f"{len(functions)} functions and {len(structs)} structs of {len(shared_headers(root))} shared headers, each defined once: "
          f"{'no' if not found else len(found)} copies found")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
