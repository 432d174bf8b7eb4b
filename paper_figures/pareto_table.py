"""A parameter sweep's speed-accuracy table against rt_only, per scene and size, with its Pareto
fronts, from any result set with rt_only beside the swept settings (experiments/configs/
ssr_fallback_sweep.toml).

    /usr/bin/python3 paper_figures/pareto_table.py RESULT_DIR [--out FILE.md]

Per scene and size (its views and path frames pooled), one line per setting (a technique with one
parameter set): its frame time over rt_only's at the same view and frame, measured in the same run
(the median of those ratios over the views and frames: a ratio, not an absolute time, is what
carries between runs on a shared machine; where the records hold the runner's rounds, the median
and 95% interval of the per-round ratios to rt_only timed in the same rounds, timing.py), whether
it is tied in time with the next faster setting of its family (timing.py's tie rule), its SSIM on the whole image and on the reflective and
refractive pixels (medians over the views and frames), the rays a pixel it traced and, for SSR,
its march steps a pixel (means). The fronts are drawn within a family, the settings of one
[[techniques]] entry of the config (its label: one parameter group swept around the defaults), so
that a family's front is not decided by another family's parameters. A setting is on its family's
time front when no other is both faster and more accurate (lower time ratio, higher SSIM), and on
its work front when no other does no more of either kind of work (rays, SSR steps), is no less
accurate and is better in one: where the machine's load makes times too noisy to rank close
settings, the work ranks them. The last table counts, per setting, the scenes on whose fronts it
is, the median of its time ratios and its lowest SSIM: a default has to be on the front, or near
it, on every scene."""
import collections
import statistics
import sys

import report_modules  # noqa: F401  (puts report/ on sys.path)
import results as rs
import timing

RT_ONLY = "rt_only"


class Point:
    """One setting over one scene and size's runs: time ratio to rt_only, SSIM, work a pixel."""

    def __init__(self, name, runs, rt_only):
        self.name = name
        self.runs = runs
        self.family = runs[0]["label"]
        # Paired over the rounds where the records hold them; else the median of the ratios of medians.
        self.interval = timing.paired_ratio(runs, [rt_only[(r["view"], r["frame"])] for r in runs])
        self.ratio = self.interval.median if self.interval else statistics.median(
            r["frame_ms"]["median"] / rt_only[(r["view"], r["frame"])]["frame_ms"]["median"] for r in runs)
        self.tied_with = None  # the next faster setting of its family, where tied with it in time
        self.ssim = median_metric(runs, "whole")
        self.ssim_masked = median_metric(runs, "masked")
        self.rays = per_pixel(runs, "rays_total")
        self.ssr_steps = per_pixel(runs, "ssr_march_steps")
        self.time_front = self.work_front = False

    def work(self):
        return (self.rays or 0.0, self.ssr_steps or 0.0)


def per_pixel(runs, counter):
    """The mean of a counter over the runs, a pixel; None where the runs do not count it."""
    values = [r["counters"][counter] / (r["width"] * r["height"]) for r in runs if counter in r["counters"]]
    return statistics.mean(values) if values else None


def median_metric(runs, region):
    values = [v for v in (rs.metric(r, region, "ssim") for r in runs) if v is not None]
    return statistics.median(values) if values else None


def does_less_work_as_well(a, b):
    """`a` does no more of either kind of work than `b` and is no less accurate, and better in one."""
    no_worse = all(x <= y for x, y in zip(a.work(), b.work())) and a.ssim >= b.ssim
    return no_worse and (a.work() != b.work() or a.ssim > b.ssim)


def mark_ties(points, tolerance):
    """Marks, in each family, every setting tied in time with the next faster one (by time ratio)."""
    families = collections.defaultdict(list)
    for p in points:
        families[p.family].append(p)
    for family in families.values():
        ordered = sorted(family, key=lambda p: (p.ratio, rs.natural_key(p.name)))
        for faster, p in zip(ordered, ordered[1:]):
            if timing.compare(p.runs, faster.runs, tolerance)[0] == timing.TIED:
                p.tied_with = faster.name


def mark_fronts(points):
    """Marks each family's time front (results.pareto_front on time ratio and SSIM) and work front."""
    families = collections.defaultdict(list)
    for p in points:
        if p.ssim is not None:
            families[p.family].append(p)
    for family in families.values():
        for _, _, p in rs.pareto_front([(p.ratio, p.ssim, p) for p in family], higher_is_better=True):
            p.time_front = True
        for p in family:
            p.work_front = not any(does_less_work_as_well(o, p) for o in family if o is not p)


def scene_points(rows):
    """{(scene, size): [Point]}: every setting of every scene and size with an rt_only run at each
    of its views and frames, fronts marked."""
    groups = collections.defaultdict(list)
    for r in rows:
        groups[(r["scene"], rs.resolution(r))].append(r)
    out = {}
    for key, runs in sorted(groups.items()):
        rt_only = {(r["view"], r["frame"]): r for r in runs if r["technique"] == RT_ONLY}
        by_setting = collections.defaultdict(list)
        for r in runs:
            if (r["view"], r["frame"]) in rt_only and rs.metric(r, "whole", "ssim") is not None:
                by_setting[rs.variant(r)].append(r)
        points = [Point(name, setting_runs, rt_only) for name, setting_runs in by_setting.items()]
        mark_fronts(points)
        mark_ties(points, timing.tolerance(runs))
        out[key] = sorted(points, key=lambda p: rs.natural_key(p.name))
    return out


def mark(on):
    return "yes" if on else ""


def table(by_scene):
    out = []
    for (scene, size), points in by_scene.items():
        out += ["**%s, %s**: time ratio = frame / rt_only's frame at the same view (median over the views and frames%s)" % (
                    scene, size, "; paired over the rounds, with its 95% interval" if any(p.interval for p in points) else ""), "",
                "| setting | time ratio | tied in time with | SSIM | SSIM refl./refr. | rays / pixel | SSR steps / pixel | time front | "
                "work front |",
                "|---|---|---|---|---|---|---|---|---|"]
        for p in points:
            out.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                p.name, p.interval.text("%.2f") if p.interval else "%.2f" % p.ratio, p.tied_with or "", rs.fmt(p.ssim, "%.4f"),
                rs.fmt(p.ssim_masked, "%.4f"), rs.fmt(p.rays, "%.2f"), rs.fmt(p.ssr_steps, "%.1f"), mark(p.time_front), mark(p.work_front)))
        out.append("")
    scenes = len(by_scene)
    per_setting = collections.defaultdict(list)
    for points in by_scene.values():
        for p in points:
            per_setting[p.name].append(p)
    out += ["**Every scene** (%d): on how many scenes' fronts each setting is, its median time ratio and its lowest SSIM" % scenes, "",
            "| setting | scenes | on time front | on work front | median time ratio | lowest SSIM |", "|---|---|---|---|---|---|"]
    for name in sorted(per_setting, key=rs.natural_key):
        ps = per_setting[name]
        lowest = [p.ssim for p in ps if p.ssim is not None]
        out.append("| %s | %d | %d | %d | %.2f | %s |" % (name, len(ps), sum(p.time_front for p in ps), sum(p.work_front for p in ps),
                                                       statistics.median(p.ratio for p in ps), rs.fmt(min(lowest) if lowest else None, "%.4f")))
    out.append("")
    return out


def main():
    a, rows = rs.table_script(__doc__, "pareto_table")
    if not any(r["technique"] == RT_ONLY for r in rows):
        sys.exit("pareto_table: %s has no rt_only runs to compare with" % a.result_dir)
    rs.write_table(table(scene_points(rows)), a.out, rs.device_line(a.result_dir, rows))


if __name__ == "__main__":
    main()
