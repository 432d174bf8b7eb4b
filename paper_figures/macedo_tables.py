#!/usr/bin/python3
"""de Macedo & Rodrigues 2019 Tables I and II from a result set of experiments/configs/macedo2019.toml.

    /usr/bin/python3 paper_figures/macedo_tables.py RESULT_DIR [--out FILE.md]

Table I (rigid: bunnies-falling-N) and Table II (deformable: teapots-deforming-N), one line per N
and technique variant, over the frames of the camera path: the scene's triangle count and its
dynamic triangles (the ray scene's counters: rigid instances moved, deformed meshes refitted), the
frame time mean +/- standard deviation, min and max (each frame's time is the median over the run's
repeats), the `bvh_update` stage's mean, and SSIM and FLIP against the `whitted` reference per frame
(mean +/- standard deviation, worst). Below each table: how the `bvh_update` stage grows with the
number of dynamic triangles (least-squares slope and correlation over the table's lines)."""
import os
import re
import statistics
import sys

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
           "bvh_update mean +/- std | SSIM mean +/- std (min) | FLIP mean +/- std (max) |",
           "|---|---|---|---|---|---|---|---|---|"]
    growth = {}
    for (variant, n), rs in sorted(lines.items()):
        rs.sort(key=lambda r: r["frame"])
        frame = [r["frame_ms"]["median"] for r in rs]
        bvh = [results.stage(r, "bvh_update", 0.0) for r in rs]
        ssim = [results.metric(r, "whole", "ssim") for r in rs]
        flip = [results.metric(r, "whole", "flip") for r in rs]
        c = rs[0]["counters"]
        dynamic = c.get("bvh_moving_triangles", 0.0) + c.get("bvh_refit_triangles", 0.0)
        growth.setdefault(variant, []).append((dynamic, statistics.mean(bvh)))
        out.append("| %s | %d | %.1f | %.1f | %.1f +/- %.1f | %.1f, %.1f | %.2f +/- %.2f | %.4f +/- %.4f (%.4f) | %.4f +/- %.4f (%.4f) |" % (
            variant, n, c.get("bvh_triangles", 0.0) / 1e3, dynamic / 1e3, *spread(frame), min(frame), max(frame),
            *spread(bvh), *spread(ssim), min(ssim), *spread(flip), max(flip)))
    out.append("")
    for variant, points in sorted(growth.items()):
        if len(points) < 2 or len({p[0] for p in points}) < 2:
            continue
        xs, ys = [p[0] / 1e3 for p in points], [p[1] for p in points]
        fit = statistics.linear_regression(xs, ys)
        r = statistics.correlation(xs, ys) if len(set(ys)) > 1 else float("nan")
        out.append("`bvh_update` of %s: %.3g ms per 1000 dynamic triangles (+ %.3g ms), correlation %.3f over N = %s" % (
            variant, fit.slope, fit.intercept, r, ", ".join(str(n) for (v, n) in sorted(lines) if v == variant)))
    out.append("")
    return out


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
