"""The side-by-side technique viewer of a report: viewer.html with viewer/ beside it (script,
styles, manifest of the result set, pixel scripts). Works from the file system and from any static
web server.

The viewer's source is ES modules in report/viewer/. Browsers refuse module scripts (and
fetch()) from file:// pages, so the modules are joined here into one classic script, each module
in its own function scope, and the manifest is written both as manifest.json and as manifest.js (a
classic script that sets window.HYBRIDLAB_MANIFEST).

The PNGs are display images (sRGB, clamped to [0, 1]); for exposure, other display transforms and
the inspector's linear values, each run's and reference's EXR is also written as a classic script
holding its linear RGB as half floats (viewer/linear/N.js), loaded when first needed."""
import base64
import functools
import json
import os
import re
import shutil
import tomllib

import matplotlib

import exr
import results as rs

VIEWER_SOURCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "viewer")
ENTRY_MODULE = "main.js"

IMPORT = re.compile(r"^import\s*\{([^}]*)\}\s*from\s*'\./([\w.]+\.js)';\s*$", re.M)
EXPORT = re.compile(r"^export\s+(?:async\s+)?(?:function\*?|const|let|class)\s+(\w+)", re.M)


class BundleError(Exception):
    pass


def bundle(source_dir, entry):
    """The modules reachable from `entry` as one classic script: every module becomes a function
    whose result holds its exports, run after the modules it imports."""
    order, seen = [], set()

    def visit(name, chain):
        if name in chain:
            raise BundleError("viewer modules import each other in a cycle: %s" % " -> ".join(chain + [name]))
        if name in seen:
            return
        path = os.path.join(source_dir, name)
        if not os.path.exists(path):
            raise BundleError("%s imports %s, which does not exist" % (chain[-1] if chain else "viewer", name))
        with open(path) as f:
            text = f.read()
        for _, dep in IMPORT.findall(text):
            visit(dep, chain + [name])
        seen.add(name)
        order.append((name, text))

    visit(entry, [])
    var = lambda name: "module_" + re.sub(r"\W", "_", name)  # noqa: E731
    parts = ["// Built by report/viewer.py from report/viewer/*.js: do not edit.", "'use strict';"]
    for name, text in order:
        if re.search(r"^\s*import\b", IMPORT.sub("", text), re.M):
            raise BundleError("%s: only `import { a, b } from './module.js';` imports are understood" % name)
        exports = EXPORT.findall(text)
        body = IMPORT.sub(lambda m: "const {%s} = %s;" % (m.group(1), var(m.group(2))), text)
        body = EXPORT.sub(lambda m: m.group(0)[len("export "):], body)
        if re.search(r"^\s*export\b", body, re.M):
            raise BundleError("%s: only `export function|const|let|class NAME` exports are understood" % name)
        parts.append("const %s = (() => {\n%s\nreturn { %s };\n})();" % (var(name), body, ", ".join(exports)))
    return "\n".join(parts) + "\n"


def colour_table(name):
    cmap = matplotlib.colormaps[name].resampled(256)
    return [[round(255 * c) for c in cmap(i)[:3]] for i in range(256)]


def run_entry(r, out_dir, result_dir):
    """One run as the viewer reads it: paths relative to the report folder, medians in ms."""
    rel = functools.partial(rs.result_link, out_dir, result_dir)
    maps = {}
    if r["images"].get("maps"):
        for name, m in r["metrics"].get("maps", {}).items():
            maps[name] = {"file": rel(r["images"]["maps"] + "/" + m["file"]), "colormap": m["colormap"], "range": m["range"]}
    return {
        "id": r["id"], "index": r["index"], "scene": r["scene"], "size": rs.resolution(r), "width": r["width"],
        "height": r["height"], "view": r["view"], "frame": r["frame"], "technique": r["technique"], "label": r["label"],
        "variant": rs.variant(r), "exr": rel(r["images"]["exr"]), "reference_exr": rel(r["reference"]["exr"]),
        "parameters_text": r["parameters_text"], "frame_ms": r["frame_ms"]["median"],
        "stages": rs.stages(r),
        "metrics": {"ssim": rs.metric(r, "whole", "ssim"), "flip": rs.metric(r, "whole", "flip"),
                    "flip_hdr": rs.metric(r, "whole", "flip_hdr"), "psnr": rs.metric(r, "whole", "psnr"),
                    "masked_ssim": rs.metric(r, "masked", "ssim"), "masked_flip": rs.metric(r, "masked", "flip"),
                    "masked_flip_hdr": rs.metric(r, "masked", "flip_hdr"),
                    "temporal": r.get("temporal_error")},
        "image": rel(r["images"]["png"]), "reference": rel(r["reference"]["png"]), "reference_ms": r["reference"]["frame_ms"],
        "maps": maps, "debug": {k: rel(v) for k, v in r["images"].get("debug", {}).items()},
    }


def shown_files(entry):
    yield entry["image"]
    yield entry["reference"]
    for m in entry["maps"].values():
        yield m["file"]
    yield from entry["debug"].values()


def write_pixel_scripts(runs, out_dir):
    """Each PNG the viewer shows as a script that hands its data: URL to the inspector."""
    scripts = {}
    os.makedirs(os.path.join(out_dir, "viewer", "pixels"), exist_ok=True)
    for entry in runs:
        for f in shown_files(entry):
            if f in scripts:
                continue
            with open(os.path.join(out_dir, f), "rb") as png:
                data = "data:image/png;base64," + base64.b64encode(png.read()).decode()
            script = "viewer/pixels/%d.js" % len(scripts)
            with open(os.path.join(out_dir, script), "w") as s:
                s.write("hybridlabPixels(%s, %s);\n" % (json.dumps(f), json.dumps(data)))
            scripts[f] = script
    return scripts


def write_linear_scripts(runs, out_dir):
    """Each shown image's linear RGB (from its EXR) as a script that hands it to the viewer:
    hybridlabLinear(png file, width, height, base64 of little-endian half floats, RGB by row).
    Keyed by the PNG the viewer shows for it."""
    scripts = {}
    os.makedirs(os.path.join(out_dir, "viewer", "linear"), exist_ok=True)
    for entry in runs:
        for png, exr_file in ((entry["image"], entry["exr"]), (entry["reference"], entry["reference_exr"])):
            if png in scripts:
                continue
            pixels = exr.rgb(os.path.join(out_dir, exr_file))
            data = base64.b64encode(pixels.astype("<f2").tobytes()).decode()
            script = "viewer/linear/%d.js" % len(scripts)
            with open(os.path.join(out_dir, script), "w") as s:
                s.write("hybridlabLinear(%s, %d, %d, %s);\n" % (json.dumps(png), pixels.shape[1], pixels.shape[0], json.dumps(data)))
            scripts[png] = script
    return scripts


def reference_parameters(result_dir):
    """The reference's parameters from the config the result set was run with, as `k=v k=v`."""
    path = os.path.join(result_dir, "config.toml")
    if not os.path.exists(path):
        return ""
    with open(path, "rb") as f:
        params = tomllib.load(f).get("reference", {}).get("params", {})
    return " ".join("%s=%s" % (k, json.dumps(v) if not isinstance(v, str) else v) for k, v in sorted(params.items()))


def write_viewer(records, out_dir, result_dir, title, not_applicable=None):
    """viewer.html and viewer/ in `out_dir` for the runs in `records` (results.json);
    `not_applicable`: {(scene, size, setting name): why} for the settings the verdict left out."""
    runs = [run_entry(r, out_dir, result_dir) for r in records]
    for entry in runs:
        entry["not_applicable"] = (not_applicable or {}).get((entry["scene"], entry["size"], entry["variant"]))
    manifest = {
        "title": title,
        "reference_parameters": reference_parameters(result_dir),
        "runs": runs,
        # The error maps' colour tables (OpenCV takes its viridis and magma from matplotlib), for
        # the legends and for reading a map's value back from its colour.
        "colormaps": {name: colour_table(name) for name in sorted({m["colormap"] for e in runs for m in e["maps"].values()})},
        "pixel_scripts": write_pixel_scripts(runs, out_dir),
        "linear_scripts": write_linear_scripts(runs, out_dir),
    }
    viewer_dir = os.path.join(out_dir, "viewer")
    text = json.dumps(manifest, separators=(",", ":"))
    with open(os.path.join(viewer_dir, "manifest.json"), "w") as f:
        f.write(text + "\n")
    with open(os.path.join(viewer_dir, "manifest.js"), "w") as f:
        f.write("window.HYBRIDLAB_MANIFEST = %s;\n" % text)
    with open(os.path.join(viewer_dir, "viewer.js"), "w") as f:
        f.write(bundle(VIEWER_SOURCE, ENTRY_MODULE))
    shutil.copyfile(os.path.join(VIEWER_SOURCE, "viewer.css"), os.path.join(viewer_dir, "viewer.css"))
    shutil.copyfile(os.path.join(VIEWER_SOURCE, "viewer.html"), os.path.join(out_dir, "viewer.html"))
    return os.path.join(out_dir, "viewer.html")


def link(run_id, from_dir=""):
    """The viewer opened on one run, from a page in `from_dir` (relative to the report folder)."""
    return os.path.join(os.path.relpath(".", from_dir or "."), "viewer.html").removeprefix("./") + "#run=" + run_id
