#!/usr/bin/python3
"""Sabino et al. 2012 Table 3 from a result set of experiments/configs/sabino2012.toml.

    /usr/bin/python3 paper_figures/sabino_table3.py RESULT_DIR [--out FILE.md]

Table 3 ("Performance comparison between our hybrid render and a pure ray tracer implementation",
ms) per scene: vertices, triangles, DR (the hybrid's deferred-rendering time: its rasterization
stages, results.raster_ms), RT (the ray-tracing-only frame), Hybrid (the hybrid's frame) and the gain RT / Hybrid. Here
the hybrid is the entry labelled `hybrid` (heuristic_rt), the ray tracer the one labelled `rt`
(rt_only); times are the medians over a run's repeats, and each one's SSIM against the reference
is given beside them (the paper reports none). A scene with several frames (a camera path) gets
the mean over its frames. The gain is "1.70x (1.64-1.77)", the median and 95% interval of the
per-round ratios RT / Hybrid over every frame, where the records hold the runner's rounds
(timing.py), else the ratio of the means. Under the table, the scenes' counts beside the paper's
(paper_scenes.py)."""
import statistics
import sys

import paper_scenes
import report_modules  # noqa: F401  (puts report/ on sys.path)
import results
import timing

HYBRID, RAY_TRACER = "hybrid", "rt"


def scene_rows(rows, scene, label):
    return [r for r in rows if r["scene"] == scene and r["label"] == label]


def mean(rows, value):
    return statistics.mean(value(r) for r in rows)


def table3(rows):
    scenes = sorted({r["scene"] for r in rows})
    out = ["**Sabino 2012 Table 3** (ms, medians over repeats; %s)" % ", ".join(sorted({results.resolution(r) for r in rows})), "",
           "| Scene | Vertices | Triangles | DR | RT | Hybrid | Gain | SSIM hybrid / RT |", "|---|---|---|---|---|---|---|---|"]
    for scene in scenes:
        hybrid, rt = scene_rows(rows, scene, HYBRID), scene_rows(rows, scene, RAY_TRACER)
        if not hybrid or not rt:
            sys.exit("sabino_table3: %s needs runs labelled '%s' and '%s'" % (scene, HYBRID, RAY_TRACER))
        if results.raster_ms(hybrid[0]) is None:
            sys.exit("sabino_table3: the '%s' runs have no rasterizer stages (is it heuristic_rt?)" % HYBRID)
        stats = hybrid[0]["scene_stats"]
        dr = mean(hybrid, results.raster_ms)
        t_rt = mean(rt, lambda r: r["frame_ms"]["median"])
        t_hybrid = mean(hybrid, lambda r: r["frame_ms"]["median"])
        out.append("| %s | %d | %d | %.1f | %.1f | %.1f | %s | %.4f / %.4f |" % (
            scene, stats["vertices"], stats["triangles"], dr, t_rt, t_hybrid, timing.speedup_cell(hybrid, rt, "%.2f" % (t_rt / t_hybrid)),
            mean(hybrid, lambda r: results.metric(r, "whole", "ssim")), mean(rt, lambda r: results.metric(r, "whole", "ssim"))))
    return out


def main():
    a, rows = results.table_script(__doc__, "sabino_table3")
    results.write_table(table3(rows) + paper_scenes.scene_count_lines(rows, "sabino2012"), a.out, results.device_line(a.result_dir, rows))


if __name__ == "__main__":
    main()
