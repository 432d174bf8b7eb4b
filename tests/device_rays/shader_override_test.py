#!/usr/bin/env python3
"""HYBRIDLAB_SHADER_DIR replaces an embedded shader with DIR/<name>.spv: a ray-generation shader
that writes one colour and traces nothing, put in place of the device Whitted tracer's, gives an
image of exactly that colour and no rays; a file that is not SPIR-V is refused with exit status 2 and its
name; a folder without the shader leaves the embedded one in place.

    shader_override_test.py HYBRIDLAB SHADER_INCLUDE_DIR WORK_DIR

Exit 77 (skipped) without glslc or without a ray-tracing Vulkan device (Mesa 25's lavapipe has one)."""
import json
import os
import pathlib
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "report"))
import images  # noqa: E402  (the report's reader of the runner's images, on OpenImageIO)

CONSTANT_RAYGEN = """#version 460
#extension GL_GOOGLE_include_directive : require
#include "device_rays.glsl"
void main() {
    const ivec2 pixel = ivec2(gl_LaunchIDEXT.xy);
    radianceOut[pixel.y * frame.size.x + pixel.x] = vec4(0.25, 0.5, 1.0, 1.0);
}
"""


def render(hybridlab, out, env):
    return subprocess.run([hybridlab, "render", "--scene", "whitted-classic", "--width", "32", "--height", "18", "--technique", "whitted",
                           "--param", "rays=vulkan", "--out", str(out), "--json"], env=env, capture_output=True, text=True, timeout=600)


def primary_rays(stdout):
    """The frame's rays_primary counter (render --json holds every counter, 0 included)."""
    try:
        return int(json.loads(stdout)["counters"]["rays_primary"])
    except (ValueError, KeyError):
        return None


def main():
    hybridlab, source, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    includes = ["-I", str(source / "common" / "shading"), "-I", str(source / "common" / "raster" / "shaders"),
                "-I", str(source / "common" / "device_rays" / "shaders")]
    glslc = shutil.which("glslc")
    if not glslc:
        print("Skipped\nno glslc")
        return 77
    shutil.rmtree(work, ignore_errors=True)
    (work / "constant").mkdir(parents=True)
    (work / "broken").mkdir()
    (work / "empty").mkdir()
    (work / "constant.rgen").write_text(CONSTANT_RAYGEN)
    subprocess.run([glslc, "--target-env=vulkan1.3", *includes, "-o", str(work / "constant" / "device_whitted.rgen.spv"),
                    str(work / "constant.rgen")], check=True)
    (work / "broken" / "device_whitted.rgen.spv").write_bytes(b"not")
    env = dict(os.environ, HYBRIDLAB_VULKAN_DEVICE="llvmpipe")

    embedded = render(hybridlab, work / "embedded.exr", dict(env, HYBRIDLAB_SHADER_DIR=str(work / "empty")))
    if embedded.returncode != 0 and "ray" in embedded.stderr and "lacks" in embedded.stderr:
        print("Skipped\nno ray-tracing Vulkan device: " + embedded.stderr.strip()[:300])
        return 77
    failures = []
    if embedded.returncode != 0 or primary_rays(embedded.stdout) != 32 * 18:
        failures.append(f"a folder without the shader: exit {embedded.returncode}, primary rays {primary_rays(embedded.stdout)} "
                        f"(expected 576, the embedded tracer's) {embedded.stderr[-300:]}")

    replaced = render(hybridlab, work / "constant.exr", dict(env, HYBRIDLAB_SHADER_DIR=str(work / "constant")))
    if replaced.returncode != 0:
        failures.append(f"the constant shader: exit {replaced.returncode} {replaced.stderr[-300:]}")
    else:
        pixels = images.rgb(str(work / "constant.exr"))
        colours = {c: sorted(set(pixels[:, :, i].ravel().tolist())) for i, c in enumerate(("R", "G", "B"))}
        rays = primary_rays(replaced.stdout)
        print(f"constant shader: values {colours}, primary rays {rays}")
        # Every pixel the shader's colour, and no rays counted.
        if colours != {"R": [0.25], "G": [0.5], "B": [1.0]} or rays != 0:
            failures.append(f"the constant shader gave {colours} and {rays} primary rays")

    broken = render(hybridlab, work / "broken.exr", dict(env, HYBRIDLAB_SHADER_DIR=str(work / "broken")))
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
