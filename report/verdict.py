"""The report's verdict: per scene and size, which technique setting to use at what cost.

A setting (a technique with one parameter set) is summarised over the runs of one scene and size
(every view and frame): its frame time is the median over those runs of each run's median frame
time, with the best and the worst run beside it; its SSIM, FLIP (LDR) and HDR-FLIP (on the whole
image and on the reflective/refractive pixels) are medians over the same runs. From these:

- the Pareto-optimal settings: no other setting is at least as fast and at least as good on every
  score (SSIM and FLIP; HDR-FLIP is shown beside them), and strictly better in one;
- per quality threshold (SSIM >= 0.99, 0.97, 0.95, whole image and reflective/refractive pixels)
  the fastest setting reaching it, with its speed-up over the reference and over `rt_only`;
- one sentence per scene saying it in words.

A setting that changes nothing on a scene is not applicable there (`not_applicable`): left off the
verdict and the scene's speed-accuracy chart, and listed with the reason."""
import collections
import hashlib
import html
import os
import statistics

import exr
import results as rs

THRESHOLDS = (0.99, 0.97, 0.95)
REGIONS = (("whole", "whole image"), ("masked", "refl./refr. pixels"))
SCORES = (("whole", "ssim", True), ("whole", "flip", False), ("masked", "ssim", True), ("masked", "flip", False))
# Shown beside the scores but not one of them: HDR-FLIP (Andersson et al. 2021) judges the same
# error as FLIP on the linear images, so the Pareto front stays on the display images' scores.
SHOWN = SCORES + (("whole", "flip_hdr", False), ("masked", "flip_hdr", False))
# Walewski 2019's "ray tracing only": the speed-up every hybrid is read against.
RT_ONLY = "rt_only"


class Setting:
    """One technique setting over the runs of one scene and size."""

    def __init__(self, name, records):
        self.name = name
        self.records = records
        self.technique = records[0]["technique"]
        times = [r["frame_ms"]["median"] for r in records]
        self.ms = statistics.median(times)
        self.best_ms, self.worst_ms = min(times), max(times)
        self.scores = {(region, name): self._median(region, name) for region, name, _ in SHOWN}
        self.not_applicable = None  # the reason, where the setting changes nothing on the scene

    def _median(self, region, name):
        values = [rs.metric(r, region, name) for r in self.records]
        values = [v for v in values if v is not None]
        return statistics.median(values) if values else None

    def score(self, region, name):
        return self.scores[(region, name)]


def settings_of(records):
    """The settings of one scene and size's records, by name."""
    by = collections.defaultdict(list)
    for r in records:
        by[rs.variant(r)].append(r)
    return {name: Setting(name, rows) for name, rows in sorted(by.items())}


def image_digest(result_dir, r):
    """The digest of a run's linear pixels (not of its EXR file, whose header carries a date)."""
    return hashlib.sha256(exr.rgb(os.path.join(result_dir, r["images"]["exr"])).tobytes()).hexdigest()


def mark_not_applicable(settings, result_dir):
    """Sets `not_applicable` on the settings that change nothing on this scene: the layered EMs
    without a lens object in view (no lens pixel), SSR without reflective pixels, and any setting
    whose every image is byte-identical to another technique's at the same view and frame (the
    first technique in name order keeps its place)."""
    for s in settings.values():
        counters = [r["counters"] for r in s.records]
        if all(c.get("lens_pixels", 1) == 0 for c in counters):
            s.not_applicable = "no lens object in view (no lens pixel): draws what raster draws"
        elif s.technique == "ssr_fallback" and all(r.get("scene_stats", {}).get("reflective", 1) == 0 for r in s.records):
            s.not_applicable = "no reflective surface: nothing for screen-space reflections to do"
    digests = {name: {(r["view"], r["frame"]): image_digest(result_dir, r) for r in s.records} for name, s in settings.items()}
    for name, s in settings.items():
        if s.not_applicable:
            continue
        for other, o in settings.items():
            if other == name or o.technique == s.technique or o.not_applicable or digests[other] != digests[name]:
                continue
            if (o.technique, other) < (s.technique, name):
                s.not_applicable = "every image byte-identical to %s's" % other
                break


def dominates(a, b):
    """`a` is at least as fast and as good as `b` on every score both have, and better in one."""
    pairs = [(a.ms, b.ms, False)] + [(a.score(rg, n), b.score(rg, n), hi) for rg, n, hi in SCORES]
    pairs = [(x, y, hi) for x, y, hi in pairs if x is not None and y is not None]
    no_worse = all((x >= y) if hi else (x <= y) for x, y, hi in pairs)
    better = any((x > y) if hi else (x < y) for x, y, hi in pairs)
    return no_worse and better


def pareto(settings):
    """The applicable settings no other applicable setting dominates, fastest first."""
    live = [s for s in settings.values() if not s.not_applicable]
    return sorted((s for s in live if not any(dominates(o, s) for o in live if o is not s)), key=lambda s: s.ms)


def fastest_reaching(settings, region, threshold):
    """The fastest applicable setting whose median SSIM on `region` is at least `threshold`."""
    ok = [s for s in settings.values() if not s.not_applicable and (s.score(region, "ssim") or 0.0) >= threshold]
    return min(ok, key=lambda s: s.ms) if ok else None


def rt_only_setting(settings):
    """The `rt_only` setting the speed-ups are read against: its default (no parameters), else its
    most accurate one; None when the result set has no `rt_only` run."""
    runs = [s for s in settings.values() if s.technique == RT_ONLY]
    if not runs:
        return None
    default = [s for s in runs if not s.records[0]["parameters_text"]]
    return default[0] if default else max(runs, key=lambda s: s.score("whole", "ssim") or 0.0)


class SceneVerdict:
    def __init__(self, scene, size, records, result_dir):
        self.scene, self.size = scene, size
        self.settings = settings_of(records)
        mark_not_applicable(self.settings, result_dir)
        self.reference_ms = statistics.median(r["reference"]["frame_ms"] for r in records)
        self.rt_only = rt_only_setting(self.settings)
        self.pareto = pareto(self.settings)
        self.regions = [(rg, label) for rg, label in REGIONS if any(s.score(rg, "ssim") is not None for s in self.settings.values())]
        self.thresholds = [(rg, label, t, fastest_reaching(self.settings, rg, t)) for rg, label in self.regions for t in THRESHOLDS]

    def applicable(self):
        return [s for s in self.settings.values() if not s.not_applicable]

    def excluded(self):
        return [s for s in self.settings.values() if s.not_applicable]

    def speedups(self, s):
        """(over the reference, over rt_only or None)."""
        return self.reference_ms / s.ms, (self.rt_only.ms / s.ms if self.rt_only else None)

    def sentence(self):
        """The verdict in words, from the numbers of the tables."""
        head = "On %s at %s" % (self.scene, self.size)
        if not self.applicable():
            return head + ", no setting changes the image: every one is not applicable here."
        parts = []
        if not self.regions:
            parts.append("no run has an SSIM score (the config's metrics leave it out)")
        for region, label in self.regions:
            reached = [(t, s) for rg, _, t, s in self.thresholds if rg == region and s]
            if not reached:
                best = max(self.applicable(), key=lambda s: s.score(region, "ssim") or 0.0)
                parts.append("no setting reaches SSIM %.2f on the %s (best: %s, %s)" % (THRESHOLDS[-1], label, best.name,
                                                                                      rs.fmt(best.score(region, "ssim"), "%.4f")))
                continue
            t, s = reached[0]
            ref, rt = self.speedups(s)
            parts.append("the fastest setting reaching SSIM %.2f on the %s is %s at %.1f ms (%.2fx the reference's speed%s)"
                         % (t, label, s.name, s.ms, ref, ", %.2fx rt_only's" % rt if rt is not None else ""))
        fastest = min(self.applicable(), key=lambda s: s.ms)
        text = head + ", " + "; ".join(parts) + ". The fastest setting of all is %s at %.1f ms (SSIM %s)" % (
            fastest.name, fastest.ms, rs.fmt(fastest.score("whole", "ssim"), "%.4f"))
        if self.excluded():
            text += "; not applicable here: " + ", ".join(s.name for s in self.excluded())
        return text + "."


def verdicts(records, result_dir):
    groups = collections.defaultdict(list)
    for r in records:
        groups[(r["scene"], rs.resolution(r))].append(r)
    return [SceneVerdict(scene, size, rows, result_dir) for (scene, size), rows in sorted(groups.items())]


# Tables as (header, rows of cells); `link` is the setting's name as HTML or Markdown.
def pareto_table(v):
    regions = ["whole"] + (["masked"] if any(rg == "masked" for rg, _ in v.regions) else [])
    suffix = {"whole": "", "masked": " refl./refr."}
    scores = [(region, name) for region in regions for name in ("ssim", "flip", "flip_hdr")]
    header = ["setting", "frame ms (median)", "best-worst ms", "x ref.", "x rt_only"] + [
        rs.METRIC_LABELS[name] + suffix[region] for region, name in scores]
    rows = []
    for s in v.pareto:
        ref, rt = v.speedups(s)
        rows.append([s, "%.2f" % s.ms, "%.2f-%.2f" % (s.best_ms, s.worst_ms), "%.2f" % ref, rs.fmt(rt, "%.2f")]
                    + [rs.fmt(s.score(region, name), "%.4f") for region, name in scores])
    return header, rows


def threshold_table(v):
    header = ["quality reached", "fastest setting", "frame ms", "x ref.", "x rt_only"]
    rows = []
    for _, label, t, s in v.thresholds:
        if s is None:
            rows.append(["SSIM >= %.2f, %s" % (t, label), "none", "-", "-", "-"])
            continue
        ref, rt = v.speedups(s)
        rows.append(["SSIM >= %.2f, %s" % (t, label), s, "%.2f" % s.ms, "%.2f" % ref, rs.fmt(rt, "%.2f")])
    return header, rows


def excluded_table(v):
    return ["setting", "not applicable because"], [[s, s.not_applicable] for s in v.excluded()]


def html_table(table, link, cls):
    header, rows = table
    out = ['<table class="%s"><thead><tr>%s</tr></thead><tbody>' % (cls, "".join("<th>%s</th>" % html.escape(h) for h in header))]
    for cells in rows:
        out.append("<tr>" + "".join("<td>%s</td>" % (link(c) if isinstance(c, Setting) else html.escape(c)) for c in cells) + "</tr>")
    return "\n".join(out) + "</tbody></table>"


def markdown_table(table, link):
    header, rows = table
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for cells in rows:
        lines.append("| " + " | ".join(link(c) if isinstance(c, Setting) else c.replace("|", "/") for c in cells) + " |")
    return lines


def setting_link(viewer_link, markdown):
    """A setting's name linked to the viewer on its first run."""
    def link(s):
        target = viewer_link(s.records[0]["id"])
        return "[%s](%s)" % (s.name, target) if markdown else '<a href="%s">%s</a>' % (html.escape(target), html.escape(s.name))
    return link


def write(verdict_list, viewer_link):
    """The verdict section as (HTML, Markdown lines)."""
    page, md = ['<h2 id="verdict">Verdict</h2>'], ["", "## Verdict"]
    intro = ("Per scene and size, each setting's median over its runs (every view and frame): the Pareto-optimal settings "
             "(none faster and at least as good on SSIM and FLIP (LDR); HDR-FLIP is shown beside them), and the fastest "
             "setting reaching each SSIM threshold, with "
             "its speed-up over the reference (whitted) and over rt_only.")
    page.append("<p>%s</p>" % html.escape(intro))
    md += ["", intro]
    for v in verdict_list:
        h, m = setting_link(viewer_link, False), setting_link(viewer_link, True)
        page += ['<h3>%s at %s</h3>' % (html.escape(v.scene), v.size), '<p class="sentence">%s</p>' % html.escape(v.sentence()),
                 "<p>Reference: %.2f ms.</p>" % v.reference_ms, html_table(threshold_table(v), h, "verdict thresholds"),
                 html_table(pareto_table(v), h, "verdict pareto")]
        md += ["", "### %s at %s" % (v.scene, v.size), "", v.sentence(), "", "Reference: %.2f ms." % v.reference_ms, ""]
        md += markdown_table(threshold_table(v), m) + ["", "Pareto-optimal settings:", ""] + markdown_table(pareto_table(v), m)
        if v.excluded():
            page.append(html_table(excluded_table(v), h, "verdict excluded"))
            md += ["", "Not applicable:", ""] + markdown_table(excluded_table(v), m)
    return "\n".join(page), md
