#!/usr/bin/python3
"""Walewski 2019 Tables 5 and 6 from a result set of experiments/configs/walewski2019.toml.

    /usr/bin/python3 paper_figures/walewski_tables.py RESULT_DIR [--out FILE.md]
    /usr/bin/python3 paper_figures/walewski_tables.py --target RESULT_DIR   (walewski2019_target.toml)

Table 5 (one static view per scene, the scene camera): the stage times of `heuristic_rt` (RAST,
HEUR, RAYT, BLEND, FRAME) and the frame time of `rt_only` ("RAYT ONLY FRAME"), with `whitted`'s
frame time and each one's SSIM and FLIP against the reference beside them. Table 6 (along the
scene's camera path): mean frame time with and without the heuristic. Times are the medians over a
run's repeats; means along a path are over its frames. The technique entries are found by label
(heuristic, no-heuristic, rt_only, whitted), as the config names them. Runs on both ray backends
(a `rays` parameter, walewski2019_backends.toml) get one pair of tables per backend, each run
compared with rt_only and whitted on its own backend. A speed-up is "1.70x (1.64-1.77)", the median
and 95% interval of the per-round ratios, where the records hold the runner's rounds (timing.py),
else the ratio of the two medians. Under the tables, the scenes' counts beside Table 4's
(paper_scenes.py)."""
import statistics
import sys

import paper_scenes
import report_modules  # noqa: F401  (puts report/ on sys.path)
import results
import timing

LABELS = {"heuristic": "heuristic", "no_heuristic": "no-heuristic", "rt_only": "rt_only", "whitted": "whitted"}


def by_label(rows, label):
    return [r for r in rows if r["label"] == label]


def table5(rows, scenes):
    out = ["**Table 5** (static view, the scene camera; ms, medians over repeats)", "",
           "| | " + " | ".join(scenes) + " |", "|---|" + "---|" * len(scenes)]

    def cell(scene, label, fn, params=None):
        rs = [r for r in by_label(rows, label) if r["scene"] == scene and r["frame"] < 0
              and (params is None or r["parameters_text"] == params)]
        return fn(rs[0]) if rs else None

    def line(name, vals):
        out.append("| %s | %s |" % (name, " | ".join(v if isinstance(v, str) else results.fmt(v) for v in vals)))

    def quality(r):
        return "%.4f / %.4f" % (results.metric(r, "whole", "ssim"), results.metric(r, "whole", "flip"))

    frame = lambda r: r["frame_ms"]["median"]
    variants = sorted({r["parameters_text"] for r in by_label(rows, LABELS["heuristic"])})
    for v in variants:
        h = "heuristic_rt" + (" [%s]" % v if v else "")
        line("FRAME %s" % h, [cell(s, LABELS["heuristic"], frame, v) for s in scenes])
        # Table 5's rows: the rasterizer's stages (occlusion queries included), then the stages
        # heuristic, trace and blend.
        for paper_name, time in (("RAST", lambda r: results.raster_ms(r, 0.0)), ("HEUR", lambda r: results.stage(r, "heuristic", 0.0)),
                                 ("RAYT", lambda r: results.stage(r, "trace", 0.0)), ("BLEND", lambda r: results.stage(r, "blend", 0.0))):
            line("&nbsp;&nbsp;%s" % paper_name, [cell(s, LABELS["heuristic"], time, v) for s in scenes])
        line("&nbsp;&nbsp;objects selected / visible", [cell(s, LABELS["heuristic"], lambda r: "%d / %d" % (
            r["counters"].get("objects_selected", 0), r["counters"].get("objects_visible", 0)), v) for s in scenes])
        line("&nbsp;&nbsp;SSIM / FLIP", [cell(s, LABELS["heuristic"], quality, v) or "-" for s in scenes])
        for name, label in (("rt_only", "rt_only"), ("whitted", "whitted")):
            ratios = []
            for s in scenes:
                a, b = cell(s, LABELS["heuristic"], lambda r: r, v), cell(s, LABELS[label], lambda r: r)
                ratios.append(timing.speedup_cell([a], [b], "%.2fx" % (frame(b) / frame(a))) if a and b and frame(a) else "-")
            line("&nbsp;&nbsp;speed-up over %s" % name, ratios)
    for name, label in (("FRAME no heuristic", "no_heuristic"), ("RAYT ONLY FRAME (rt_only)", "rt_only"), ("WHITTED FRAME", "whitted")):
        line(name, [cell(s, LABELS[label], frame) for s in scenes])
        line("&nbsp;&nbsp;SSIM / FLIP", [cell(s, LABELS[label], quality) or "-" for s in scenes])
    return out


def table6(rows, scenes):
    out = ["", "**Table 6** (along the camera path; mean over its frames of the median frame time, ms; mean SSIM)", "",
           "| | " + " | ".join(scenes) + " |", "|---|" + "---|" * len(scenes)]
    entries = [("with heuristic [%s]" % v, "heuristic", v) for v in sorted({r["parameters_text"] for r in by_label(rows, LABELS["heuristic"])})]
    entries += [("no heuristic", "no_heuristic", None), ("rt_only", "rt_only", None), ("whitted", "whitted", None)]
    for name, label, params in entries:
        vals = []
        for s in scenes:
            rs = [r for r in by_label(rows, LABELS[label]) if r["scene"] == s and r["frame"] >= 0
                  and (params is None or r["parameters_text"] == params)]
            if not rs:
                vals.append("-")
                continue
            t = statistics.mean(r["frame_ms"]["median"] for r in rs)
            q = statistics.mean(results.metric(r, "whole", "ssim") for r in rs)
            vals.append("%.1f (SSIM %.4f, %d frames)" % (t, q, len(rs)))
        out.append("| %s | %s |" % (name, " | ".join(vals)))
    return out


def target_report(rows, settle=10, tolerance=0.15):
    """The frame-time target along a path: per frame target, predicted and actual frame time, and
    the share of frames within `tolerance` of the target after the first `settle`."""
    rs = sorted((r for r in rows if "target_ms" in r["counters"]), key=lambda r: r["frame"])
    if not rs:
        sys.exit("walewski_tables: no run has a target_ms counter")
    out = ["| frame | target ms | predicted ms | actual ms | budget T | objects selected | SSIM |", "|---|---|---|---|---|---|---|"]
    for r in rs:
        c = r["counters"]
        out.append("| %d | %.0f | %.0f | %.0f | %.3g | %d / %d | %.4f |" % (
            r["frame"], c["target_ms"], c["predicted_ms"], r["frame_ms"]["median"], c.get("budget", 0.0),
            c.get("objects_selected", 0), c.get("objects_visible", 0), results.metric(r, "whole", "ssim")))
    settled = rs[settle:]

    def near(r):
        return abs(r["frame_ms"]["median"] - r["counters"]["target_ms"]) <= tolerance * r["counters"]["target_ms"]

    def not_over(r):
        return r["frame_ms"]["median"] <= (1.0 + tolerance) * r["counters"]["target_ms"]

    # Where the selection could not fill the budget (everything visible fitted, or what is left is
    # too expensive for what remains: the predicted time falls short of the target) the frame can
    # only be late, not early.
    bound = [r for r in settled if r["counters"]["predicted_ms"] >= (1.0 - tolerance) * r["counters"]["target_ms"]]
    free = [r for r in settled if r not in bound]
    n = max(len(settled), 1)
    out += ["", "After the first %d frames: %d of %d frames (%.0f%%) within %.0f%% of the target, or not over it where"
            " the selection could not fill the budget (%d of %d filled frames within, %d of %d unfilled frames not over)" % (
                settle, sum(map(near, bound)) + sum(map(not_over, free)), len(settled),
                100.0 * (sum(map(near, bound)) + sum(map(not_over, free))) / n, 100 * tolerance,
                sum(map(near, bound)), len(bound), sum(map(not_over, free)), len(free)),
            "Prediction error |predicted - actual| / actual: median %.1f%%" % (
                100.0 * statistics.median(abs(r["counters"]["predicted_ms"] - r["frame_ms"]["median"]) / r["frame_ms"]["median"]
                                          for r in settled))]
    return out


def main():
    a, rows = results.table_script(__doc__, "walewski_tables", [(("--target",), {
        "action": "store_true", "help": "report the frame-time target run (walewski2019_target.toml)"})])
    scenes = sorted({r["scene"] for r in rows})
    if a.target:
        lines = target_report(rows)
    else:
        lines = []
        # The backends of the tables' entries: raster traces no rays (and reads as "embree").
        backends = sorted({results.backend(r) for r in rows if r["label"] in LABELS.values()})
        for b in backends:
            same = [results.without_backend(r) for r in rows if results.backend(r) == b]
            if len(backends) > 1 or b != "embree":
                lines += ["", "### rays = %s (ratios to rt_only and whitted on this backend)" % b, ""]
            lines += table5(same, scenes)
            if len(backends) == 1 or any(r["frame"] >= 0 for r in same):  # Table 6 needs camera-path runs
                lines += table6(same, scenes)
        lines += paper_scenes.scene_count_lines(rows, "walewski2019")
    results.write_table(lines, a.out, results.device_line(a.result_dir, rows))


if __name__ == "__main__":
    main()
