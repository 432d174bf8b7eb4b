"""The hybrid techniques with a rasterized and a ray-cast G-buffer against rt_only, from a result
set of experiments/configs/gbuffer_rays.toml (or any with rt_only beside heuristic_rt or
ssr_fallback runs).

    /usr/bin/python3 paper_figures/gbuffer_rays_table.py RESULT_DIR [--out FILE.md]

One line per scene, size, view and hybrid setting: its frame time (median over the repeats), the
speed-up rt_only / setting measured in the same run, SSIM and FLIP against the reference, the rays
per pixel (primary rays included where the G-buffer is ray cast) and where the frame goes: the
rasterizer's stages (results.raster_ms: the G-buffer pass, lighting and read-back, or lighting and
the upload; none with lighting = "cpu"), the primary rays' stage (gbuffer.rays), the lighting on
the host (lighting.cpu), SSR's pass (ssr) and the rays traced for shading (trace). The speed-up is
"1.70x (1.64-1.77)", the median and 95% interval of the per-round ratios, where the records hold
the runner's rounds (timing.py), else the ratio of the medians."""
import sys

import report_modules  # noqa: F401  (puts report/ on sys.path)
import results
import timing

HYBRIDS = ("heuristic_rt", "ssr_fallback")


def key(r):
    return (r["scene"], results.resolution(r), results.view_name(r))


def frame(r):
    return r["frame_ms"]["median"]


def table(rows):
    rt_only = {key(r): r for r in rows if r["technique"] == "rt_only"}
    out = ["**G-buffer from the rasterizer and from primary rays** (ms, medians over the repeats; speed-up = rt_only / setting)", "",
           "| scene | size | view | technique | setting | ms | speed-up | SSIM | FLIP | rays / pixel | rasterizer | gbuffer.rays | lighting.cpu | ssr | trace |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for k, base in sorted(rt_only.items()):
        pixels = base["width"] * base["height"]
        out.append("| %s | %s | %s | rt_only | %s | %.1f | 1.00 | %s | %s | %.2f | | | | | %s |" % (
            k[0], k[1], k[2], base["parameters_text"] or "defaults", frame(base), results.fmt(results.metric(base, "whole", "ssim"), "%.4f"),
            results.fmt(results.metric(base, "whole", "flip"), "%.4f"), base["counters"]["rays_total"] / pixels,
            results.fmt(results.stage(base, "trace"), "%.0f")))
        for r in rows:
            if r["technique"] not in HYBRIDS or key(r) != k:
                continue
            out.append("| %s | %s | %s | %s | %s | %.1f | %s | %s | %s | %.2f | %s | %s | %s | %s | %s |" % (
                k[0], k[1], k[2], r["label"], r["parameters_text"] or "defaults", frame(r),
                timing.speedup_cell([r], [base], "%.2f" % (frame(base) / frame(r))),
                results.fmt(results.metric(r, "whole", "ssim"), "%.4f"), results.fmt(results.metric(r, "whole", "flip"), "%.4f"),
                r["counters"]["rays_total"] / pixels, results.fmt(results.raster_ms(r), "%.0f"),
                results.fmt(results.stage(r, "gbuffer.rays"), "%.0f"), results.fmt(results.stage(r, "lighting.cpu"), "%.0f"),
                results.fmt(results.stage(r, "ssr"), "%.0f"), results.fmt(results.stage(r, "trace"), "%.0f")))
    out.append("")
    return out


def main():
    a, rows = results.table_script(__doc__, "gbuffer_rays_table")
    if not any(r["technique"] == "rt_only" for r in rows):
        sys.exit("gbuffer_rays_table: %s has no rt_only runs to compare with" % a.result_dir)
    results.write_table(table(rows), a.out, results.device_line(a.result_dir, rows))


if __name__ == "__main__":
    main()
