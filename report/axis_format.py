"""Value axes that read as plain numbers at every scale: no offset ("1e-6+9.999e-1") and no
multiplier, and a score axis never narrower than the scores' tolerance, so that differences a
reader should not see as differences (a 2e-6 dip in SSIM) draw flat instead of filling the axis."""
from matplotlib.ticker import ScalarFormatter

# Score differences smaller than this are noise, not a change of quality: SSIM and FLIP are
# printed to 4 decimals in every table, and a technique that changes nothing of substance moves
# its scores by less than a thousandth between frames.
SCORE_TOLERANCE = 1e-3


def plain(axis):
    """Tick labels as plain decimals, with no offset or scientific multiplier."""
    formatter = ScalarFormatter(useOffset=False)
    formatter.set_scientific(False)
    axis.set_major_formatter(formatter)


def score_axis(ax, values, tolerance=SCORE_TOLERANCE):
    """ax's y axis for scores `values`: plain ticks, and at least `tolerance` wide about the
    values' middle."""
    plain(ax.yaxis)
    values = [v for v in values if v is not None]
    if values:
        lo, hi = min(values), max(values)
        if hi - lo < tolerance:
            middle = 0.5 * (lo + hi)
            ax.set_ylim(middle - tolerance, middle + tolerance)
