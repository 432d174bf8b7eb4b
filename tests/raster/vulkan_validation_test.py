#!/usr/bin/env python3
"""Every technique on Vulkan renders a small frame under the Khronos validation layer without one
validation message and exits cleanly. lavapipe forgives what a GPU's driver does not (a shader
feature the device was not asked for, objects destroyed after the driver's exit handlers); the
layer reports it on any machine.

    vulkan_validation_test.py HYBRIDLAB WORK_DIR

Exit 77 (skipped) where the layer is not installed (setup.sh --tests installs it)."""
import os
import pathlib
import shutil
import subprocess
import sys

LAYER_MANIFESTS = ("/usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json",
                   "/etc/vulkan/explicit_layer.d/VkLayer_khronos_validation.json")

# Each technique on each of its Vulkan paths: the rasterizer's, the ray-cast G-buffer uploaded
# to it, and the ray-tracing device's.
TECHNIQUES = [
    ("raster", "{}"),
    ("layered_em", "{}"),
    ("heuristic_rt", "{ budget = 1000000.0, gbuffer = [\"raster\", \"rays\"] }"),
    ("ssr_fallback", "{ gbuffer = [\"raster\", \"rays\"] }"),
    ("whitted", "{ rays = \"vulkan\" }"),
    ("heuristic_rt", "{ budget = 1000000.0, rays = \"vulkan\", gbuffer = [\"raster\", \"rays\"] }"),
    ("ssr_fallback", "{ rays = \"vulkan\", gbuffer = [\"raster\", \"rays\"] }"),
]


def config():
    lines = ["[experiment]", 'name = "vulkan_validation"', "warmup_frames = 0", "repeats = 1", "",
             "[[scenes]]", 'scene = "whitted-classic"', "resolutions = [[64, 36]]", ""]
    for i, (name, params) in enumerate(TECHNIQUES):
        lines += ["[[techniques]]", f'name = "{name}"', f'label = "{name}-{i}"', f"params = {params}", ""]
    return "\n".join(lines)


def main():
    hybridlab, work = sys.argv[1], pathlib.Path(sys.argv[2])
    if not any(os.path.exists(m) for m in LAYER_MANIFESTS):
        print("Skipped\nthe Khronos validation layer is not installed (setup.sh --tests installs vulkan-validationlayers)")
        return 77
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    (work / "config.toml").write_text(config())
    env = dict(os.environ, HYBRIDLAB_VULKAN_VALIDATION="1", HYBRIDLAB_VULKAN_DEVICE="llvmpipe", HYBRIDLAB_CACHE=str(work / "cache"))
    done = subprocess.run([hybridlab, "run", str(work / "config.toml"), "--out", str(work / "results"), "--quiet"],
                          env=env, capture_output=True, text=True, timeout=1500)
    messages = [line for line in done.stderr.splitlines() if line.startswith("vulkan validation:")]
    for m in messages[:3]:
        print(m[:400])
    runs = len(list((work / "results" / "runs").glob("*.json"))) if (work / "results" / "runs").is_dir() else 0
    print(f"exit status {done.returncode}; {runs} runs recorded; {len(messages)} validation messages")
    if done.returncode != 0:
        print(done.stderr[-1500:])
    return 0 if done.returncode == 0 and not messages and runs == 11 else 1


if __name__ == "__main__":
    sys.exit(main())
