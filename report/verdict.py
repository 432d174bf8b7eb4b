"""The report's verdict: per scene and size, which technique setting to use at what cost.

A setting (a technique with one parameter set) is summarised over the runs of one scene and size
(every view and frame): its frame time is the median over those runs of each run's median frame
time, with the 95% interval of that median beside it (timing.py; the best and the worst run in a
result set without intervals); its summarised metrics (the result set's metric table: SSIM, FLIP
(LDR) and HDR-FLIP, on the whole image and on the reflective/refractive pixels) are medians over
the same runs. From these:

- the Pareto-optimal settings: no other setting is at least as fast and at least as good on every
  score (the table's scored metrics: SSIM and FLIP; HDR-FLIP, which judges the same error on the
  linear images, is shown beside them), and strictly better in one; each marked
  where it is tied in time with the next faster one;
- per quality threshold (SSIM >= 0.99, 0.97, 0.95, whole image and reflective/refractive pixels)
  the fastest setting reaching it, with its speed-up over the reference and over `rt_only`; where
  the rounds cannot rule out others reaching it (timing.py's rule: a confidence set for the
  fastest, from paired rounds), the row names them all, in name order, and says whether they are
  tied (within the set's precision) or not decided (the rounds cannot tell them apart);
  thresholds whose answer is the same settings, decided alike, share one row; each row says in
  words whether what reaches the threshold beats the reference and rt_only at all (by the same
  rule: a speed-up whose interval lies wholly above 1 / (1 - precision));
- one sentence per scene saying it in words, "nothing ... beats the reference" where nothing does.

A setting that changes nothing on a scene is not applicable there (`not_applicable`): left off the
verdict and the scene's speed-accuracy chart, and listed with the reason.

    verdict.py RESULT_DIR      prints the verdict in words, a sentence per scene and size (what
                               `hybridlab run` ends with)"""
import collections
import hashlib
import html
import os
import statistics
import sys

import images
import results as rs
import timing

THRESHOLDS = (0.99, 0.97, 0.95)
REGIONS = (("whole", "whole image"), ("masked", "refl./refr. pixels"))
# The metric the quality thresholds are set on.
THRESHOLD_METRIC = "ssim"
# Walewski 2019's "ray tracing only": the speed-up every hybrid is read against.
RT_ONLY = "rt_only"


class Setting:
    """One technique setting over the runs of one scene and size."""

    def __init__(self, name, records, table):
        self.name = name
        self.records = records
        self.technique = records[0]["technique"]
        self.time = timing.setting_time(records)  # the median of the runs' medians, and its bar
        self.ms = self.time.ms
        # (region, metric, higher is better) of the scores that rank settings.
        self.ranked = [(region, m["key"], rs.higher_is_better(m)) for region, _ in REGIONS for m in table if m["scored"]]
        self.scores = {(region, m["key"]): self._median(region, m["key"]) for region, _ in REGIONS
                       for m in table if m["scored"] or m["summarised"]}
        self.not_applicable = None  # the reason, where the setting changes nothing on the scene

    def _median(self, region, name):
        values = [rs.metric(r, region, name) for r in self.records]
        values = [v for v in values if v is not None]
        return statistics.median(values) if values else None

    def score(self, region, name):
        return self.scores.get((region, name))


def settings_of(records, table):
    """The settings of one scene and size's records, by name, scored by the metrics of `table`."""
    by = collections.defaultdict(list)
    for r in records:
        by[rs.variant(r)].append(r)
    return {name: Setting(name, rows, table) for name, rows in sorted(by.items())}


def image_digest(result_dir, r):
    """The digest of a run's linear pixels (not of its EXR file, whose header carries a date); None
    where the image is not there (a set whose images were dropped to fit a transfer, as the GPU
    campaign's larger ones are)."""
    path = os.path.join(result_dir, r["images"]["exr"])
    if not os.path.exists(path):
        return None
    return hashlib.sha256(images.rgb(path).tobytes()).hexdigest()


def mark_not_applicable(settings, result_dir):
    """Sets `not_applicable` on the settings that change nothing on this scene: the layered EMs
    without a lens object in view (no lens pixel), SSR without reflective pixels, and any setting
    whose every image is byte-identical to another technique's at the same view and frame (the
    first technique in name order keeps its place; where images are missing, none is compared)."""
    for s in settings.values():
        counters = [r["counters"] for r in s.records]
        if all(c.get("lens_pixels", 1) == 0 for c in counters):
            s.not_applicable = "no lens object in view (no lens pixel): draws what raster draws"
        elif s.technique == "ssr_fallback" and all(r.get("scene_stats", {}).get("reflective", 1) == 0 for r in s.records):
            s.not_applicable = "no reflective surface: nothing for screen-space reflections to do"
    digests = {name: {(r["view"], r["frame"]): image_digest(result_dir, r) for r in s.records} for name, s in settings.items()}
    for name, s in settings.items():
        if s.not_applicable or None in digests[name].values():
            continue
        for other, o in settings.items():
            if other == name or o.technique == s.technique or o.not_applicable or digests[other] != digests[name]:
                continue
            if (o.technique, other) < (s.technique, name):
                s.not_applicable = "every image byte-identical to %s's" % other
                break


def dominates(a, b):
    """`a` is at least as fast and as good as `b` on every score both have, and better in one."""
    pairs = [(a.ms, b.ms, False)] + [(a.score(rg, n), b.score(rg, n), hi) for rg, n, hi in a.ranked]
    pairs = [(x, y, hi) for x, y, hi in pairs if x is not None and y is not None]
    no_worse = all((x >= y) if hi else (x <= y) for x, y, hi in pairs)
    better = any((x > y) if hi else (x < y) for x, y, hi in pairs)
    return no_worse and better


def pareto(settings):
    """The applicable settings no other applicable setting dominates, fastest first."""
    live = [s for s in settings.values() if not s.not_applicable]
    return sorted((s for s in live if not any(dominates(o, s) for o in live if o is not s)), key=lambda s: s.ms)


def by_name(s):
    return rs.natural_key(s.name)


def fastest_of(candidates, tolerance):
    """The timing.FastestSet of `candidates`, its settings in name order."""
    return timing.fastest(candidates, lambda s: s.records, tolerance, key=by_name)


def fastest_reaching(settings, region, threshold, tolerance=timing.DEFAULT_TOLERANCE):
    """The timing.FastestSet of the applicable settings whose median SSIM on `region` is at least
    `threshold`: one setting, or several (tied, or not decided); no settings when none reaches it."""
    ok = [s for s in settings.values() if not s.not_applicable and (s.score(region, THRESHOLD_METRIC) or 0.0) >= threshold]
    return fastest_of(ok, tolerance)


class Tie:
    """A fastest set (timing.FastestSet) named together in name order: "a and b, tied within 3%",
    "a and b, not decided (the rounds cannot tell them apart)"."""

    def __init__(self, fastest, tolerance):
        self.settings, self.tolerance = fastest.settings, tolerance
        self.decision, self.unpaired, self.basis = fastest.decision, fastest.unpaired, fastest.basis

    def words(self, about):
        """The tie in a sentence: "X at 10.1 ms (what)" for one setting, "X and Y, tied ... (X: 10.1
        ms, what; Y: ...)" for several; `about(s)`: a setting's "what"."""
        if len(self.settings) == 1:
            s = self.settings[0]
            return "%s at %.1f ms (%s)" % (s.name, s.ms, about(s))
        return "%s (%s)" % (self.text(), "; ".join("%s: %.1f ms, %s" % (s.name, s.ms, about(s)) for s in self.settings))

    def noun(self):
        """"setting ... is" or "settings ... are": the sentence's subject and verb."""
        return ("setting", "is") if len(self.settings) == 1 else ("settings", "are")

    def suffix(self):
        if len(self.settings) <= 1:
            return ""
        if self.decision == timing.TIED:
            return ", tied within %.0f%%" % (100.0 * self.tolerance) if self.basis == timing.PAIRED else \
                ", tied within %.0f%% or the noise" % (100.0 * self.tolerance)
        unpaired = " (%d timed in other processes, not paired)" % self.unpaired if self.unpaired else ""
        return ", not decided: the rounds cannot tell them apart%s" % unpaired

    def text(self, name=lambda s: s.name):
        names = [name(s) for s in self.settings]
        joined = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]
        return joined + self.suffix()


def rt_only_setting(settings):
    """The `rt_only` setting the speed-ups are read against: its default (no parameters), else its
    most accurate one; None when the result set has no `rt_only` run."""
    runs = [s for s in settings.values() if s.technique == RT_ONLY]
    if not runs:
        return None
    default = [s for s in runs if not s.records[0]["parameters_text"]]
    return default[0] if default else max(runs, key=lambda s: s.score("whole", THRESHOLD_METRIC) or 0.0)


class SceneVerdict:
    def __init__(self, scene, size, records, result_dir, table):
        self.scene, self.size = scene, size
        self.table = table
        self.settings = settings_of(records, table)
        mark_not_applicable(self.settings, result_dir)
        self.reference_ms = statistics.median(r["reference"]["frame_ms"] for r in records)
        self.tolerance = timing.tolerance(records)
        self.rt_only = rt_only_setting(self.settings)
        self.pareto = pareto(self.settings)
        self.regions = [(rg, label) for rg, label in REGIONS if any(s.score(rg, THRESHOLD_METRIC) is not None for s in self.settings.values())]
        # Per row: the timing.FastestSet of the settings reaching the threshold (no settings for none).
        self.thresholds = [(rg, label, t, fastest_reaching(self.settings, rg, t, self.tolerance))
                           for rg, label in self.regions for t in THRESHOLDS]

    def applicable(self):
        return [s for s in self.settings.values() if not s.not_applicable]

    def excluded(self):
        return [s for s in self.settings.values() if s.not_applicable]

    def speedups(self, s):
        """(over the reference, over rt_only or None): each a timing.Interval where the records hold
        rounds (the record's own `speedup` for a setting of one run, else its rounds pooled), else
        the ratio of the medians."""
        ref = timing.speedup_over_reference(s.records) or self.reference_ms / s.ms
        if not self.rt_only:
            return ref, None
        recorded = RT_ONLY if not self.rt_only.records[0]["parameters_text"] else None  # the runner pairs the default
        return ref, timing.speedup_over(s.records, self.rt_only.records, recorded) or self.rt_only.ms / s.ms

    def tied_with_faster(self, settings):
        """For each of `settings` (fastest first), the one before it where the two are tied in time."""
        return [prev if prev and timing.compare(s.records, prev.records, self.tolerance)[0] == timing.TIED else None
                for prev, s in zip([None] + settings[:-1], settings)]

    def against_reference(self, s):
        """`s` against the reference (timing.FASTER, SLOWER, TIED or NOT_DECIDED) by the rule: its
        speed-up's interval against the band (timing.compare_ratio on reference / own); without an
        interval, not decided where the records hold rounds (too few), and by the ratio of the
        medians alone in a result set without rounds."""
        ref, _ = self.speedups(s)
        if isinstance(ref, timing.Interval):
            inverse = timing.Interval(1.0 / ref.median, 1.0 / ref.high, 1.0 / ref.low)
            return timing.compare_ratio(inverse, self.tolerance)
        if timing.has_rounds(s.records):
            return timing.NOT_DECIDED
        return timing.FASTER if ref > 1.0 else timing.SLOWER

    def beats_reference(self, s):
        """Whether `s` is faster than the reference (against_reference)."""
        return self.against_reference(s) == timing.FASTER

    def beats_rt_only(self, s):
        """Whether `s` is faster than rt_only by the tie rule (False without rt_only, and for rt_only)."""
        return bool(self.rt_only) and s is not self.rt_only and timing.compare(s.records, self.rt_only.records,
                                                                               self.tolerance)[0] == timing.FASTER

    def beaten(self, tied):
        """In words, what of the reference and rt_only the settings `tied` (reaching a threshold)
        beat: "nothing reaching it beats the reference", "beats the reference; nothing reaching it
        beats rt_only", or "beats the reference and rt_only"."""
        if not tied:
            return "no setting reaches it"
        if not any(self.beats_reference(s) for s in tied):
            if any(self.against_reference(s) == timing.NOT_DECIDED for s in tied):
                return "not decided against the reference (too few rounds or too wide an interval)"
            return "nothing reaching it beats the reference"
        if self.rt_only and self.rt_only not in tied and not any(self.beats_rt_only(s) for s in tied):
            return "beats the reference; nothing reaching it beats rt_only"
        return "beats the reference" + (" and rt_only" if self.rt_only else "")

    def threshold_rows(self):
        """The threshold rows with their answers joined: [(the (region label, threshold) pairs a row
        covers, the timing.FastestSet that answers them)], in the order of the first pair;
        thresholds whose fastest settings are the same, decided alike, share one row."""
        rows = []
        for _, label, t, fastest in self.thresholds:
            answer = ([s.name for s in fastest.settings], fastest.decision, fastest.unpaired)
            same = [row for row in rows if ([s.name for s in row[1].settings], row[1].decision, row[1].unpaired) == answer]
            if same:
                same[0][0].append((label, t))
            else:
                rows.append(([(label, t)], fastest))
        return rows

    def speed_words(self, s):
        """"2.10x (2.00-2.20) the reference's speed, 1.30x rt_only's"."""
        ref, rt = self.speedups(s)
        own = rt is None or s is self.rt_only  # rt_only's speed-up over itself says nothing
        return "%s the reference's speed%s" % (speedup_text(ref, "%.2fx"), "" if own else ", %s rt_only's" % speedup_text(rt, "%.2fx"))

    def sentence(self):
        """The verdict in words, from the numbers of the tables."""
        head = "On %s at %s" % (self.scene, self.size)
        if not self.applicable():
            return head + ", no setting changes the image: every one is not applicable here."
        parts = []
        if not self.regions:
            parts.append("no run has an SSIM score (the config's metrics leave it out)")
        for region, label in self.regions:
            reached = [(t, fastest) for rg, _, t, fastest in self.thresholds if rg == region and fastest.settings]
            if not reached:
                best = max(self.applicable(), key=lambda s: s.score(region, THRESHOLD_METRIC) or 0.0)
                parts.append("no setting reaches SSIM %.2f on the %s (best: %s, %s)" % (THRESHOLDS[-1], label, best.name,
                                                                                      rs.fmt(best.score(region, THRESHOLD_METRIC), "%.4f")))
                continue
            t, fastest = reached[0]
            tied = fastest.settings
            tie = Tie(fastest, self.tolerance)
            if not any(self.beats_reference(s) for s in tied):
                undecided = any(self.against_reference(s) == timing.NOT_DECIDED for s in tied)
                parts.append("%s reaching SSIM %.2f on the %s %s the reference (%.1f ms): the fastest, %s" % (
                    "no setting" if undecided else "nothing", t, label,
                    "is decided faster than" if undecided else "beats", self.reference_ms, tie.words(self.speed_words)))
                continue
            noun, verb = tie.noun()
            part = "the fastest %s reaching SSIM %.2f on the %s %s %s" % (noun, t, label, verb, tie.words(self.speed_words))
            if self.rt_only and self.rt_only not in tied and not any(self.beats_rt_only(s) for s in tied):
                part += ", and nothing reaching it beats rt_only"
            parts.append(part)
        fastest = Tie(fastest_of(self.applicable(), self.tolerance), self.tolerance)
        noun, verb = fastest.noun()
        text = head + ", " + "; ".join(parts) + ". The fastest %s of all %s %s" % (noun, verb, fastest.words(
            lambda s: "SSIM %s" % rs.fmt(s.score("whole", "ssim"), "%.4f")))
        if self.excluded():
            text += "; not applicable here: " + ", ".join(s.name for s in self.excluded())
        return text + "."


def verdicts(records, result_dir, table=None):
    """A verdict per scene and size; `table`: the metric table (by default the result set's)."""
    table = table or rs.metric_table(result_dir)
    groups = collections.defaultdict(list)
    for r in records:
        groups[(r["scene"], rs.resolution(r))].append(r)
    return [SceneVerdict(scene, size, rows, result_dir, table) for (scene, size), rows in sorted(groups.items())]


def speedup_text(value, spec="%.2f"):
    """A speed-up as text: "1.70x (1.64-1.77)" for a timing.Interval, `spec` for a ratio of
    medians (a result set without rounds), "-" for none."""
    if value is None:
        return "-"
    return value.text("%.2f", "x") if isinstance(value, timing.Interval) else spec % value


def time_bar_text(s, as_interval):
    """A setting's bar: its median's 95% interval, or (without one) its best and worst run's."""
    text = "%.2f-%.2f" % (s.time.low, s.time.high)
    return text + " (runs' range)" if as_interval and not s.time.is_interval else text


# Tables as (header, rows of cells); a cell is text, a Setting or a Tie (linked by `link`).
def pareto_table(v):
    regions = ["whole"] + (["masked"] if any(rg == "masked" for rg, _ in v.regions) else [])
    suffix = {"whole": "", "masked": " refl./refr."}
    scores = [(region, m) for region in regions for m in rs.summarised(v.table)]
    as_interval = any(s.time.is_interval for s in v.pareto)
    header = ["setting", "frame ms (median)", "95% interval ms" if as_interval else "best-worst ms", "tied in time with", "x ref.",
              "x rt_only"] + [m["label"] + suffix[region] for region, m in scores]
    rows = []
    for s, tied in zip(v.pareto, v.tied_with_faster(v.pareto)):
        ref, rt = v.speedups(s)
        rows.append([s, "%.2f" % s.ms, time_bar_text(s, as_interval), tied or "", speedup_text(ref), speedup_text(rt)]
                    + [rs.metric_cell(m, s.score(region, m["key"])) for region, m in scores])
    return header, rows


def qualities_text(covers):
    """The thresholds a row covers: "SSIM >= 0.99, whole image", "SSIM >= 0.99, >= 0.97 and >= 0.95,
    whole image; SSIM >= 0.99, refl./refr. pixels"."""
    by_region = collections.OrderedDict()
    for label, t in covers:
        by_region.setdefault(label, []).append(">= %.2f" % t)
    parts = []
    for label, ts in by_region.items():
        joined = ts[0] if len(ts) == 1 else ", ".join(ts[:-1]) + " and " + ts[-1]
        parts.append("SSIM %s, %s" % (joined, label))
    return "; ".join(parts)


def threshold_table(v):
    """A row per answer: the thresholds it covers, the fastest setting reaching them or the settings
    tied for fastest (each one's time and speed-ups, in the order the row names them), and whether
    they beat the reference and rt_only, in words."""
    header = ["quality reached", "fastest setting", "frame ms", "x ref.", "x rt_only", "in words"]
    rows = []
    for covers, fastest in v.threshold_rows():
        tied = fastest.settings
        if not tied:
            rows.append([qualities_text(covers), "none", "-", "-", "-", v.beaten(tied)])
            continue
        speeds = [v.speedups(s) for s in tied]
        rows.append([qualities_text(covers), Tie(fastest, v.tolerance), " / ".join("%.2f" % s.ms for s in tied),
                     " / ".join(speedup_text(ref) for ref, _ in speeds), " / ".join(speedup_text(rt) for _, rt in speeds),
                     v.beaten(tied)])
    return header, rows


def excluded_table(v):
    return ["setting", "not applicable because"], [[s, s.not_applicable] for s in v.excluded()]


def cell_text(c, link, escape):
    """A cell as HTML or Markdown: a Setting linked, a Tie's settings each linked, text escaped."""
    if isinstance(c, Setting):
        return link(c)
    if isinstance(c, Tie):
        return c.text(link)
    return escape(c)


def html_table(table, link, cls):
    header, rows = table
    out = ['<div class="wide"><table class="%s"><thead><tr>%s</tr></thead><tbody>' % (cls, "".join("<th>%s</th>" % html.escape(h) for h in header))]
    for cells in rows:
        out.append("<tr>" + "".join("<td>%s</td>" % cell_text(c, link, html.escape) for c in cells) + "</tr>")
    return "\n".join(out) + "</tbody></table></div>"


def markdown_table(table, link):
    header, rows = table
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for cells in rows:
        lines.append("| " + " | ".join(cell_text(c, link, lambda text: text.replace("|", "/")) for c in cells) + " |")
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
    records = [r for v in verdict_list for s in v.settings.values() for r in s.records]
    intro = ("Per scene and size, each setting's median over its runs (every view and frame): the Pareto-optimal settings "
             "(none faster and at least as good on SSIM and FLIP (LDR); HDR-FLIP is shown beside them), and the fastest "
             "setting reaching each SSIM threshold, with "
             "its speed-up over the reference (whitted) and over rt_only. " + timing.describe_rule(records)
             + "".join(" " + c for c in timing.caveats(records)))
    page.append("<p>%s</p>" % html.escape(intro))
    md += ["", intro]
    for v in verdict_list:
        h, m = setting_link(viewer_link, False), setting_link(viewer_link, True)
        page += ['<h3 id="verdict-%s-%s">%s at %s</h3>' % (html.escape(rs.anchor(v.scene)), v.size, html.escape(v.scene), v.size), '<p class="sentence">%s</p>' % html.escape(v.sentence()),
                 "<p>Reference: %.2f ms.</p>" % v.reference_ms, html_table(threshold_table(v), h, "verdict thresholds"),
                 html_table(pareto_table(v), h, "verdict pareto")]
        md += ["", "### %s at %s" % (v.scene, v.size), "", v.sentence(), "", "Reference: %.2f ms." % v.reference_ms, ""]
        md += markdown_table(threshold_table(v), m) + ["", "Pareto-optimal settings:", ""] + markdown_table(pareto_table(v), m)
        if v.excluded():
            page.append(html_table(excluded_table(v), h, "verdict excluded"))
            md += ["", "Not applicable:", ""] + markdown_table(excluded_table(v), m)
    return "\n".join(page), md


def main(argv):
    if len(argv) != 2:
        print("usage: verdict.py RESULT_DIR", file=sys.stderr)
        return 2
    for v in verdicts(rs.load(argv[1]), argv[1]):
        print(v.sentence())
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
