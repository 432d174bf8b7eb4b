"""Frame times to trust: the median's interval, paired comparisons over the runner's rounds, and the
tie rule that says when one setting is faster than another.

The runner times every setting of a group (one scene, view, frame and size: a record's
`timing.group`) in interleaved rounds, and the reference in the same rounds; a record holds its
time in each round (`timing.frame_ms_rounds`, the k-th element in round k for every run of the
group) and the reference's (`timing.reference_ms_rounds`). Result sets written before that have
only each run's median, min and max over its repeats; everything here falls back to what the report
did with those.

- median_interval: the median of n values and its distribution-free 95% interval [x_(l), x_(u)],
  order statistics chosen from the binomial(n, 1/2) distribution (the number of values below the
  true median): the narrowest symmetric pair u = n + 1 - l whose coverage is at least 95%. No
  assumption about the shape of the distribution (frame times are skewed: a slow outlier, never a
  fast one). Below 6 values no such pair exists (x_(1), x_(n) cover 1 - 2 / 2^n < 95%).
- Paired comparison of settings A and B: in every group where both were timed, the ratios
  A_k / B_k of their times in the same round k, pooled over the groups; their median and interval
  as above. A load that drifts during a run (another process, a clock that changes) hits both
  settings of a round alike and cancels in their ratio, which comparing two medians timed at
  different moments does not.
- The tie rule: A is faster than B only when the paired ratio's interval lies wholly below 1 (the
  difference is beyond the timing noise) AND its median is below 1 - tolerance (the difference
  matters), the tolerance being the precision the runner timed to (`timing.precision`, 3% by
  default). Otherwise they are tied. Where the records hold no rounds to pair, A is faster when the
  intervals of the two medians do not overlap and A's median is below 1 - tolerance of B's; where
  they hold no intervals either, when its median is lower (a result set measured before intervals:
  no tie but an exact one).
- A setting measured over several runs (views, frames of a path) has as its time the median of its
  runs' medians; its interval is [median of the runs' ci_low, median of the runs' ci_high]: the
  median is monotone in every run's time, so it lies there whenever each run's median lies in its
  own interval. Its speed-up over the reference pools the per-round ratios reference_k / own_k of
  all its runs."""
import collections
import math
import statistics

CONFIDENCE = 0.95
DEFAULT_TOLERANCE = 0.03
MIN_VALUES = 6  # the fewest values with a 95% interval of the median
# Other processes' share of the cores above which a run's times answer for a loaded machine: two
# busy loops on this project's two-core machine slowed settings 1.6x to 3.0x, unequally.
BUSY_MACHINE = 0.2
FASTER, SLOWER, TIED = "faster", "slower", "tied"

# The clocks a record may hold: its key (the summary's place), where its per-round times are, and
# what it measures. frame_ms is the one every record has and every table uses.
Clock = collections.namedtuple("Clock", "key rounds_key what")
CLOCKS = (Clock("frame_ms", "frame_ms_rounds", "wall time"),
          Clock("cpu_ms", "cpu_ms_rounds", "CPU time (the process's, all threads)"),
          Clock("device_ms", "device_ms_rounds", "device time (GPU timestamps)"))
WALL = CLOCKS[0]


class Interval(collections.namedtuple("Interval", "median low high")):
    """A median with its 95% interval [low, high]."""

    def text(self, spec="%.2f", suffix=""):
        """"1.70x (1.64-1.77)" for spec "%.2f" and suffix "x"."""
        return (spec + "%s (" + spec + "-" + spec + ")") % (self.median, suffix, self.low, self.high)


SettingTime = collections.namedtuple("SettingTime", "ms low high is_interval")
SettingTime.__doc__ = """A setting's time over its runs: the median of their medians, and a bar from
`low` to `high`: the median's 95% interval where every run has one (`is_interval`), else the
fastest and slowest run's median (what the report drew before intervals)."""


def interval_ranks(n, confidence=CONFIDENCE):
    """The 1-based ranks (l, n + 1 - l) of the narrowest symmetric pair of order statistics of n
    values that holds the median with probability at least `confidence`; None when even the
    smallest and largest do not (n < 6 at 95%)."""
    if n < 1:
        return None
    total = 2 ** n
    below = 0  # P(B < l) * 2^n for B ~ binomial(n, 1/2), accumulated as l grows
    best = None
    for l in range(1, (n + 1) // 2 + 1):
        below += math.comb(n, l - 1)
        if 1.0 - 2.0 * below / total < confidence:
            break
        best = l
    return (best, n + 1 - best) if best else None


def median_interval(values, confidence=CONFIDENCE):
    """Interval(median, x_(l), x_(u)) of `values` (interval_ranks); None with too few values."""
    ranks = interval_ranks(len(values), confidence)
    if ranks is None:
        return None
    ordered = sorted(values)
    return Interval(statistics.median(ordered), ordered[ranks[0] - 1], ordered[ranks[1] - 1])


def summary(r, clock=WALL):
    """A record's {median, min, max[, ci_low, ci_high]} on `clock`; None where it has none."""
    if clock.key == "frame_ms":
        return r.get("frame_ms")
    return (r.get("timing") or {}).get(clock.key)


def rounds(r, clock=WALL):
    """A record's time in each round on `clock`; None in a result set without rounds."""
    return (r.get("timing") or {}).get(clock.rounds_key) or None


def group(r):
    """The group a record was timed in (runs of one group share their rounds); None without rounds."""
    return (r.get("timing") or {}).get("group")


def has_rounds(records):
    return any(rounds(r) and group(r) is not None for r in records)


def has_intervals(records):
    """Whether any record says how precise its median is (an interval, or rounds to make one)."""
    return any("ci_low" in (r.get("frame_ms") or {}) for r in records) or has_rounds(records)


def tolerance(records):
    """The result set's precision (the runner's `timing.precision`, the coarsest where runs
    differ), the difference the tie rule asks for; DEFAULT_TOLERANCE where the records name none."""
    given = [r["timing"]["precision"] for r in records if isinstance((r.get("timing") or {}).get("precision"), (int, float))]
    return max(given) if given else DEFAULT_TOLERANCE


def _by_group(runs, clock):
    out = {}
    for r in runs:
        if group(r) is not None and rounds(r, clock):
            out[group(r)] = rounds(r, clock)
    return out


def round_ratios(a_runs, b_runs, clock=WALL):
    """A_k / B_k for every round k of every group that both A's and B's runs were timed in, groups
    in name order."""
    a, b = _by_group(a_runs, clock), _by_group(b_runs, clock)
    ratios = []
    for g in sorted(set(a) & set(b)):
        if len(a[g]) == len(b[g]):
            ratios += [x / y for x, y in zip(a[g], b[g]) if x > 0 and y > 0]
    return ratios


def paired_ratio(a_runs, b_runs, clock=WALL):
    """A's time over B's, paired over their common rounds: Interval, or None without 6 pairs."""
    return median_interval(round_ratios(a_runs, b_runs, clock))


def reference_ratios(runs):
    """reference_k / own_k over every round of every run."""
    ratios = []
    for r in runs:
        own, ref = rounds(r), (r.get("timing") or {}).get("reference_ms_rounds") or []
        if own and len(own) == len(ref):
            ratios += [x / y for x, y in zip(ref, own) if x > 0 and y > 0]
    return ratios


def _recorded_speedup(runs, kind):
    """The runner's own `speedup[kind]` of a setting measured in one run, as an Interval."""
    if len(runs) != 1:
        return None
    s = (runs[0].get("speedup") or {}).get(kind)
    return Interval(s["ratio"], s["low"], s["high"]) if s and all(k in s for k in ("ratio", "low", "high")) else None


def speedup_over_reference(runs):
    """How many times faster than the reference a setting is: its record's `speedup.reference`
    where it was measured in one run, else the pooled per-round ratios; None without rounds."""
    return _recorded_speedup(runs, "reference") or median_interval(reference_ratios(runs))


def speedup_over(runs, other_runs, recorded=None):
    """How many times faster than `other_runs` the setting of `runs` is, paired over their common
    rounds (other_k / own_k); with `recorded` ("rt_only"), the record's own `speedup[recorded]`
    where the setting has one run. None without rounds to pair."""
    return (recorded and _recorded_speedup(runs, recorded)) or paired_ratio(other_runs, runs)


def speedup_cell(runs, other_runs, fallback, spec="%.2f"):
    """A table's speed-up of `runs` over `other_runs` (other's time / this one's): "1.70x
    (1.64-1.77)" where their records hold rounds to pair, else `fallback` (the table's text from the
    medians, as printed before rounds). Every speed-up column of the paper tables is this cell."""
    iv = speedup_over(runs, other_runs)
    return iv.text(spec, "x") if iv else fallback


def setting_time(runs, clock=WALL):
    """SettingTime of a setting's runs on `clock`; None where a run lacks that clock."""
    sums = [summary(r, clock) for r in runs]
    if not sums or any(s is None for s in sums):
        return None
    medians = [s["median"] for s in sums]
    ms = statistics.median(medians)
    if all("ci_low" in s and "ci_high" in s for s in sums):
        return SettingTime(ms, statistics.median(s["ci_low"] for s in sums), statistics.median(s["ci_high"] for s in sums), True)
    return SettingTime(ms, min(medians), max(medians), False)


def _beats(ratios, tol):
    iv = median_interval(ratios)
    return iv is not None and iv.high < 1.0 and iv.median < 1.0 - tol


def compare(a_runs, b_runs, tol=DEFAULT_TOLERANCE):
    """(FASTER, SLOWER or TIED: A against B by the tie rule, the basis: "paired rounds",
    "intervals" or "medians")."""
    ratios = round_ratios(a_runs, b_runs)
    if len(ratios) >= MIN_VALUES:
        if _beats(ratios, tol):
            return FASTER, "paired rounds"
        if _beats([1.0 / x for x in ratios], tol):
            return SLOWER, "paired rounds"
        return TIED, "paired rounds"
    a, b = setting_time(a_runs), setting_time(b_runs)
    if a.is_interval and b.is_interval:
        if a.high < b.low and a.ms < (1.0 - tol) * b.ms:
            return FASTER, "intervals"
        if b.high < a.low and b.ms < (1.0 - tol) * a.ms:
            return SLOWER, "intervals"
        return TIED, "intervals"
    return (FASTER if a.ms < b.ms else SLOWER if a.ms > b.ms else TIED), "medians"


def fastest(candidates, runs_of, tol=DEFAULT_TOLERANCE, key=None):
    """The candidates no other candidate is faster than by the tie rule: the fastest and those
    tied with it. Which of them has the lowest median does not change the answer (the set depends
    only on the pairwise comparisons), and it is ordered by `key` (default: as given), so that
    two measurements of the same tie name it alike. `runs_of(c)`: a candidate's records."""
    unbeaten = [c for c in candidates
                if not any(o is not c and compare(runs_of(o), runs_of(c), tol)[0] == FASTER for o in candidates)]
    if not unbeaten and candidates:  # a cycle of "faster" (medians of ratios need not compose): the lowest median
        unbeaten = [min(candidates, key=lambda c: setting_time(runs_of(c)).ms)]
    return sorted(unbeaten, key=key) if key else unbeaten


def describe_rule(records):
    """One paragraph for a report's intro: which test decides "faster" and "tied" on this result
    set, and why."""
    tol = tolerance(records)
    if has_rounds(records):
        return ("Times are wall-clock frame times (frame_ms), medians with their 95%% interval (order statistics, no "
                "assumption about the distribution). Each setting was timed in interleaved rounds with the other settings "
                "of its scene, view, frame and size and with the reference, so two settings are compared by the ratio of "
                "their times in the same round (a load that drifts hits both alike and cancels): A is faster than B only "
                "when that ratio's 95%% interval lies wholly below 1 and its median below %.2f (the set's precision, "
                "%.0f%%); otherwise they are tied, and tied settings are named together." % (1.0 - tol, 100.0 * tol))
    if has_intervals(records):
        return ("Times are wall-clock frame times (frame_ms), medians with their 95%% interval. The records hold no "
                "rounds to pair, so A is faster than B only when their intervals do not overlap and A's median is more "
                "than %.0f%% below B's; otherwise they are tied, and tied settings are named together." % (100.0 * tol))
    return ("Times are wall-clock frame times (frame_ms), medians over each run's repeats. This result set has no "
            "intervals (it was measured before the runner timed settings in rounds): the lower median is called "
            "faster however close, and bars span the fastest to the slowest run.")


def caveats(records):
    """Sentences on runs whose times the runner itself doubts: the precision not reached in the
    rounds allowed, no steady state after the warm-up, other processes' load while timed
    (`timing.other_load`) unless the rounds ran ahead of it (`timing.priority`), the GPU's clocks
    changed while timed."""
    timed = [r.get("timing") or {} for r in records]
    out = []
    missed = sum(t.get("precision_reached") is False for t in timed)
    if missed:
        out.append("%d of %d runs did not reach the precision asked for (%.0f%%) in the rounds allowed: their intervals "
                   "are wider, and more of their comparisons tied." % (missed, len(records), 100.0 * tolerance(records)))
    unsteady = sum(t.get("steady") is False for t in timed)
    if unsteady:
        out.append("%d of %d runs had not reached a steady frame time after their warm-up." % (unsteady, len(records)))
    # Rounds at real-time priority (`run --realtime`) ran ahead of the load: it took only what the
    # kernel's real-time throttling leaves other processes, so their ranks are not the loaded
    # machine's.
    ahead = [t for t in timed if t.get("priority") == "realtime"]
    if ahead:
        loads = [t["other_load"] for t in ahead if t.get("other_load") is not None]
        out.append("%d of %d runs were timed at real-time priority (run --realtime), ahead of other processes%s." % (
            len(ahead), len(records), " (which used up to %.0f%% of the cores meanwhile)" % (100.0 * max(loads)) if loads else ""))
    loads = [t["other_load"] for t in timed if t.get("other_load") is not None and t.get("priority") != "realtime"]
    loaded = [x for x in loads if x > BUSY_MACHINE]
    if loaded:
        out.append("%d of %d runs were timed while other processes used more than %.0f%% of the machine's cores (up to "
                   "%.0f%%): load slows settings unequally (a parallel frame waits for its preempted thread, a serial one "
                   "barely notices), so their ranks answer for a loaded machine; time them on a quiet one, or with run "
                   "--realtime ahead of the load, to rank for an idle machine." % (len(loaded), len(records), 100.0 * BUSY_MACHINE, 100.0 * max(loaded)))
    clocks = sum(bool((t.get("gpu_clocks") or {}).get("changed")) for t in timed)
    if clocks:
        out.append("The GPU's clocks changed while %d of %d runs were timed." % (clocks, len(records)))
    return out


def clock_note(records):
    """Which clock the report's times are on, and the charts on other clocks that it adds."""
    others = [c for c in CLOCKS[1:] if any(summary(r, c) for r in records)]
    text = ("Times are wall time per frame (the records' frame_ms: from a frame's start to its finished image), in every "
            "table and chart unless it says otherwise.")
    if others:
        text += " Each scene's speed-accuracy chart is drawn again on %s, where its records hold %s." % (
            " and on ".join(c.what for c in others), " and ".join("timing." + c.key for c in others))
    return text
