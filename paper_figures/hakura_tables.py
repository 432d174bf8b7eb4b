#!/usr/bin/python3
"""Hakura & Snyder 2001 tables from a result set of experiments/configs/hakura2001.toml.

    /usr/bin/python3 paper_figures/hakura_tables.py RESULT_DIR [--out FILE.md]

Results table (teapot-lens, the scene camera): per technique the paper's stages (ray tracing at
vertices, texture-coordinate generation, tessellation, other including rendering), the total frame
time, the rays, vertices and triangles after tessellation, SSIM and FLIP on the lens pixels against
uniformly sampled ray tracing with the two-term model, and the reduction factors in time and rays
against it (the paper: 25-45x in time, 6-10.8x in rays). Figure 8 as numbers: SSIM and FLIP at a
views between viewpoint samples (circle frames 4, 12, 20) and above their plane (above frames
4, 12, 20), each and their means over each path's frames, multi-layer against single-layer, and
the temporal error along the circling path. Figure 9 as
numbers: FLIP on the lens pixels with and without disocclusion prevention along em-disocclusion's
approach. Times are medians over a run's repeats; the time reduction is "25.1x (24.0-26.3)", the
median and 95% interval of the per-round ratios, where the records hold the runner's rounds
(timing.py), else the ratio of the medians. Entries are found by label, as the config names
them (two-term-rt, lem-tau3, lem-tau5, lem-single, lem-no-prevention; lem-display and
lem-display-single, the bake at the display's resolution, where present). From a result set of
experiments/configs/hakura2001_em_size.toml, the EM resolution table: SSIM and FLIP on the lens
pixels of lem-display (EM 128 texels a face), lem-display-256 and lem-display-512-3vp at each view
and size. Under the tables, teapot-lens beside what the paper says of its scene (paper_scenes.py)."""
import statistics

import paper_scenes
import report_modules  # noqa: F401  (puts report/ on sys.path)
import results
import timing

REFERENCE = "two-term-rt"
# The paper's stages; "other" is every other stage of the frame (rendering included).
STAGES = [("trace.lens_vertices", "ray tracing at vertices"), ("lens.texture_coordinates", "texture coordinates"),
          ("lens.tessellation", "tessellation")]
# Figure 8's (multi-layer, single-layer) pairs: the default bake, the bake at the display's resolution,
# and that bake without matching neighbouring viewpoint samples (hakura2001_popping.toml).
SINGLE_LAYER_PAIRS = [("lem-tau3", "lem-single"), ("lem-display", "lem-display-single"),
                      ("lem-display-nv0", "lem-display-single-nv0")]


def find(rows, label, scene, view, frame, size=None):
    """The run of a label at a view (at `size`, "WxH", or the smallest size there)."""
    rs = [r for r in rows if r["label"] == label and r["scene"] == scene and r["view"] == view and r["frame"] == frame
          and (size is None or results.resolution(r) == size)]
    return min(rs, key=lambda r: r["width"] * r["height"]) if rs else None


def lens_metric(r, name):
    return results.metric(r, "masked", name) if r else None


def results_table(rows, size):
    scene = "teapot-lens"
    labels = ["lem-tau3", "lem-tau5"] + [l for l in ("lem-display",) if any(r["label"] == l for r in rows)]
    if not any(find(rows, l, scene, "camera", -1, size) for l in ("lem-tau3", "lem-tau5")):
        return []  # not the paper's experiment (an EM-resolution set, say)
    ref = find(rows, REFERENCE, scene, "camera", -1, size)
    out = ["**Results table** (teapot-lens, scene camera, %s; ms, medians over repeats; quality on the lens pixels "
           "against two-term ray tracing)" % size, "",
           "| | " + " | ".join([REFERENCE] + labels) + " |",
           "|---|" + "---|" * (1 + len(labels))]
    runs = [ref] + [find(rows, l, scene, "camera", -1, size) for l in labels]

    def line(name, fn, spec="%.2f"):
        out.append("| %s | %s |" % (name, " | ".join(results.fmt(fn(r), spec) if r else "-" for r in runs)))

    for key, name in STAGES:
        line(name, lambda r, k=key: results.stage(r, k) if r is not ref else None, "%.1f")
    line("other (incl. rendering)", lambda r: sum(ms for s, ms in results.stages(r).items() if s not in dict(STAGES)) if r is not ref else None,
         "%.1f")
    line("trace (ray tracing every pixel)", lambda r: results.stage(r, "trace") if r is ref else None, "%.1f")
    line("**total**", lambda r: r["frame_ms"]["median"], "%.1f")
    line("rays (lens pixels for ray tracing)",
         lambda r: r["counters"].get("rays_lens_pixels") if r is ref else r["counters"].get("rays_total"), "%.0f")
    line("rays (whole image)", lambda r: r["counters"].get("rays_total"), "%.0f")
    out.append("| triangle intersection tests | %s |" % " | ".join(["not counted (Embree)"] * len(runs)))
    line("vertices after tessellation", lambda r: r["counters"].get("vertices") if r is not ref else None, "%.0f")
    line("triangles after tessellation", lambda r: r["counters"].get("triangles") if r is not ref else None, "%.0f")
    line("lens pixels", lambda r: r["counters"].get("lens_pixels"), "%.0f")
    line("SSIM (lens pixels)", lambda r: lens_metric(r, "ssim") if r is not ref else None, "%.4f")
    line("FLIP (lens pixels)", lambda r: lens_metric(r, "flip") if r is not ref else None, "%.4f")
    if ref:
        t0 = ref["frame_ms"]["median"]
        rays0 = ref["counters"].get("rays_lens_pixels")
        line("**time reduction** (paper 25-45x)",
             lambda r: timing.speedup_cell([r], [ref], "%.1f" % (t0 / r["frame_ms"]["median"]), "%.1f") if r is not ref else None, "%s")
        line("**ray reduction** (paper 6-10.8x)",
             lambda r: rays0 / r["counters"]["rays_total"] if r is not ref and rays0 and r["counters"].get("rays_total") else None, "%.1f")
    return out + [""]


def figure8(rows):
    scene = "teapot-lens"
    labels = [l for pair in SINGLE_LAYER_PAIRS for l in pair if any(r["label"] == l for r in rows)]
    if not any(l.endswith("-single") for l in labels):
        return []  # Figure 8 is multi-layer against single-layer
    out = ["**Figure 8** (teapot-lens; SSIM / FLIP on the lens pixels against two-term ray tracing; -single: one layer, "
           "nearest viewpoint sample)", "", "| view | " + " | ".join(labels) + " |", "|---|" + "---|" * len(labels)]
    def row(name, runs_of):
        cells = []
        for label in labels:
            rs = runs_of(label)
            ssim = [lens_metric(r, "ssim") for r in rs]
            flip = [lens_metric(r, "flip") for r in rs]
            if rs and None not in ssim + flip:
                cells.append("%s / %s" % (results.fmt(statistics.mean(ssim), "%.4f"), results.fmt(statistics.mean(flip), "%.4f")))
            else:
                cells.append("-")
        out.append("| %s | %s |" % (name, " | ".join(cells)))

    for view, where in (("circle", "between viewpoint samples"), ("above", "above their plane")):
        frames = sorted({r["frame"] for r in rows if r["scene"] == scene and r["view"] == view and r["label"] in labels})
        # Frames midway between samples (every 8 degrees, from frame 0), each, then all the path's.
        for frame in (f for f in frames if f % 8 == 4):
            row("%s (%s@%d)" % (where, view, frame), lambda label: [r for r in [find(rows, label, scene, view, frame)] if r])
        if len(frames) > 1:
            row("mean over %s frames %d-%d (%d)" % (view, frames[0], frames[-1], len(frames)),
                lambda label: [r for r in (find(rows, label, scene, view, f) for f in frames) if r])
    row("at a viewpoint sample (camera)", lambda label: [r for r in [find(rows, label, scene, "camera", -1)] if r])
    out += temporal_series(rows, labels, scene, "temporal_error_masked", "lens pixels", SINGLE_LAYER_PAIRS)
    out += temporal_series(rows, labels, scene, "temporal_error", "whole image")
    return out + [""]


def temporal_series(rows, labels, scene, key, region, pairs=()):
    """One row per label: the temporal error `key` into each frame of the circling path; then, for each
    (multi-layer, single-layer) pair of `pairs` present, single minus multi, where popping shows as spikes."""
    series = {}
    for label in labels:
        rs = sorted((r for r in rows if r["label"] == label and r["scene"] == scene and r["view"] == "circle"
                     and r.get(key) is not None), key=lambda r: r["frame"])
        series[label] = {r["frame"]: r[key] for r in rs}
    frames = sorted(set().union(*[set(s) for s in series.values()])) if series else []
    if not frames:
        return []
    out = ["", "Temporal error along the circling path (mean |(T_k - T_k-1) - (R_k - R_k-1)|, %s; viewpoint samples every 8 "
               "frames, the nearest changes at frames 4, 12, 20):" % region, "",
           "| frame | " + " | ".join(str(f) for f in frames) + " | mean | max |", "|---|" + "---|" * (len(frames) + 2)]

    def row(name, s, spec):
        vals = [s.get(f) for f in frames]
        present = [v for v in vals if v is not None]
        out.append("| %s | %s | %s | %s |" % (name, " | ".join(results.fmt(v, spec) for v in vals),
                                               results.fmt(statistics.mean(present), spec) if present else "-",
                                               results.fmt(max(present), spec) if present else "-"))

    for label, s in series.items():
        row(label, s, "%.4f")
    for multi, single in pairs:
        m, s = series.get(multi), series.get(single)
        if m and s:
            row("%s minus %s" % (single, multi), {f: s[f] - m[f] for f in frames if f in s and f in m}, "%+.4f")
    return out


def figure9(rows):
    scene = "em-disocclusion"
    rs = sorted({(r["view"], r["frame"]) for r in rows if r["scene"] == scene})
    if not rs:
        return []
    out = ["**Figure 9** (em-disocclusion; FLIP / SSIM on the lens pixels against two-term ray tracing)", "",
           "| view | with disocclusion prevention (lem-tau3) | without (lem-no-prevention) |", "|---|---|---|"]
    means = {"lem-tau3": [], "lem-no-prevention": []}
    for view, frame in rs:
        cells = []
        for label in means:
            r = find(rows, label, scene, view, frame)
            if r:
                means[label].append(lens_metric(r, "flip"))
            cells.append("%s / %s" % (results.fmt(lens_metric(r, "flip"), "%.4f"), results.fmt(lens_metric(r, "ssim"), "%.4f")) if r else "-")
        out.append("| %s@%d | %s |" % (view, frame, " | ".join(cells)))
    out.append("| mean FLIP | %s |" % " | ".join(results.fmt(statistics.mean(v), "%.4f") if v else "-" for v in means.values()))
    return out + [""]


def em_resolution(rows):
    scene = "teapot-lens"
    labels = [l for l in ("lem-display", "lem-display-256", "lem-display-512-3vp") if any(r["label"] == l for r in rows)]
    if "lem-display-256" not in labels:
        return []
    out = ["**EM resolution** (teapot-lens, display bake; SSIM / FLIP on the lens pixels against two-term ray tracing)", "",
           "| view | " + " | ".join(labels) + " |", "|---|" + "---|" * len(labels)]
    views = sorted({(results.resolution(r), r["view"], r["frame"]) for r in rows if r["scene"] == scene and r["label"] in labels},
                   key=lambda v: (int(v[0].split("x")[0]), v[1], v[2]))
    for size, view, frame in views:
        runs = [find(rows, label, scene, view, frame, size) for label in labels]
        cells = ["%s / %s" % (results.fmt(lens_metric(r, "ssim"), "%.4f"), results.fmt(lens_metric(r, "flip"), "%.4f")) if r else "-"
                 for r in runs]
        out.append("| %s %s | %s |" % (size, view if frame < 0 else "%s@%d" % (view, frame), " | ".join(cells)))
    return out + [""]


def main():
    a, rows = results.table_script(__doc__, "hakura_tables")
    sizes = sorted({results.resolution(r) for r in rows if r["scene"] == "teapot-lens" and r["view"] == "camera"},
                   key=lambda s: int(s.split("x")[0]))
    tables = [line for size in sizes for line in results_table(rows, size)]
    results.write_table(tables + figure8(rows) + figure9(rows) + em_resolution(rows) + paper_scenes.scene_count_lines(rows, "hakura2001"),
                        a.out, results.device_line(a.result_dir, rows))


if __name__ == "__main__":
    main()
