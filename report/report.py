#!/usr/bin/python3
"""The report of a hybridlab result set: index.html (works from the file system), report.md and
the figures as SVG and PDF.

    report.py RESULT_DIR --out REPORT_DIR [--baseline SCENE] [--check-only]

A result set's file that is malformed (a record, experiment.json, config.toml, an image) is named on
one line of standard error, with the place in it and what was expected: exit status 2, nothing
written. A report folder that cannot be written: one line, exit status 3, the folder as it was.

Figures: per scene and resolution, frame time (wall clock: the records' frame_ms) against SSIM and
against FLIP for every setting, a bar over its median's 95% interval, with the Pareto front drawn
and labelled and the reference's frame time marked (on the whole image, and on the reflective and
refractive pixels where a scene has them), and the same on the process's CPU time and on the
device's time where the records hold them (timing.cpu_ms, timing.device_ms); per scene the stage-time
breakdown of every technique (Walewski 2019 Table 5 as a chart) and SSIM against rays per pixel
(the work, which carries over between machines); along each camera path the frame
time, the error and the temporal error per frame; and "where methods fail" (failures.py): each
technique setting's worst frames along every path against its median and against the baseline
scene's path. Every run in the tables and every point in the
charts links to viewer.html (viewer.py) opened on that run."""
import argparse
import collections
import html
import os
import statistics
import sys

import figure_files  # first: it selects matplotlib's file backend before pyplot loads
import axis_format
import device
import failures
import images
import matplotlib.pyplot as plt
import palette
import point_labels
import results as rs
import staged_folder
import timing
import verdict
import viewer
from figure_files import point_links, save
from matplotlib.lines import Line2D
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter


# The regions a record is scored on, with their label suffix and temporal-error key: the whole
# image, and where a scene has reflective or refractive pixels (the technique's subject, often a
# small part of the frame) those alone.
REGIONS = (("whole", "", "temporal_error"), ("masked", " refl./refr.", "temporal_error_masked"))


def regions_of(records):
    return [region for region in REGIONS if any(r["metrics"].get(region[0]) for r in records)]


def log_ticks(axis):
    """Labelled ticks at 1, 2 and 5 times the powers of ten (a log axis spanning less than a decade
    would otherwise label none or one)."""
    axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda v, _: "%g" % v))
    axis.set_minor_formatter(NullFormatter())


def speed_accuracy(v, out_dir, key, title, colours=None):
    """The speed-accuracy figures of a scene and size: on the wall clock, and on each other clock
    (CPU time, device time) that one of its settings' records hold."""
    records = [r for s in v.settings.values() for r in s.records]
    figures = [save(speed_accuracy_figure(v, title, colours=colours), out_dir, "speed-accuracy-" + key, records)]
    for clock in timing.CLOCKS[1:]:
        if any(timing.setting_time(s.records, clock) for s in v.applicable()):
            figures.append(save(speed_accuracy_figure(v, "%s, on %s" % (title, clock.what), clock, colours), out_dir,
                                "speed-accuracy-%s-%s" % (clock.key.replace("_ms", ""), key), records))
    return figures


def bar_words(times):
    """What the bars of a speed-accuracy chart span."""
    if all(t.is_interval for t in times):
        return "bar: 95% interval of the median"
    if not any(t.is_interval for t in times):
        return "bar: best to worst run"
    return "bar: 95% interval of the median (runs' range where none)"


def speed_accuracy_figure(v, title, clock=timing.WALL, colours=None):
    """Time on `clock` (the wall clock's frame_ms by default) against each scored metric of the result
    set's table (SSIM and FLIP), a point per
    applicable setting that has that clock (its median over the runs, a bar over that median's 95%
    interval, or from its best to its worst run in a result set without intervals), the Pareto
    front through the settings, the reference's frame time (wall clock only: it has no other), the
    points numbered with the key beside the axes; a row per region scored (the whole image, then
    the reflective and refractive pixels). Each setting in its report-wide colour (`colours`,
    palette.py's; by default those of the scene's records)."""
    regions = [rg for rg in REGIONS if rg[0] in dict(v.regions)] or [REGIONS[0]]
    ordered = sorted(v.applicable(), key=lambda s: (s.technique, rs.natural_key(s.name)))
    number = {s.name: i + 1 for i, s in enumerate(ordered)}  # the same numbers on every clock's chart
    time = {s.name: timing.setting_time(s.records, clock) for s in ordered}
    settings = [s for s in ordered if time[s.name]]
    untimed = [s.name for s in ordered if not time[s.name]]
    wall = clock is timing.WALL
    col = colours or palette.setting_colours([r for s in v.settings.values() for r in s.records])
    scored = [m for m in v.table if m["scored"]]
    fig, axes = plt.subplots(len(regions), len(scored), figsize=(6.5 * len(scored), 4.6 * len(regions)), squeeze=False)
    fig.subplots_adjust(left=0.06, right=0.70, top=0.9 if len(regions) > 1 else 0.86, bottom=0.1, hspace=0.32, wspace=0.25)
    panels = [(axes[i][j], region, suffix, m) for i, (region, suffix, _) in enumerate(regions) for j, m in enumerate(scored)]
    handles = {s.name: Line2D([], [], ls="none", marker="o", ms=5, color=col[s.name], mec="black", mew=0.3) for s in settings}
    for ax, region, suffix, m in panels:
        points = []
        for s in settings:
            y = s.score(region, m["key"])
            if y is None:
                continue
            t = time[s.name]
            ax.errorbar([t.ms], [y], xerr=[[t.ms - t.low], [t.high - t.ms]], fmt="none", ecolor=col[s.name], elinewidth=0.8,
                        capsize=2, alpha=0.7)
            points.append((t.ms, y, s.name))
        # One scatter for the panel's points, each linked to its setting's first run: matplotlib's SVG
        # writer drops the link of a scatter of one point, so a lone point is drawn twice.
        shown = points * (2 if len(points) == 1 else 1)
        ax.scatter([p[0] for p in shown], [p[1] for p in shown], color=[col[p[2]] for p in shown], s=26, edgecolors="black",
                   linewidths=0.3, zorder=3).set_urls([point_links(v.settings[p[2]].records[:1])[0] for p in shown])
        front = rs.pareto_front(points, rs.higher_is_better(m))
        handles["Pareto front"] = ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="black", lw=1)[0]
        if wall:
            handles["reference"] = ax.axvline(v.reference_ms, color="grey", ls="--", lw=1)
        ax.set_xscale("log")
        log_ticks(ax.xaxis)
        lo = min([time[s.name].low for s in settings] + ([v.reference_ms] if wall else []))
        hi = max([time[s.name].high for s in settings] + ([v.reference_ms] if wall else []))
        ax.set_xlim(lo / 1.25, hi * 1.25)
        ax.set_xlabel("%s per frame (ms, log scale)\nmedian over runs; %s" % (clock.what, bar_words([time[s.name] for s in settings])),
                      fontsize=8)
        ax.set_ylabel("%s%s (%s is better)" % (m["label"], suffix, m["better"]))
        ax.grid(alpha=0.3, which="both")
        axis_format.score_axis(ax, [p[1] for p in points])
        ax.points = points
    for ax, *_ in panels:
        point_labels.place(ax, [(t, y) for t, y, _ in ax.points], [str(number[n]) for _, _, n in ax.points])
    names = [n for n in number if any(n == p[2] for ax, *_ in panels for p in ax.points)]
    extra = ["Pareto front"] + (["reference"] if wall else [])
    fig.legend([handles[n] for n in names] + [handles[n] for n in extra],
               ["%d  %s" % (number[n], n) for n in names] + ["Pareto front"] + (["reference %.1f ms" % v.reference_ms] if wall else []),
               loc="upper left", bbox_to_anchor=(0.71, 0.9), fontsize=7, frameon=False)
    notes = (["not applicable here (not drawn):"] + [s.name for s in v.excluded()] if v.excluded() else []) + (
        ["no %s recorded (not drawn):" % clock.what] + untimed if untimed else [])
    if notes:
        fig.text(0.71, 0.06, "\n".join(notes), fontsize=7, va="bottom", color="dimgrey")
    fig.suptitle(title)
    return fig


def rays_per_pixel(r):
    """A run's rays per pixel (primary rays included where a technique casts them), None without counts."""
    rays = r["counters"].get("rays_total")
    return None if rays is None else rays / float(r["width"] * r["height"])


def work_accuracy(records, out_dir, key, title, col):
    """SSIM against rays per pixel: the speed-accuracy chart's second view, by work that carries over
    between machines instead of this machine's milliseconds (runs without rays sit at 0); each
    setting in its report-wide colour (`col`)."""
    scores = []
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for v in sorted({rs.variant(r) for r in records}, key=rs.natural_key):
        rows = [r for r in records if rs.variant(r) == v and rays_per_pixel(r) is not None and rs.metric(r, "whole", "ssim") is not None]
        ax.scatter([rays_per_pixel(r) for r in rows], [rs.metric(r, "whole", "ssim") for r in rows], color=col[v], label=v, s=22,
                   alpha=0.85).set_urls(point_links(rows))
        scores += [rs.metric(r, "whole", "ssim") for r in rows]
    axis_format.score_axis(ax, scores)
    axis_format.plain(ax.xaxis)
    ax.set_xlabel("rays per pixel")
    ax.set_ylabel("SSIM (higher is better)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.02, 1), frameon=False)
    fig.suptitle(title)
    return save(fig, out_dir, "work-accuracy-" + key, records)


def stage_breakdown(records, out_dir, key, title):
    """Stacked median stage times per technique variant, averaged over the frames: one bar segment
    and legend entry per kind of work (the stage vocabulary, techniques/stage_names.h), in a
    frame's order and in the same colour on every chart."""
    by_variant = collections.defaultdict(list)
    for r in records:
        by_variant[rs.variant(r)].append(r)
    kinds = rs.kind_order({k for r in records for k in rs.stage_kinds(r)})
    variants = sorted(by_variant, key=rs.natural_key)
    fig, ax = plt.subplots(figsize=(max(6, 0.7 * len(variants) + 2), 4.5))
    bottom = [0.0] * len(variants)
    cmap = plt.get_cmap("tab20")
    for k in kinds:
        vals = [statistics.mean(rs.stage_kinds(r).get(k, 0.0) for r in by_variant[v]) for v in variants]
        colour = cmap((rs.STAGE_KINDS.index(k) if k in rs.STAGE_KINDS else len(rs.STAGE_KINDS) + kinds.index(k)) % 20)
        ax.bar(range(len(variants)), vals, bottom=bottom, label=k, color=colour)
        bottom = [b + v for b, v in zip(bottom, vals)]
    ax.set_xticks(range(len(variants)))
    ax.set_xticklabels(variants, rotation=35, ha="right", fontsize=7)
    ax.set_ylabel("stage time (ms, median, mean over frames)")
    # Whole bars, from zero, with the legend beside them rather than over them, top to bottom as stacked.
    ax.set_ylim(0.0, 1.05 * max(bottom + [1e-3]))
    handles, labels = ax.get_legend_handles_labels()
    ax.legend(handles[::-1], labels[::-1], fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.set_title(title)
    ax.grid(axis="y", alpha=0.3)
    return save(fig, out_dir, "stages-" + key, records)


def along_path(records, out_dir, key, title, col):
    """Frame time, FLIP and temporal error per frame along a camera path, one series a variant in
    its report-wide colour (`col`); a second row of FLIP and temporal error on the reflective and
    refractive pixels where scored."""
    regions = regions_of(records) or [REGIONS[0]]
    fig, axes = plt.subplots(len(regions), 3, figsize=(15, 4 * len(regions)), squeeze=False)
    flip_values = {i: [] for i in range(len(regions))}
    for v in sorted({rs.variant(r) for r in records}, key=rs.natural_key):
        rows = sorted((r for r in records if rs.variant(r) == v), key=lambda r: r["frame"])
        axes[0][0].plot([r["frame"] for r in rows], [r["frame_ms"]["median"] for r in rows], marker="o", ms=3, color=col[v], label=v)
        axes[0][0].scatter([r["frame"] for r in rows], [r["frame_ms"]["median"] for r in rows], s=12, color=col[v]).set_urls(point_links(rows))
        for i, (region, _, temporal_key) in enumerate(regions):
            scored = [r for r in rows if rs.metric(r, region, "flip") is not None]
            flips = [rs.metric(r, region, "flip") for r in scored]
            axes[i][1].plot([r["frame"] for r in scored], flips, marker="o", ms=3, color=col[v])
            axes[i][1].scatter([r["frame"] for r in scored], flips, s=12, color=col[v]).set_urls(point_links(scored))
            flip_values[i] += flips
            temporal = [(r["frame"], r[temporal_key]) for r in rows if temporal_key in r]
            if temporal:
                axes[i][2].plot([f for f, _ in temporal], [t for _, t in temporal], marker="o", ms=3, color=col[v])
    for i, (_, suffix, _) in enumerate(regions):
        for ax, label in zip(axes[i], ("frame time (ms, median)", "FLIP mean" + suffix, "temporal error" + suffix)):
            ax.set_xlabel("frame")
            ax.set_ylabel(label)
            ax.grid(alpha=0.3)
            axis_format.plain(ax.yaxis)
        axis_format.score_axis(axes[i][1], flip_values[i])
    for i in range(1, len(regions)):
        axes[i][0].set_visible(False)  # frame time is one per run, not per region
    axes[0][0].legend(fontsize=6, loc="upper left", bbox_to_anchor=(0.0, -0.18), ncol=2, frameon=False)
    fig.suptitle(title)
    return save(fig, out_dir, "path-" + key, records)


TABLE_SCRIPT = """<script>
// Click a column header to sort the table by it (numbers numerically).
document.querySelectorAll('table.sortable th').forEach((th, i) => th.addEventListener('click', () => {
  const body = th.closest('table').tBodies[0];
  const asc = th.dataset.asc !== '1'; th.dataset.asc = asc ? '1' : '0';
  const val = tr => { const t = tr.cells[i].dataset.v ?? tr.cells[i].textContent; const n = parseFloat(t); return isNaN(n) ? t : n; };
  [...body.rows].sort((a, b) => { const x = val(a), y = val(b); return (x > y ? 1 : x < y ? -1 : 0) * (asc ? 1 : -1); })
    .forEach(r => body.appendChild(r));
}));
</script>"""


def runs_table(records, out_dir, result_dir, table):
    """Every run: its images, setting, frame time, every metric of `table` on the whole image and the
    summarised ones on the reflective and refractive pixels, temporal error and error maps."""
    shown = [("whole", m, "") for m in table] + [("masked", m, " refl./refr.") for m in rs.summarised(table)]
    head = (["run", "image", "scene", "view", "size", "technique", "parameters", "frame ms"] +
            [m["label"] + suffix for _, m, suffix in shown] + ["temporal", "maps"])
    maps_of = ["diff"] + [m["key"] for m in table if m["colormap"]]
    rows = []
    for r in records:
        img = rs.result_link(out_dir, result_dir, r["images"]["png"])
        maps = ""
        if r["images"].get("maps"):
            # The maps the record lists (result sets older than that list had these three).
            written = r["metrics"].get("maps") or ("diff", "ssim", "flip")
            maps = " ".join('<a href="%s">%s</a>' % (html.escape(rs.result_link(out_dir, result_dir, r["images"]["maps"] + "/" + m + ".png")), m)
                            for m in maps_of if m in written)
        cells = [
            '<td data-v="%d"><a href="%s" title="open in the viewer">%d</a></td>' % (r["index"], html.escape(viewer.link(r["id"])), r["index"]),
            '<td><a href="%s"><img src="%s" width="96" loading="lazy" alt="%s"></a> <a href="%s">exr</a> <a href="%s">ref</a></td>'
            % (html.escape(img), html.escape(img), html.escape(r["id"]), html.escape(rs.result_link(out_dir, result_dir, r["images"]["exr"])),
               html.escape(rs.result_link(out_dir, result_dir, r["reference"]["png"]))),
            "<td>%s</td>" % html.escape(r["scene"]),
            "<td>%s</td>" % html.escape(rs.view_name(r)),
            "<td>%s</td>" % rs.resolution(r),
            "<td>%s</td>" % html.escape(r["label"]),
            "<td>%s</td>" % html.escape(r["parameters_text"]),
            "<td>%.2f</td>" % r["frame_ms"]["median"],
        ] + ["<td>%s</td>" % rs.metric_cell(m, rs.metric(r, region, m["key"])) for region, m, _ in shown] + [
            "<td>%s</td>" % rs.fmt(r.get("temporal_error"), "%.5f", missing=""),
            "<td>%s</td>" % maps,
        ]
        rows.append("<tr>" + "".join(cells) + "</tr>")
    return ('<table class="runs sortable"><thead><tr>' + "".join("<th>%s</th>" % h for h in head) + "</tr></thead><tbody>\n" + "\n".join(rows)
            + "\n</tbody></table>")


def markdown_summary(records, table):
    """Per scene and resolution: each variant's mean frame time and summarised metrics (of `table`),
    on the whole image and on the reflective and refractive pixels where the scene has them."""
    lines = []
    groups = collections.defaultdict(list)
    for r in records:
        groups[(r["scene"], rs.resolution(r))].append(r)
    for (scene, res), rows in sorted(groups.items()):
        regions = regions_of(rows) or [REGIONS[0]]
        metrics = [(region, suffix, m) for region, suffix, _ in regions for m in rs.summarised(table)]
        lines += ["", "### %s at %s" % (scene, res), "",
                  "| technique | frames | frame ms (median, mean over frames) | %s |" %
                  " | ".join(m["label"] + suffix for _, suffix, m in metrics),
                  "|---|---|---|" + "---|" * len(metrics)]
        by = collections.defaultdict(list)
        for r in rows:
            by[rs.variant(r)].append(r)
        for v, vs in sorted(by.items(), key=lambda item: rs.natural_key(item[0])):
            lines.append("| %s | %d | %.2f | %s |" % (v, len(vs), statistics.mean(r["frame_ms"]["median"] for r in vs), " | ".join(
                rs.metric_cell(m, rs.mean_known(rs.metric(r, region, m["key"]) for r in vs)) for region, _, m in metrics)))
        lines.append("| reference (whitted) | | %.2f | %s |" % (statistics.median(r["reference"]["frame_ms"] for r in rows),
                                                              " | ".join(rs.fmt(rs.best_value(m), "%g") for _, _, m in metrics)))
    return "\n".join(lines)


# The page: a table of contents, the verdict first, and nothing wider than the window (at 800 px
# too): tables too wide for it scroll inside their own box, figures shrink to the column.
PAGE = """<!doctype html><html><head><meta charset="utf-8"><meta name="viewport" content="width=device-width, initial-scale=1">
<link rel="icon" href="data:,">
<title>%(title)s</title><style>
body{font-family:sans-serif;margin:1em;max-width:1400px} h1{font-size:1.5em;overflow-wrap:anywhere}
h2,h3{overflow-wrap:anywhere} p{max-width:60em;overflow-wrap:anywhere}
nav.contents{border:1px solid #ccc;padding:0.3em 1em;margin:0.5em 0 1em;font-size:14px;max-width:40em}
nav.contents ul{margin:0.2em 0;padding-left:1.2em} nav.contents li.sub{margin-left:1.2em;list-style:circle}
.wide{max-width:100%%;overflow-x:auto} table{border-collapse:collapse;font-size:12px}
th,td{border:1px solid #ccc;padding:2px 5px} th{cursor:pointer;background:#eee}
table.device th{text-align:left;cursor:auto} .warning{color:#a40;font-weight:bold} .sentence{font-size:15px}
table.verdict{margin:0.4em 0 1em} figure{margin:0.5em 0 1.5em;max-width:100%%}
figure object{display:block;max-width:100%%;height:auto} figcaption{font-size:13px}
</style></head><body>
<h1>%(title)s</h1>
%(contents)s
%(warning)s
%(verdict)s
<h2 id="device">Measured on</h2>%(device)s
<p>%(runs)d runs. Data: <a href="%(csv)s">results.csv</a>, <a href="%(json)s">results.json</a>. The viewer shows techniques side by
side with their differences; a run's number in the table or its point in a chart opens it there. It reads the result set's own
images, which a browser lets a page read only from a web server: run <code>%(viewer)s</code> and open the address it prints.
%(clock)s</p>
%(figures)s
%(failures)s
<h2 id="runs">Every run</h2><p>Click a column header to sort.</p><div class="wide">%(table)s</div>
%(script)s</body></html>"""


def contents_html(entries):
    """The table of contents: (id, heading) or (id, heading, depth) entries, depth 1 indented."""
    items = ['<li class="%s"><a href="#%s">%s</a></li>' % ("sub" if (e[2] if len(e) > 2 else 0) else "", html.escape(e[0]),
                                                         html.escape(e[1])) for e in entries]
    return '<nav class="contents"><b>Contents</b><ul>%s</ul></nav>' % "".join(items)


def fail(message, status):
    """One line on standard error, and exit `status`: 2 for a result set's file that is malformed, 3
    for a report that cannot be written (`hybridlab report` adds nothing to it)."""
    sys.stderr.write("hybridlab: error: %s\n" % str(message).replace("\n", "; "))
    sys.exit(status)


class Inputs(collections.namedtuple("Inputs", "records table reference verdicts")):
    """What the report is drawn from, every file of the result set it reads checked."""


def read_inputs(result_dir):
    """Inputs of the result set in `result_dir`. ResultSetError or ImageError where one of its files
    is malformed (a record, experiment.json, config.toml, an image), before anything is written."""
    table = rs.metric_table(result_dir)
    records = rs.checked_records(result_dir, table)
    reference = viewer.reference_parameters(result_dir)
    for path in sorted({p for r in records for p in (r["images"]["exr"], r["reference"]["exr"])}):
        images.check(os.path.join(result_dir, path))
    verdicts = {(v.scene, v.size): v for v in verdict.verdicts(records, result_dir, table)}
    return Inputs(records, table, reference, verdicts)


def write_report(inputs, result_dir, out, into, baseline):
    """The report of `inputs` for the folder `out`, its files written into the folder `into`."""
    records, table, verdicts = inputs.records, inputs.table, inputs.verdicts
    os.makedirs(os.path.join(into, "figures"))
    colours = palette.setting_colours(records)  # one colour per setting for the whole report

    sections = []
    by_scene = collections.defaultdict(list)
    for r in records:
        by_scene[(r["scene"], rs.resolution(r))].append(r)
    for (scene, res), rows in sorted(by_scene.items()):
        key = "%s-%s" % (os.path.basename(scene).replace(".toml", ""), res)
        figs = speed_accuracy(verdicts[(scene, res)], into, key, "%s at %s: speed against accuracy" % (scene, res), colours) + [
                stage_breakdown(rows, into, key, "%s at %s: stage times" % (scene, res)),
                work_accuracy(rows, into, key, "%s at %s: rays per pixel against accuracy" % (scene, res), colours)]
        paths = collections.defaultdict(list)
        for r in rows:
            if r["frame"] >= 0:
                paths[r["view"]].append(r)
        for path, prs in sorted(paths.items()):
            figs.append(along_path(prs, into, key + "-" + path, "%s at %s along path %s" % (scene, res, path), colours))
        sections.append((scene, res, figs))
    failure_html, failure_md = failures.write_section(records, into, baseline, colours, table) or ("", [])
    device_html, device_md = device.write(result_dir, records)
    verdict_html, verdict_md = verdict.write(list(verdicts.values()), viewer.link)

    title = "hybridlab report: %s" % os.path.basename(os.path.abspath(result_dir))
    chart_sections = [("charts-%s-%s" % (rs.anchor(scene), res), "%s at %s" % (scene, res), figs) for scene, res, figs in sections]
    contents = ([("verdict", "Verdict")] + [("verdict-%s-%s" % (rs.anchor(v.scene), v.size), "%s at %s" % (v.scene, v.size), 1)
                                            for v in verdicts.values()]
                + [("device", "Measured on")] + [(i, t, 0) for i, t, _ in chart_sections]
                + ([("failures", "Where methods fail")] if failure_html else []) + [("runs", "Every run")])
    figure_html = []
    for section_id, heading, figs in chart_sections:
        figure_html.append('<h2 id="%s">%s</h2>' % (section_id, html.escape(heading)))
        figure_html += [figure_files.embed_html(f, into) for f in figs]
    page = PAGE % dict(
        title=html.escape(title), contents=contents_html(contents), warning=device.warning_html(result_dir, records),
        verdict=verdict_html, device=device_html, runs=len(records),
        csv=html.escape(rs.result_link(out, result_dir, "results.csv")), json=html.escape(rs.result_link(out, result_dir, "results.json")),
        viewer=html.escape(viewer.serve_command(result_dir, out)), clock=html.escape(timing.clock_note(records)),
        figures="\n".join(figure_html), failures=failure_html, table=runs_table(records, out, result_dir, table), script=TABLE_SCRIPT)
    with open(os.path.join(into, "index.html"), "w") as f:
        f.write(page)
    viewer.write_viewer(records, out, result_dir, title,
                        {(v.scene, v.size, s.name): s.not_applicable for v in verdicts.values() for s in v.excluded()},
                        palette.hex_colours(colours), table, inputs.reference, into)
    md = ["# " + title] + verdict_md + ["", "## Measured on"] + device_md + ["", "## Every setting", "",
                                                    "%d runs; figures in figures/ (SVG and PDF); every run in index.html. %s" % (
                                                        len(records), timing.clock_note(records)),
                                                    markdown_summary(records, table)]
    for scene, res, figs in sections:
        md += ["", "## %s at %s" % (scene, res)] + ["![](%s) ([PDF](%s))" % (os.path.relpath(f, into), os.path.relpath(f, into)[:-4] + ".pdf")
                                                    for f in figs]
    md += failure_md
    with open(os.path.join(into, "report.md"), "w") as f:
        f.write("\n".join(md) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("result_dir")
    ap.add_argument("--out", required=True)
    ap.add_argument("--baseline", default=failures.BASELINE_SCENE,
                    help="the scene whose path is the \"where methods fail\" section's baseline (default: %(default)s)")
    ap.add_argument("--check-only", action="store_true", help="check the result set's files and write nothing")
    a = ap.parse_args()
    if viewer.missing():
        fail(viewer.missing(), 1)
    # Every file the report reads is checked before anything is written: bad input leaves nothing.
    try:
        inputs = read_inputs(a.result_dir)
    except (rs.ResultSetError, images.ImageError) as e:
        fail(e, 2)
    except OSError as e:
        fail("%s: cannot be read (%s)" % (e.filename or a.result_dir, e.strerror), 3)
    if a.check_only:
        return
    # Drawn beside --out and moved into it whole: a failure leaves it as it was.
    try:
        with staged_folder.staged(a.out) as into:
            write_report(inputs, a.result_dir, a.out, into, a.baseline)
    except OSError as e:
        fail("%s: cannot be written (%s)" % (a.out, e.strerror or e), 3)
    print("report: %s" % os.path.join(a.out, "index.html"))
    print("viewer: %s (%s)" % (os.path.join(a.out, "viewer.html"), viewer.serve_command(a.result_dir, a.out)))


if __name__ == "__main__":
    main()
