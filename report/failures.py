"""The report's "where methods fail" section: along every camera path, how each
technique's quality and frame time behave frame by frame, and where they break.

Per scene, path and resolution one figure, a row per technique and a series per setting: frame
time, SSIM and FLIP per frame with each setting's worst frame marked and its median drawn, and the
temporal error. A summary table per (scene, technique, setting): the worst-frame SSIM (and its
frame), the median SSIM, the worst SSIM on the reflective/refractive pixels, the worst frame of
every other summarised metric of the result set's metric table (FLIP (LDR), HDR-FLIP: "-" where a
result set predates the metric), the mean and worst temporal error and
the frame-time spike (the largest frame time over the median), beside the same setting's median
SSIM and frame time along the baseline scene's path (sponza-spheres by default) where the result
set has that scene. A frame-time spike counts as a failure only where it is beyond the timing
noise: where the records hold 95% intervals of their medians (timing.py), when the slowest frame's
interval lies wholly above the path's median (above the median of the frames' upper ends, where
the median lies whenever every frame's does); in a result set without intervals, when it exceeds
the slowest frame's own repeat spread (max - min of its repeats). Reads only the records of
results.json."""
import collections
import html
import os
import statistics

import figure_files  # first: it selects matplotlib's file backend before pyplot loads
import axis_format
import matplotlib.pyplot as plt
import palette
import results as rs
import viewer
from figure_files import point_links, save

BASELINE_SCENE = "sponza-spheres"


def series_key(r):
    """One sequence along a path: scene, resolution, path and the technique setting."""
    return (r["scene"], rs.resolution(r), r["view"], r["technique"], rs.variant(r))


def sequences(records):
    """Every sequence of two or more frames along a camera path, its records in frame order."""
    seqs = collections.defaultdict(list)
    for r in records:
        if r["frame"] >= 0:
            seqs[series_key(r)].append(r)
    return {k: sorted(v, key=lambda r: r["frame"]) for k, v in seqs.items() if len(v) >= 2}


def worst(rows, value, higher_is_better=True):
    """(value, record) of the worst frame; None when no record has the value."""
    scored = [(value(r), r) for r in rows if value(r) is not None]
    if not scored:
        return None
    return (min if higher_is_better else max)(scored, key=lambda vr: vr[0])


def median_of(rows, value):
    vals = [value(r) for r in rows if value(r) is not None]
    return statistics.median(vals) if vals else None


def frame_ms(r):
    return r["frame_ms"]["median"]


def ssim(r):
    return rs.metric(r, "whole", "ssim")


def masked_ssim(r):
    return rs.metric(r, "masked", "ssim")


def flip(r):
    return rs.metric(r, "whole", "flip")


def temporal(r):
    return r.get("temporal_error")


def repeat_spread(r):
    """How far one run's own repeats of the frame lie apart (ms): its timing noise."""
    t = r["frame_ms"]
    return t.get("max", t["median"]) - t.get("min", t["median"])


def spike_beyond_noise(rows):
    """Whether the slowest frame of a sequence stands out from its median by more than the timing
    noise (the module's docstring says how, with intervals and without)."""
    t_median = median_of(rows, frame_ms)
    slowest = max(rows, key=frame_ms)
    if all("ci_low" in r["frame_ms"] and "ci_high" in r["frame_ms"] for r in rows):
        return slowest["frame_ms"]["ci_low"] > statistics.median(r["frame_ms"]["ci_high"] for r in rows)
    # A loaded machine's noise shows up in the spread of the frame's own repeats too.
    return frame_ms(slowest) - t_median > repeat_spread(slowest)


# The metric the summary's headline columns (worst, median, masked and the baseline's) are on.
HEADLINE = "ssim"


def other_metrics(table):
    """The summarised metrics of `table` besides the headline: a worst-frame column each."""
    return [m for m in rs.summarised(table) if m["key"] != HEADLINE]


def sequence_summary(rows, table=rs.BUILT_IN_METRICS):
    """The summary numbers of one sequence (see the module's docstring); `table`: the metric table."""
    t_median = median_of(rows, frame_ms)
    t_max = max(frame_ms(r) for r in rows)
    temporals = [temporal(r) for r in rows if temporal(r) is not None]
    return {
        "frames": len(rows),
        "worst_ssim": worst(rows, ssim),
        "median_ssim": median_of(rows, ssim),
        "worst_masked_ssim": worst(rows, masked_ssim),
        "worst": {m["key"]: worst(rows, lambda r, k=m["key"]: rs.metric(r, "whole", k), rs.higher_is_better(m)) for m in other_metrics(table)},
        "temporal_mean": statistics.mean(temporals) if temporals else None,
        "temporal_worst": max(temporals) if temporals else None,
        "median_ms": t_median,
        "spike": t_max / t_median if t_median else None,
        "spike_beyond_noise": spike_beyond_noise(rows),
    }


def baseline_summaries(seqs, baseline_scene, table):
    """The baseline scene's sequences by (resolution, technique setting)."""
    return {(k[1], k[4]): sequence_summary(rows, table) for k, rows in seqs.items() if k[0] == baseline_scene}


def summary_rows(seqs, baseline, baseline_scene, table):
    """One row per sequence outside the baseline scene: (key, its summary, the baseline's or None)."""
    return [(k, sequence_summary(rows, table), baseline.get((k[1], k[4])))
            for k, rows in sorted(seqs.items(), key=lambda item: rs.natural_key(item[0])) if k[0] != baseline_scene]


def worst_beyond_noise(rows, value, higher_is_better=True):
    """(value, record) of the sequence's worst frame on `value` where it stands out from the
    sequence by more than the noise, else None: for the frame time, a spike beyond the timing noise
    (spike_beyond_noise); for a score, worse than the sequence's median by more than
    axis_format.SCORE_TOLERANCE (a dip of 2e-6 in SSIM is no failure)."""
    w = worst(rows, value, higher_is_better)
    if w is None:
        return None
    if value is frame_ms:
        return w if spike_beyond_noise(rows) else None
    return w if abs(w[0] - median_of(rows, value)) > axis_format.SCORE_TOLERANCE else None


PANELS = ((frame_ms, "frame time (ms, median)", False), (ssim, "SSIM", True), (flip, "FLIP (LDR) mean", False),
          (temporal, "temporal error", False))
NO_MARK = {frame_ms: "no frame time beyond the timing noise", ssim: "no frame worse than its median by more than %g" % axis_format.SCORE_TOLERANCE,
           flip: "no frame worse than its median by more than %g" % axis_format.SCORE_TOLERANCE}


def failure_figure(seqs, title, baseline, colours):
    """Rows: techniques; columns: frame time, SSIM, FLIP, temporal error per frame, each setting in
    its report-wide colour (`colours`). Each setting's worst frame is marked where it stands out by
    more than the noise (worst_beyond_noise), a panel without any mark says so, and each setting's
    median is drawn dotted; the same setting's median SSIM on the baseline scene is drawn dashed.
    The value axes are plain numbers, a score axis at least the tolerance wide (axis_format)."""
    techniques = sorted({k[3] for k in seqs})
    fig, axes = plt.subplots(len(techniques), 4, figsize=(17, 2.9 * len(techniques)), squeeze=False)
    for row, technique in zip(axes, techniques):
        variants = sorted((k for k in seqs if k[3] == technique), key=rs.natural_key)
        for ax, (value, _, higher_is_better) in zip(row, PANELS):
            drawn, marked = [], False
            for k in variants:
                pts = [r for r in seqs[k] if value(r) is not None]
                if not pts:
                    continue
                colour = colours[k[4]]
                frames, ys = [r["frame"] for r in pts], [value(r) for r in pts]
                drawn += ys
                ax.plot(frames, ys, lw=1.2, color=colour, label=k[4] if value is frame_ms else None)
                ax.scatter(frames, ys, s=9, color=colour).set_urls(point_links(pts))
                ax.axhline(statistics.median(ys), color=colour, ls=":", lw=0.8)
                w = worst_beyond_noise(seqs[k], value, higher_is_better) if value in NO_MARK else None
                if w:
                    marked = True
                    ax.scatter([w[1]["frame"]], [w[0]], s=70, marker="v" if higher_is_better else "^", facecolors="none",
                               edgecolors="red", linewidths=1.3, zorder=5, label=WORST_MARK)
                if value is ssim:
                    base = baseline.get((k[1], k[4]))
                    if base and base["median_ssim"] is not None:
                        ax.axhline(base["median_ssim"], color=colour, ls="--", lw=0.8)
                        drawn.append(base["median_ssim"])
            if value in (ssim, flip):
                axis_format.score_axis(ax, drawn)
            else:
                axis_format.plain(ax.yaxis)
            if drawn and value in NO_MARK and not marked:
                ax.text(0.5, 0.03, NO_MARK[value], transform=ax.transAxes, ha="center", va="bottom", fontsize=7, color="dimgrey")
        for ax, (_, label, _) in zip(row, PANELS):
            ax.set_xlabel("frame")
            ax.set_ylabel(label, fontsize=8)
            ax.grid(alpha=0.3)
        row[0].set_title(technique, loc="left", fontsize=9, fontweight="bold")
        # The settings' key beside the row, not over its data.
        handles, labels = row[0].get_legend_handles_labels()
        keep = [(h, lab) for h, lab in zip(handles, labels) if lab != WORST_MARK]
        row[-1].legend([h for h, _ in keep], [lab for _, lab in keep], fontsize=6, loc="upper left", bbox_to_anchor=(1.02, 1.0),
                       frameon=False)
    fig.suptitle(title + "\nred: a setting's worst frame where it stands out by more than the noise (frame time: the timing "
                 "intervals; scores: %g); dotted: its median along the path" % axis_format.SCORE_TOLERANCE
                 + ("; dashed (SSIM): its median on the baseline scene" if baseline else ""), fontsize=10)
    fig.tight_layout()
    return fig


WORST_MARK = "worst frame"


def worst_cell(w, spec):
    return "-" if w is None else (spec + " (%d)") % (w[0], w[1]["frame"])


BASELINE_HEADER = ["baseline median SSIM", "baseline frame ms median", "baseline spike"]


def header(table):
    """The summary table's header: a worst-frame column per metric of other_metrics(table)."""
    return (["scene", "path", "size", "technique", "setting", "frames", "worst-frame SSIM (frame)", "median SSIM", "worst SSIM refl./refr. (frame)"]
            + ["worst %s (frame)" % m["label"] for m in other_metrics(table)]
            + ["temporal error mean / worst", "frame ms median", "frame-time spike (max / median)", "spike beyond noise"])


def row_cells(key, s, b, with_baseline, table):
    """The summary row's cells as text (Markdown and HTML share them); the worst SSIM cell (the
    seventh) links to the viewer."""
    scene, res, path, technique, variant = key
    cells = [scene, path, res, technique, variant, str(s["frames"]), worst_cell(s["worst_ssim"], "%.4f"), rs.fmt(s["median_ssim"], "%.4f"),
             worst_cell(s["worst_masked_ssim"], "%.4f")] + [worst_cell(s["worst"][m["key"]], "%%.%df" % m["digits"]) for m in other_metrics(table)] + [
             "%s / %s" % (rs.fmt(s["temporal_mean"], "%.5f"), rs.fmt(s["temporal_worst"], "%.5f")), rs.fmt(s["median_ms"], "%.1f"),
             rs.fmt(s["spike"], "%.2f"), "yes" if s["spike_beyond_noise"] else "no (noise)"]
    if with_baseline:
        cells += [rs.fmt(b["median_ssim"], "%.4f"), rs.fmt(b["median_ms"], "%.1f"), rs.fmt(b["spike"], "%.2f")] if b else ["-", "-", "-"]
    return cells


def markdown_table(rows, link, with_baseline, table):
    """`link(run_id)`: the viewer on a run, from report.md."""
    head = header(table) + (BASELINE_HEADER if with_baseline else [])
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for key, s, b in rows:
        cells = row_cells(key, s, b, with_baseline, table)
        if s["worst_ssim"]:
            cells[6] = "[%s](%s)" % (cells[6], link(s["worst_ssim"][1]["id"]))
        lines.append("| " + " | ".join(c.replace("|", "/") for c in cells) + " |")
    return lines


def html_table(rows, link, with_baseline, table):
    head = header(table) + (BASELINE_HEADER if with_baseline else [])
    out = ['<div class="wide"><table class="failures sortable"><thead><tr>' + "".join("<th>%s</th>" % html.escape(h) for h in head) + "</tr></thead><tbody>"]
    for key, s, b in rows:
        cells = [html.escape(c) for c in row_cells(key, s, b, with_baseline, table)]
        if s["worst_ssim"]:
            cells[6] = '<a href="%s" title="the worst frame in the viewer">%s</a>' % (html.escape(link(s["worst_ssim"][1]["id"])), cells[6])
        out.append("<tr>" + "".join("<td>%s</td>" % c for c in cells) + "</tr>")
    return "\n".join(out) + "\n</tbody></table></div>"


def write_section(records, out_dir, baseline_scene=BASELINE_SCENE, colours=None, table=rs.BUILT_IN_METRICS):
    """Writes the figures, each setting in its report-wide colour (`colours`, palette.py's, by
    default those of `records`); returns the section as (HTML, Markdown lines), or None when no
    path has two frames. `table`: the result set's metric table."""
    colours = colours or palette.setting_colours(records)
    seqs = sequences(records)
    if not seqs:
        return None
    baseline = baseline_summaries(seqs, baseline_scene, table)
    figures = []
    by_path = collections.defaultdict(dict)
    for k, rows in seqs.items():
        by_path[k[:3]][k] = rows
    for (scene, res, path), group in sorted(by_path.items()):
        name = "failures-%s-%s-%s" % (os.path.basename(scene).replace(".toml", ""), res, path)
        title = "%s at %s along %s: per technique and frame" % (scene, res, path)
        rows = [r for seq in group.values() for r in seq]
        figures.append(((scene, res, path), save(failure_figure(group, title, baseline, colours), out_dir, name, rows)))
    rows = summary_rows(seqs, baseline, baseline_scene, table)
    with_baseline = bool(baseline)
    beyond = ("the slowest frame's 95% interval lies wholly above the path's median" if all("ci_low" in r["frame_ms"] for rows in seqs.values()
                                                                                             for r in rows)
              else "the slowest frame exceeds the median by more than that frame's own repeats differ (this result set has no "
                   "intervals)")
    intro = ("Along every camera path, each technique setting's worst frame against its median: the worst-frame SSIM, the "
             "frame-time spike (largest frame time over the median; a failure only where %s, else timing noise) and the "
             "temporal error" % beyond)
    intro += (", beside the same setting's median SSIM and frame time along %s's path (the baseline)." % baseline_scene if with_baseline
              else ". (No baseline: the result set has no camera path of %s.)" % baseline_scene)
    intro += " The worst-frame SSIM opens that frame in the viewer."
    page = ["<h2 id=\"failures\">Where methods fail</h2>", "<p>%s</p>" % html.escape(intro), html_table(rows, viewer.link, with_baseline, table)]
    md = ["", "## Where methods fail", "", intro, ""] + markdown_table(rows, viewer.link, with_baseline, table)
    for (scene, res, path), svg in figures:
        page += ["<h3>%s at %s along %s</h3>" % (html.escape(scene), res, html.escape(path)), figure_files.embed_html(svg, out_dir)]
        md += ["", "### %s at %s along %s" % (scene, res, path), "", "![](%s)" % os.path.relpath(svg, out_dir)]
    return "\n".join(page), md
