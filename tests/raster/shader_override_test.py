#!/usr/bin/env python3
"""HYBRIDLAB_SHADER_DIR replaces an embedded shader with DIR/<name>.spv: a ray-generation shader
that writes one colour and traces nothing, put in place of the device Whitted tracer's, gives an
image of that colour and no rays; a file that is not SPIR-V is refused with exit status 2 and its
name; a folder without the shader leaves the embedded one in place.

    shader_override_test.py HYBRIDLAB SHADER_INCLUDE_DIR WORK_DIR

Exit 77 (skipped) without glslc or without a ray-tracing Vulkan device (Mesa 25's lavapipe has one)."""
import os
import pathlib
import re
import shutil
import struct
import subprocess
import sys
import zlib

CONSTANT_RAYGEN = """#version 460
#extension GL_GOOGLE_include_directive : require
#include "device_rays.glsl"
void main() {
    const ivec2 pixel = ivec2(gl_LaunchIDEXT.xy);
    radianceOut[pixel.y * frame.size.x + pixel.x] = vec4(0.25, 0.5, 1.0, 1.0);
}
"""


def png_pixels(path):
    """The RGB(A) 8-bit pixels of a non-interlaced PNG, as rows of byte strings."""
    data = path.read_bytes()
    pos, idat, width, height, channels = 8, b"", 0, 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and colour in (2, 6), (depth, colour)
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride, rows, previous = zlib.decompress(idat), width * channels, [], bytearray(width * channels)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = previous[i], previous[i - channels] if i >= channels else 0
            predictor = {0: 0, 1: a, 2: b, 3: (a + b) // 2,
                         4: min((a, b, c), key=lambda p: (abs(a + b - c - p), (a, b, c).index(p)))}[kind]
            line[i] = (line[i] + predictor) & 0xFF
        rows.append([tuple(line[x * channels:x * channels + 3]) for x in range(width)])
        previous = line
    return rows


def render(hybridlab, out, env):
    return subprocess.run([hybridlab, "render", "--scene", "whitted-classic", "--width", "32", "--height", "18", "--technique", "whitted",
                           "--param", "rays=vulkan", "--out", str(out)], env=env, capture_output=True, text=True, timeout=600)


def primary_rays(stdout):
    match = re.search(r"^rays_primary\s+(\d+)", stdout, re.MULTILINE)
    return int(match.group(1)) if match else None


def main():
    hybridlab, include, work = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
    glslc = shutil.which("glslc")
    if not glslc:
        print("Skipped\nno glslc")
        return 77
    shutil.rmtree(work, ignore_errors=True)
    (work / "constant").mkdir(parents=True)
    (work / "broken").mkdir()
    (work / "empty").mkdir()
    (work / "constant.rgen").write_text(CONSTANT_RAYGEN)
    subprocess.run([glslc, "--target-env=vulkan1.3", "-I", include, "-o", str(work / "constant" / "device_whitted.rgen.spv"),
                    str(work / "constant.rgen")], check=True)
    (work / "broken" / "device_whitted.rgen.spv").write_bytes(b"not")
    env = dict(os.environ, HYBRIDLAB_VULKAN_DEVICE="llvmpipe")

    embedded = render(hybridlab, work / "embedded.png", dict(env, HYBRIDLAB_SHADER_DIR=str(work / "empty")))
    if embedded.returncode != 0 and "ray" in embedded.stderr and "lacks" in embedded.stderr:
        print("Skipped\nno ray-tracing Vulkan device: " + embedded.stderr.strip()[:300])
        return 77
    failures = []
    if embedded.returncode != 0 or primary_rays(embedded.stdout) != 32 * 18:
        failures.append(f"a folder without the shader: exit {embedded.returncode}, primary rays {primary_rays(embedded.stdout)} "
                        f"(expected 576, the embedded tracer's) {embedded.stderr[-300:]}")

    replaced = render(hybridlab, work / "constant.png", dict(env, HYBRIDLAB_SHADER_DIR=str(work / "constant")))
    if replaced.returncode != 0:
        failures.append(f"the constant shader: exit {replaced.returncode} {replaced.stderr[-300:]}")
    else:
        colours = {p for row in png_pixels(work / "constant.png") for p in row}
        rays = primary_rays(replaced.stdout)
        print(f"constant shader: colours {sorted(colours)}, primary rays {rays}")
        # One colour, blue brightest and red darkest; and no rays counted.
        if len(colours) != 1 or not (lambda c: c[0] < c[1] < c[2])(next(iter(colours))) or rays != 0:
            failures.append(f"the constant shader gave colours {sorted(colours)[:4]} and {rays} primary rays")

    broken = render(hybridlab, work / "broken.png", dict(env, HYBRIDLAB_SHADER_DIR=str(work / "broken")))
    print(f"a broken file: exit {broken.returncode}: {broken.stderr.strip()[:200]}")
    if broken.returncode != 2 or "device_whitted.rgen.spv" not in broken.stderr or "SPIR-V" not in broken.stderr:
        failures.append(f"a broken file: exit {broken.returncode}, {broken.stderr[-300:]}")
    if (work / "broken.png").exists() or (work / "broken.exr").exists():
        failures.append("a broken file left an image behind")

    for f in failures:
        print("FAILED: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
