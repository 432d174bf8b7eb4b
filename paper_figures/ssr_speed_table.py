#!/usr/bin/python3
"""SSR's speed against accuracy from a result set of experiments/configs/ssr.toml.

    /usr/bin/python3 paper_figures/ssr_speed_table.py RESULT_DIR [--out FILE.md]

Speed: one line per scene and `ssr_fallback` variant (label `ssr_fallback`): the `whitted` run's
frame time, the variant's, their ratio (whitted / ssr_fallback: the speed-up), SSIM against the
reference, the SSR hit rate and the fallback rays, with the variant's stage times (medians over the
repeats; raster is the rasterizer's stages, results.raster_ms, and blend its seam blur and
composite). Bound: one line per run labelled `glass-trees` (SSR on, no fallback, SSR hits not
recursed: what remains in the `trace` stage is the refractive texels' ray trees, which the
method always traces): its raster, SSR and ray-trace stages, the trees' share of whitted's frame,
and the largest speed-up the method could reach if everything else cost nothing,
whitted / (raster + ssr + trace), beside whitted / raster (the raster stages alone). The speed
table's ratio is "1.70x (1.64-1.77)", the median and 95% interval of the per-round ratios, where
the records hold the runner's rounds (timing.py), else the ratio of the medians; the bound's
ratios are of stage times, which have no rounds."""
import sys

import report_modules  # noqa: F401  (puts report/ on sys.path)
import results
import timing


def frame(r):
    return r["frame_ms"]["median"]


def key(r):
    # The ray backend too: a run is compared with whitted on its own backend (ssr_backends.toml).
    return (r["scene"], results.resolution(r), results.view_name(r), results.backend(r))


def beside_whitted(rows, whitted, label):
    """The runs labelled `label` with the whitted run of their scene, size and view."""
    for r in rows:
        if r["label"] == label and key(r) in whitted:
            yield r, whitted[key(r)]


def speed_table(rows, whitted):
    out = ["**Speed against accuracy** (ms, medians over the repeats; ratio = whitted / ssr_fallback)", "",
           "| scene | size | setting | whitted ms | ssr_fallback ms | ratio | SSIM | SSR hit rate | fallback rays | "
           "raster | ssr | trace | blend.seam_blur | blend |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r, whitted_run in beside_whitted(rows, whitted, "ssr_fallback"):
        c = r["counters"]
        w = frame(whitted_run)
        ssim = results.metric(r, "whole", "ssim")
        out.append("| %s | %s | %s | %.1f | %.1f | %s | %s | %.3f | %d | %.1f | %.1f | %.1f | %.1f | %.1f |" % (
            r["scene"], results.resolution(r), r["parameters_text"] or "defaults", w, frame(r),
            timing.speedup_cell([r], [whitted_run], "%.2f" % (w / frame(r))),
            "%.4f" % ssim if ssim is not None else "-", c.get("ssr_hit_rate", 0.0), int(c.get("fallback_rays", 0)),
            results.raster_ms(r, 0.0), *(results.stage(r, s, 0.0) for s in ("ssr", "trace", "blend.seam_blur", "blend"))))
    out.append("")
    return out


def bound_table(rows, whitted):
    out = ["**Bound**: the refractive texels' ray trees (runs labelled `glass-trees`) and the largest speed-up "
           "whitted / (raster + ssr + trace)", "",
           "| scene | size | setting | whitted ms | raster | ssr | refractive trees | trees / whitted | largest speed-up | "
           "whitted / raster |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    for r, whitted_run in beside_whitted(rows, whitted, "glass-trees"):
        w = frame(whitted_run)
        raster, ssr, trees = results.raster_ms(r, 0.0), results.stage(r, "ssr", 0.0), results.stage(r, "trace", 0.0)
        out.append("| %s | %s | %s | %.1f | %.1f | %.1f | %.1f | %.2f | %.2f | %.2f |" % (
            r["scene"], results.resolution(r), r["parameters_text"] or "defaults", w, raster, ssr, trees, trees / w,
            w / (raster + ssr + trees), w / raster))
    out.append("")
    return out


def main():
    a, rows = results.table_script(__doc__, "ssr_speed_table")
    whitted = {key(r): r for r in rows if r["label"] == "whitted"}
    if not whitted:
        sys.exit("ssr_speed_table: %s has no whitted runs to compare with" % a.result_dir)
    results.write_table(speed_table(rows, whitted) + bound_table(rows, whitted), a.out, results.device_line(a.result_dir, rows))


if __name__ == "__main__":
    main()
