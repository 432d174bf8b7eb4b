"""Figures of the report as files (SVG and PDF in figures/) and as they appear in its pages: the
SVG's points link to the viewer, the page embeds the SVG as an <object> so that those links work."""
import html
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import results as rs  # noqa: E402
import viewer  # noqa: E402


def device_note(records):
    """Where a chart's runs were measured on more than one device (a result set merged or resumed
    with --allow-mixed-devices, whose runs each keep their `device`): a footnote numbering the
    devices and naming the settings measured on each; None on one device."""
    devices, settings = [], []
    for r in records:
        d = r.get("device")
        if d not in devices:
            devices.append(d)
            settings.append([])
        v = rs.variant(r)
        if v not in settings[devices.index(d)]:
            settings[devices.index(d)].append(v)
    if len(devices) < 2:
        return None
    return "\n".join(["MIXED devices: times do not compare across them"] +
                     ["(%d) %s: %s" % (i + 1, rs.device_summary(d), ", ".join(sorted(vs, key=rs.natural_key)))
                      for i, (d, vs) in enumerate(zip(devices, settings))])


def save(fig, out_dir, name, records=()):
    """figures/NAME.svg and .pdf, with device_note(records) under the chart where the runs drawn
    were measured on several devices; returns the SVG's path."""
    note = device_note(records)
    if note:
        fig.text(0.01, -0.02, note, fontsize=7, va="top", ha="left", color="#a40", wrap=True)
    paths = []
    for ext in ("svg", "pdf"):
        p = os.path.join(out_dir, "figures", name + "." + ext)
        fig.savefig(p, bbox_inches="tight")
        paths.append(p)
    plt.close(fig)
    # The points' links (set_urls) open the viewer in the whole window, not inside the <object>
    # that shows the figure in index.html.
    with open(paths[0]) as f:
        svg = f.read()
    with open(paths[0], "w") as f:
        f.write(svg.replace("<a xlink:href=", '<a target="_top" xlink:href='))
    return paths[0]


def point_links(records):
    """The viewer on each run, from a figure in figures/."""
    return [viewer.link(r["id"], "figures") for r in records]


def embed_html(svg, out_dir):
    """The figure in index.html: an <object>, not an <img>, so that its points link to the viewer,
    with its files (SVG and PDF) named beside it."""
    r = os.path.relpath(svg, out_dir)
    return ('<figure><object data="%s" type="image/svg+xml"></object><figcaption>%s: <a href="%s">SVG</a>, <a href="%s">PDF</a>'
            '</figcaption></figure>' % (html.escape(r), html.escape(os.path.basename(r)[:-4]), html.escape(r), html.escape(r[:-4] + ".pdf")))
