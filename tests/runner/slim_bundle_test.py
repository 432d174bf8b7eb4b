#!/usr/bin/env python3
"""experiments/runner/slim_bundle.py: a slimmed bundle is a fraction of the size and renders the
images the program in the build folder renders, with Embree, with the rasterizer and with rays on
the Vulkan device (lavapipe here), from another folder.

    slim_bundle_test.py HYBRIDLAB SOURCE_DIR WORK_DIR"""
import filecmp
import os
import pathlib
import shutil
import subprocess
import sys

RENDERS = [("whitted", []), ("raster", []), ("whitted-vulkan", ["--technique", "whitted", "--param", "rays=vulkan"])]


def main():
    hybridlab, source, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    (work / "elsewhere").mkdir(parents=True)
    bundle = work / "bundle"
    subprocess.run([hybridlab, "bundle", "--out", str(bundle)], check=True, capture_output=True)
    full = sum(f.stat().st_size for f in (bundle / "lib").iterdir())
    slim = subprocess.run(["/usr/bin/python3", str(source / "experiments" / "runner" / "slim_bundle.py"), str(bundle)],
                          capture_output=True, text=True)
    print(slim.stdout.strip(), slim.stderr.strip())
    if slim.returncode != 0:
        return 1
    slimmed = sum(f.stat().st_size for f in (bundle / "lib").iterdir())
    print(f"lib/: {full / 1e6:.0f} MB -> {slimmed / 1e6:.0f} MB")
    failures = []
    if slimmed > 0.4 * full:
        failures.append(f"lib/ is {slimmed / full:.2f} of the full bundle's, expected at most 0.4")
    env = {"PATH": "/usr/bin:/bin", "HOME": str(work), "HYBRIDLAB_VULKAN_DEVICE": "llvmpipe"}
    for name, args in RENDERS:
        technique = args or ["--technique", name]
        common = ["render", "--scene", "whitted-classic", "--width", "32", "--height", "18"] + technique
        ran = subprocess.run([str(bundle / "hybridlab")] + common + ["--out", f"{name}.exr"], cwd=work / "elsewhere", env=env,
                             capture_output=True, text=True, timeout=300)
        direct = subprocess.run([hybridlab] + common + ["--out", str(work / f"{name}-direct.exr")], capture_output=True, text=True,
                                timeout=300)
        same = ran.returncode == 0 and direct.returncode == 0 and filecmp.cmp(work / "elsewhere" / f"{name}.exr",
                                                                              work / f"{name}-direct.exr", shallow=False)
        print(f"{name}: exit {ran.returncode}, {'the same image' if same else 'DIFFERENT'}")
        if not same:
            failures.append(f"{name}: exit {ran.returncode}: {ran.stderr[-800:]}")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
