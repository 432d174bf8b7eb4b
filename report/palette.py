"""The report's colours: one hue per technique, and per technique one shade per setting (darker to
lighter in the settings' name order), so that a chart with a dozen settings still reads as a few
techniques. The colours are chosen once for the whole result set (setting_colours on every
record), so that a setting has the same colour on every chart and in the viewer, whichever
settings a chart shows."""
import colorsys

import matplotlib.colors as mcolors
import matplotlib.pyplot as plt

import results as rs


def shades(rgb, n):
    """`n` shades of `rgb` by lightness, darkest first; the middle one is `rgb` itself."""
    h, l, s = colorsys.rgb_to_hls(*rgb)
    if n == 1:
        return [rgb]
    lo, hi = max(0.18, l - 0.22), min(0.78, l + 0.22)
    return [colorsys.hls_to_rgb(h, lo + (hi - lo) * i / (n - 1), s) for i in range(n)]


def setting_colours(records):
    """{setting name (results.variant): colour} for the records' settings: pass every record of the
    result set, so that each setting keeps its colour whichever subset a chart draws."""
    by_technique = {}
    for r in records:
        by_technique.setdefault(r["technique"], set()).add(rs.variant(r))
    hues = plt.get_cmap("tab10")
    colours = {}
    for i, technique in enumerate(sorted(by_technique)):
        base = mcolors.to_rgb(hues(i % hues.N))
        names = sorted(by_technique[technique], key=rs.natural_key)
        colours.update(zip(names, shades(base, len(names))))
    return colours


def hex_colours(colours):
    """The same colours as "#rrggbb" (the viewer's, and the SVGs' fill)."""
    return {name: mcolors.to_hex(c) for name, c in colours.items()}
