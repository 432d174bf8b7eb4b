#!/usr/bin/python3
"""de Macedo & Rodrigues 2019 Tables I and II from a result set of experiments/configs/macedo2019.toml.

    /usr/bin/python3 paper_figures/macedo_tables.py RESULT_DIR [--out FILE.md]

Table I (rigid: bunnies-falling-N) and Table II (deformable: teapots-deforming-N), one line per N
and technique variant, over the frames of the camera path: the scene's triangle count and its
dynamic triangles (the ray scene's counters: rigid instances moved, deformed meshes refitted), the
frame time mean +/- standard deviation, min and max (each frame's time is the median over the run's
repeats), the process's CPU time a frame (all threads: what the frame costs on a machine shared
with other work), the `bvh_update` stage's mean, and SSIM and FLIP against the `whitted` reference
per frame (mean +/- standard deviation, worst). Below each table: how the frame time, its CPU time
and the `bvh_update` stage grow with the number of dynamic triangles (least-squares slope and
correlation over the table's lines, and the time at the largest N over the time at the smallest),
beside the same for the frame times of the paper's CUDA and OptiX rows; then the scenes' counts
beside the paper's (paper_scenes.py)."""
import os
import re
import statistics
import sys

import paper_scenes
import report_modules  # noqa: F401  (puts report/ on sys.path)
import results

FAMILIES = [("I", "bunnies-falling", "rigid Stanford bunnies"), ("II", "teapots-deforming", "deformable Utah teapots")]


def spread(values):
    """mean +/- sample standard deviation (0 for one value)."""
    return statistics.mean(values), (statistics.stdev(values) if len(values) > 1 else 0.0)


def table(rows, number, family, what):
    pattern = re.compile(r"^%s-(\d+)$" % re.escape(family))
    lines = {}
    for r in rows:
        # The config names a scene by name or by file: bunnies-falling-10 or .../bunnies-falling-10.toml.
        m = pattern.match(os.path.splitext(os.path.basename(r["scene"]))[0])
        if m and r["frame"] >= 0 and r["label"] != "whitted":
            lines.setdefault((results.variant(r), int(m.group(1))), []).append(r)
    if not lines:
        return []
    first = next(iter(lines.values()))[0]
    out = ["**Table %s**: dynamic simulation of %s (%s, %d frames of the `%s` path per line; ms)" % (
               number, what, results.resolution(first), len(next(iter(lines.values()))), first["view"]), "",
           "| technique | N | triangles (x10^3) | dynamic triangles (x10^3) | frame time mean +/- std | min, max | "
           "frame CPU time mean +/- std | bvh_update mean +/- std | SSIM mean +/- std (min) | FLIP mean +/- std (max) |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    growth = {}
    for (variant, n), rs in sorted(lines.items()):
        rs.sort(key=lambda r: r["frame"])
        frame = [r["frame_ms"]["median"] for r in rs]
        # The process's CPU time a frame (all threads), where the runner timed it: on a machine shared
        # with other work, the frame's work without the waits for a core.
        cpu = [r["timing"]["cpu_ms"]["median"] for r in rs if "cpu_ms" in r.get("timing", {})]
        bvh = [results.stage(r, "bvh_update", 0.0) for r in rs]
        ssim = [results.metric(r, "whole", "ssim") for r in rs]
        flip = [results.metric(r, "whole", "flip") for r in rs]
        c = rs[0]["counters"]
        dynamic = c.get("bvh_moving_triangles", 0.0) + c.get("bvh_refit_triangles", 0.0)
        cpu_mean = statistics.mean(cpu) if len(cpu) == len(rs) else None
        growth.setdefault(variant, []).append((dynamic, statistics.mean(frame), cpu_mean, statistics.mean(bvh)))
        out.append("| %s | %d | %.1f | %.1f | %.1f +/- %.1f | %.1f, %.1f | %s | %.2f +/- %.2f | %.4f +/- %.4f (%.4f) | %.4f +/- %.4f (%.4f) |" % (
            variant, n, c.get("bvh_triangles", 0.0) / 1e3, dynamic / 1e3, *spread(frame), min(frame), max(frame),
            "%.1f +/- %.1f" % spread(cpu) if cpu_mean is not None else "-", *spread(bvh), *spread(ssim), min(ssim), *spread(flip), max(flip)))
    out.append("")
    for variant, points in sorted(growth.items()):
        ns = ", ".join(str(n) for (v, n) in sorted(lines) if v == variant)
        for what, column in (("Frame time", 1), ("Frame CPU time", 2), ("`bvh_update`", 3)):
            fit = growth_fit([(p[0], p[column]) for p in points]) if None not in (p[column] for p in points) else None
            if fit:
                out.append("%s of %s: %s over N = %s" % (what, variant, fit, ns))
    for implementation in ("CUDA", "OptiX"):
        rows = [r for r in paper_scenes.macedo_rows(number) if r.implementation == implementation]
        out.append("Frame time of the paper's %s rows: %s" % (implementation, growth_fit([(r.dynamic_k * 1e3, r.mean_ms) for r in rows])))
    family_rows = [r for rs in lines.values() for r in rs]
    return out + paper_scenes.scene_count_lines(family_rows, "macedo2019")


def growth_fit(points):
    """How a time grows with the dynamic triangles over (triangles, ms) points in N's order: the
    least-squares slope per 1000 triangles and intercept, the correlation, and the time at the
    largest N over the time at the smallest; None with fewer than two triangle counts."""
    if len(points) < 2 or len({p[0] for p in points}) < 2:
        return None
    xs, ys = [p[0] / 1e3 for p in points], [p[1] for p in points]
    fit = statistics.linear_regression(xs, ys)
    r = statistics.correlation(xs, ys) if len(set(ys)) > 1 else float("nan")
    ratio = ("%.2fx" % (ys[-1] / ys[0])) if ys[0] > 0 else "-"
    return "%.3g ms per 1000 dynamic triangles (+ %.3g ms), correlation %.3f, largest N / smallest %s" % (
        fit.slope, fit.intercept, r, ratio)


def main():
    a, rows = results.table_script(__doc__, "macedo_tables")
    lines = []
    for number, family, what in FAMILIES:
        lines += table(rows, number, family, what)
    if not lines:
        sys.exit("macedo_tables: %s has no bunnies-falling-N or teapots-deforming-N runs along a path" % a.result_dir)
    results.write_table(lines, a.out, results.device_line(a.result_dir, rows))


if __name__ == "__main__":
    main()
