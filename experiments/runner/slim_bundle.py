#!/usr/bin/env python3
"""Make a bundle of `hybridlab bundle` small enough to copy to a GPU machine: every library the
program never calls is replaced by a stub of a few kilobytes.

    /usr/bin/python3 experiments/runner/slim_bundle.py BUNDLE_DIR

Most of a bundle's 400 MB are libraries OpenImageIO links for formats no experiment reads (GDAL,
FFmpeg, OpenVDB, DCMTK, ICU's data, ...). The dynamic linker loads them all at start-up, and with
their symbols bound at load (BIND_NOW) every one must be found. A stub has the library's SONAME,
its symbol-version nodes and every symbol it exports: functions that print the library and the
symbol's index on stderr and return a pointer to zeroed memory (an empty string or structure, as
OpenImageIO's start-up queries of format libraries' versions expect), and objects of the same
size in zero-filled memory. A slim bundle's lib/ is about 120 MB, 25 MB as a .tar.xz, and renders the
same images (tests/runner/slim_bundle_test.py).

Kept whole: the program's own dependencies (its DT_NEEDED), KEPT below, and what a Vulkan driver
loads from the bundle's folder. Stubbing needs readelf (binutils) and gcc, as on the build machine.
"""
import concurrent.futures
import os
import re
import subprocess
import sys
import tempfile

# Libraries whose code runs: image formats the experiments read and write (OpenImageIO's EXR, PNG,
# JPEG, TIFF, WebP, GIF and HEIF plugins with their codecs; libheif also at start-up), OpenColorIO
# and its parsers, Boost, and what Mesa's lavapipe and the X/Wayland-free loader paths load.
KEPT = re.compile(r"^lib(heif|OpenImageIO|OpenImageIO_Util|OpenEXR|OpenEXRCore|OpenEXRUtil|Imath|Iex|IlmThread|"
                  r"OpenColorIO|opencv_core|opencv_imgproc|opencv_imgcodecs|png16|z|jpeg|deflate|zstd|lzma|bz2|vulkan|"
                  r"gomp|boost_.*|fmt|yaml-cpp|pugixml|expat|tiff|webp|webpmux|webpdemux|sharpyuv|gif|Lerc|jbig|"
                  r"pystring|minizip|xcb|xcb-.*|X11|X11-xcb|Xau|Xdmcp|Xext|Xrender|Xfixes|drm|ffi|xml2|bsd|md|"
                  r"wayland-.*|xshmfence|Xxf86vm|udev|gcc_s|sensors|elf|LLVM.*|tinfo|edit|tbb|tbbmalloc)[-_0-9.]*\.so")

# The stub's one function: report the call and return zeroed memory.
STUB_C = r"""
#include <string.h>
#include <unistd.h>
__attribute__((visibility("hidden"))) void hl_stub_called(int symbol, const char* library) {
    const char* a = "hybridlab bundle: called a stubbed library: ";
    char digits[16], line[40];
    int n = 0, m = 0;
    write(2, a, strlen(a));
    write(2, library, strlen(library));
    line[n++] = ' ';
    line[n++] = '#';
    do { digits[m++] = (char)('0' + symbol % 10); symbol /= 10; } while (symbol);
    while (m) line[n++] = digits[--m];
    line[n++] = '\n';
    write(2, line, n);
}
"""


def readelf(*args):
    return subprocess.run(["readelf", *args], check=True, capture_output=True, text=True).stdout


def version_nodes(path):
    """The library's symbol-version definitions, the base one (its SONAME) left out."""
    text = readelf("-V", "-W", path).split("Version definition section")
    if len(text) < 2:
        return []
    body = re.split(r"Version (?:needs|symbols) section", text[1])[0]
    return [m.group(2) for m in re.finditer(r"Flags: (\S+)\s+Index: \d+\s+Cnt: \d+\s+Name: (\S+)", body) if m.group(1) != "BASE"]


def exported_symbols(path, soname):
    """(name, version or None, default version?, type, size) of every symbol the library defines."""
    for line in readelf("--dyn-syms", "-W", path).splitlines():
        f = line.split()
        if len(f) < 8 or not f[0].endswith(":") or f[6] in ("UND", "ABS") or f[4] not in ("GLOBAL", "WEAK", "UNIQUE"):
            continue
        name, version, default = f[7], None, True
        if "@@" in name:
            name, version = name.split("@@")
        elif "@" in name:
            (name, version), default = name.split("@"), False
        yield name, (None if version == soname else version), default, f[3], int(f[2], 0), f[4] == "WEAK"


def stub_assembly(path, soname):
    lines = [".text", "hl_fail: subq $8, %rsp; leaq hl_library(%rip), %rsi; call hl_stub_called@PLT; addq $8, %rsp",
             "leaq hl_zero(%rip), %rax; ret", ".local hl_zero", ".comm hl_zero,65536,64"]
    by_node = {}
    for i, (name, version, default, kind, size, weak) in enumerate(exported_symbols(path, soname)):
        label = f"s{i}"
        if kind in ("OBJECT", "TLS", "COMMON"):
            section = '.section .tbss,"awT",@nobits' if kind == "TLS" else ".bss"
            lines += [section, ".balign 16", f"{label}: .zero {max(size, 1)}",
                      f".type {label},{'@tls_object' if kind == 'TLS' else '@object'}", f".size {label},{max(size, 1)}"]
        else:
            lines += [".text", f".type {label},@function", f"{label}: movl ${i}, %edi; jmp hl_fail"]
        if version is not None and not default:
            lines += [f'.symver {label}, "{name}@{version}"', f".globl {label}"]
            continue
        lines += [f'{".weak" if weak else ".globl"} "{name}"', f'.set "{name}", {label}']
        if version is not None:
            by_node.setdefault(version, []).append(name)
    lines += ['.section .note.GNU-stack,"",@progbits', ".section .rodata", f'hl_library: .asciz "{soname}"']
    return "\n".join(lines) + "\n", by_node


def write_stub(path):
    """Replaces the library at `path` by its stub."""
    soname_match = re.search(r"\(SONAME\)\s+Library soname: \[(.*?)\]", readelf("-d", "-W", path))
    soname = soname_match.group(1) if soname_match else os.path.basename(path)
    assembly, by_node = stub_assembly(path, soname)
    with tempfile.TemporaryDirectory() as tmp:
        asm, c, script, out = (os.path.join(tmp, n) for n in ("stub.s", "stub.c", "versions.map", "stub.so"))
        open(asm, "w").write(assembly)
        open(c, "w").write(STUB_C)
        command = ["gcc", "-shared", "-fPIC", "-o", out, asm, c, "-Wl,-soname," + soname, "-Wl,--no-undefined"]
        nodes = version_nodes(path)
        if nodes:
            previous, text = None, []
            for node in nodes:
                names = " ".join(f'"{n}";' for n in by_node.get(node, []))
                text.append(f"{node} {{ {'global: ' + names if names else ''} }}{' ' + previous if previous else ''};")
                previous = node
            open(script, "w").write("\n".join(text) + "\n")
            command.append("-Wl,--version-script=" + script)
        subprocess.run(command, check=True, capture_output=True, text=True)
        subprocess.run(["strip", "--strip-unneeded", out], check=True)
        os.replace(out, path)


def main():
    if len(sys.argv) != 2 or not os.path.isfile(os.path.join(sys.argv[1], "bin", "hybridlab")):
        sys.stderr.write("usage: slim_bundle.py BUNDLE_DIR (a folder written by `hybridlab bundle`)\n")
        return 2
    bundle = sys.argv[1]
    needed = set(re.findall(r"\(NEEDED\)\s+Shared library: \[(.*?)\]", readelf("-d", "-W", os.path.join(bundle, "bin", "hybridlab"))))
    lib = os.path.join(bundle, "lib")
    names = sorted(os.listdir(lib))
    stubbed = [n for n in names if n not in needed and not KEPT.match(n)]
    before = sum(os.path.getsize(os.path.join(lib, n)) for n in names)
    with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 1) as pool:
        list(pool.map(write_stub, [os.path.join(lib, n) for n in stubbed]))
    after = sum(os.path.getsize(os.path.join(lib, n)) for n in names)
    with open(os.path.join(bundle, "README.txt"), "a") as readme:
        readme.write(f"\nSlimmed by experiments/runner/slim_bundle.py: {len(stubbed)} of {len(names)} libraries are stubs "
                     "(a call prints 'hybridlab bundle: called a stubbed library' and returns zeroed memory):\n")
        readme.writelines(f"    {n}\n" for n in stubbed)
    print(f"slimmed {bundle}: {len(stubbed)} of {len(names)} libraries stubbed, lib/ {before / 1e6:.0f} MB -> {after / 1e6:.0f} MB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
