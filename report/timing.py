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
- Paired comparison of settings A and B: the ratios A_k / B_k of their times in the same round k
  of the same timing (a record's `timing.timing_id`: the runner's call that timed the group; a
  group split over processes, shards or resumed runs has several, which never pair), pooled over
  the timings both were in; their median and interval as above. A load that drifts during a run
  (another process, a clock that changes) hits both settings of a round alike and cancels in their
  ratio, which comparing two medians timed at different moments does not.
- The rule (fastest_of_rounds, compare_rounds; the runner's experiments/runner/fastest_set.h is the
  same, held to it by tests/fixtures/fastest_set_cases.json): A is faster than B only when the
  paired ratio's whole interval lies below 1 - tolerance and A's time below 1 - tolerance of B's,
  the tolerance being the precision the runner timed to (`timing.precision`, 3% by default); tied
  when both lie inside [1 - tolerance, 1 / (1 - tolerance)]; otherwise not decided. The fastest
  settings are a confidence set for the fastest: the empirical best and every setting it is not
  faster than, the k - 1 comparisons each at 1 - 0.05 / (k - 1). Where the records hold no rounds
  (result sets measured before them), the rules they were reported by: A is faster when the
  intervals of the two medians do not overlap and A's median is below 1 - tolerance of B's; where
  they hold no intervals either, when its median is lower (no tie but an exact one).
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
# Other processes' share of the cores above which a run's times answer for a loaded machine: two
# busy loops on this project's two-core machine slowed settings 1.6x to 3.0x, unequally.
BUSY_MACHINE = 0.2
FASTER, SLOWER, TIED, NOT_DECIDED = "faster", "slower", "tied", "not decided"
SINGLE = "single"  # a fastest set of one setting
PAIRED = "paired rounds"

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
    smallest and largest do not (n < 6 at 95%). The binomial terms C(n, i) / 2^n are formed in log
    space, as the runner's intervalRank forms them (the two choose the same ranks, and the sum
    costs no big integers at 100000 rounds)."""
    best = 0
    below = 0.0  # P(B < l) for B ~ binomial(n, 1/2), accumulated as l grows
    log_term = -n * math.log(2.0)
    for l in range(1, (n + 1) // 2 + 1):
        below += math.exp(log_term)
        log_term += math.log(n - (l - 1)) - math.log(l)
        if 1.0 - 2.0 * below < confidence:
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


def timing_key(r):
    """What a record's rounds pair with: its `timing.timing_id`, the runner's call that timed them;
    in a set written before timing ids, its group (rounds then pair by group name and count, which
    a group split over processes by --max-runs, --resume or shards may fake); None without rounds."""
    t = r.get("timing") or {}
    if t.get("timing_id"):
        return t["timing_id"]
    return "group " + t["group"] if t.get("group") is not None else None


def setting_rounds(runs, clock=WALL):
    """{timing key: the setting's time in each of its rounds} over its runs that have rounds."""
    out = {}
    for r in runs:
        if timing_key(r) is not None and rounds(r, clock):
            out[timing_key(r)] = rounds(r, clock)
    return out


def paired_ratios(a, b):
    """A_k / B_k over the rounds of every timing both setting_rounds `a` and `b` were in (timings in
    key order); none across two timings."""
    ratios = []
    for key in sorted(set(a) & set(b)):
        if len(a[key]) == len(b[key]):
            ratios += [x / y for x, y in zip(a[key], b[key]) if x > 0 and y > 0]
    return ratios


def round_ratios(a_runs, b_runs, clock=WALL):
    """A_k / B_k for every round k of every timing that both A's and B's runs were in."""
    return paired_ratios(setting_rounds(a_runs, clock), setting_rounds(b_runs, clock))


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


def _in_band(x, tol):
    return 1.0 - tol <= x <= 1.0 / (1.0 - tol)


def compare_ratio(iv, tol):
    """A ratio A/B's Interval (or None) against the band [1 - tol, 1 / (1 - tol)]: FASTER wholly
    below it, SLOWER wholly above, TIED wholly inside, NOT_DECIDED otherwise or without one."""
    if iv is None:
        return NOT_DECIDED
    if iv.high < 1.0 - tol:
        return FASTER
    if iv.low > 1.0 / (1.0 - tol):
        return SLOWER
    return TIED if _in_band(iv.low, tol) and _in_band(iv.high, tol) else NOT_DECIDED


def rounds_time(a):
    """A setting's time from its setting_rounds: the median over its timings of its median in each
    (the median of its runs' medians); None without rounds."""
    medians = [statistics.median(v) for v in a.values() if v]
    return statistics.median(medians) if medians else None


def compare_rounds(a, b, tol, confidence=CONFIDENCE):
    """A against B from their setting_rounds: the paired ratio's interval at `confidence` by
    compare_ratio, and their times' ratio on the same side of the band (or inside it, for TIED);
    NOT_DECIDED where the two disagree (rounds pooled over frames where A is faster on some and B on
    others) or nothing pairs."""
    ratios = paired_ratios(a, b)
    if not ratios:
        return NOT_DECIDED
    by_rounds = compare_ratio(median_interval(ratios, confidence), tol)
    times = rounds_time(a) / rounds_time(b)
    agree = {FASTER: times < 1.0 - tol, SLOWER: times > 1.0 / (1.0 - tol), TIED: _in_band(times, tol)}.get(by_rounds, True)
    return by_rounds if agree else NOT_DECIDED


def comparison_confidence(settings, family=CONFIDENCE):
    """The confidence of each of the k - 1 comparisons with the empirical best (Bonferroni)."""
    return family if settings <= 2 else 1.0 - (1.0 - family) / (settings - 1)


def rounds_for_decision(settings, family=CONFIDENCE):
    """The fewest paired rounds with which the best of `settings` can be told apart from each other
    one: 6 for two settings, 10 for 16 (the runner times at least these)."""
    if settings <= 1:
        return 0
    n = 1
    while interval_ranks(n, comparison_confidence(settings, family)) is None:
        n += 1
    return n


FastestSet = collections.namedtuple("FastestSet", "settings best decision unpaired basis")
FastestSet.__doc__ = """The fastest settings: `settings` (the set, ordered), `best` (the empirical
best), `decision` (SINGLE, TIED or NOT_DECIDED), `unpaired` (members kept because they share no
round with the best) and `basis` (PAIRED, "intervals" or "medians": which rule decided)."""


def fastest_of_rounds(settings, tol, family=CONFIDENCE):
    """The fastest set of a list of setting_rounds, as (indices of the members in order, index of
    the best, decision, unpaired): a confidence set for the fastest. The empirical best (the lowest
    rounds_time, the first of equal ones) is compared with each of the k - 1 others at
    comparison_confidence (Bonferroni); a setting leaves only when it is SLOWER than the best so.
    The true fastest leaves only when one of its k - 1 comparisons wrongly finds it slower, so the
    set holds it with probability at least `family`. Tied: every other member TIED with the best;
    otherwise not decided. The runner's fastestSet (experiments/runner/fastest_set.h) is the same
    rule; tests/fixtures/fastest_set_cases.json holds the two to it."""
    times = [rounds_time(s) for s in settings]
    timed = [i for i, t in enumerate(times) if t is not None]
    best = min(timed, key=lambda i: times[i]) if timed else 0
    confidence = comparison_confidence(len(settings), family)
    members, unpaired, all_tied = [], 0, True
    for i, s in enumerate(settings):
        if i == best:
            members.append(i)
            continue
        if not paired_ratios(s, settings[best]):
            members.append(i)
            unpaired += 1
            all_tied = False
            continue
        order = compare_rounds(s, settings[best], tol, confidence)
        if order == SLOWER:
            continue
        members.append(i)
        all_tied = all_tied and order == TIED
    decision = SINGLE if len(members) == 1 else TIED if all_tied else NOT_DECIDED
    return members, best, decision, unpaired


def compare(a_runs, b_runs, tol=DEFAULT_TOLERANCE):
    """(FASTER, SLOWER, TIED or NOT_DECIDED: A against B, the basis: PAIRED, "intervals" or
    "medians"). Where either has rounds: compare_rounds at 95%, paired within timings (no rounds in
    common, or fewer than 6: not decided). In a result set without rounds, the rules it was
    reported by before: the medians' intervals apart and the medians more than the tolerance
    apart; without intervals, the lower median (tied only when equal)."""
    if has_rounds(a_runs) or has_rounds(b_runs):
        a, b = setting_rounds(a_runs), setting_rounds(b_runs)
        return (compare_rounds(a, b, tol) if a and b else NOT_DECIDED), PAIRED
    a, b = setting_time(a_runs), setting_time(b_runs)
    if a.is_interval and b.is_interval:
        if a.high < b.low and a.ms < (1.0 - tol) * b.ms:
            return FASTER, "intervals"
        if b.high < a.low and b.ms < (1.0 - tol) * a.ms:
            return SLOWER, "intervals"
        return TIED, "intervals"
    return (FASTER if a.ms < b.ms else SLOWER if a.ms > b.ms else TIED), "medians"


def fastest(candidates, runs_of, tol=DEFAULT_TOLERANCE, key=None):
    """The FastestSet of `candidates` (`runs_of(c)`: a candidate's records), its settings ordered by
    `key` (default: as given). With rounds: fastest_of_rounds. In a result set without rounds, the
    rule it was reported by before: the candidates no other is faster than by compare (a cycle:
    the lowest median), tied when more than one."""
    if not candidates:
        return FastestSet([], None, NOT_DECIDED, 0, PAIRED)
    if any(has_rounds(runs_of(c)) for c in candidates):
        members, best, decision, unpaired = fastest_of_rounds([setting_rounds(runs_of(c)) for c in candidates], tol)
        chosen, basis = [candidates[i] for i in members], PAIRED
        best = candidates[best]
    else:
        chosen = [c for c in candidates
                  if not any(o is not c and compare(runs_of(o), runs_of(c), tol)[0] == FASTER for o in candidates)]
        if not chosen:  # a cycle of "faster" (medians of ratios need not compose): the lowest median
            chosen = [min(candidates, key=lambda c: setting_time(runs_of(c)).ms)]
        best = min(chosen, key=lambda c: setting_time(runs_of(c)).ms)
        decision, unpaired = (SINGLE if len(chosen) == 1 else TIED), 0
        basis = "intervals" if all(setting_time(runs_of(c)).is_interval for c in candidates) else "medians"
    return FastestSet(sorted(chosen, key=key) if key else chosen, best, decision, unpaired, basis)


def has_timing_ids(records):
    return any((r.get("timing") or {}).get("timing_id") for r in records)


def describe_rule(records):
    """One paragraph for a report's intro: which test decides "faster", "tied" and "not decided" on
    this result set, and why."""
    tol = tolerance(records)
    if has_rounds(records):
        pairing = ("in the same round of the same timing (the runner's call that timed them: a group split over "
                   "processes, shards or resumed runs is not paired across them)" if has_timing_ids(records) else
                   "in the same round of the same group (this set predates timing ids: a group split over processes, "
                   "shards or resumed runs cannot be told apart)")
        return ("Times are wall-clock frame times (frame_ms), medians with their 95%% interval (order statistics, no "
                "assumption about the distribution). Each setting was timed in interleaved rounds with the other settings "
                "of its scene, view, frame and size and with the reference, so two settings are compared by the ratio of "
                "their times %s: A is faster than B only when that ratio's 95%% interval lies wholly below %.2f (the "
                "set's precision, %.0f%%) and A's median time too; slower likewise above %.2f; tied when both lie inside "
                "%.2f-%.2f; otherwise not decided. A row's fastest settings are a 95%% confidence set for the fastest: the "
                "setting with the lowest median and every setting it is not faster than, each comparison at 1 - 0.05 / "
                "(k - 1) for k settings; a row naming several says whether they are tied or not decided (the rounds "
                "cannot tell them apart). With fewer paired rounds than a comparison needs (6 for two settings, 10 for "
                "16) nothing is called faster." % (pairing, 1.0 - tol, 100.0 * tol, 1.0 / (1.0 - tol), 1.0 - tol,
                                                   1.0 / (1.0 - tol)))
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
    (`timing.other_load`) unless the rounds ran ahead of it (`timing.priority`), groups timed by
    several calls (whose rounds do not all pair), the GPU's clocks changed while timed."""
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
    ids = collections.defaultdict(set)
    for t in timed:
        if t.get("timing_id"):
            ids[t.get("group")].add(t["timing_id"])
    split = sorted(g for g, found in ids.items() if len(found) > 1)
    if split:
        out.append("%d of %d groups were timed by more than one call of the runner (split by --max-runs, --resume or "
                   "shards): their rounds pair only within each call, and settings with no call in common are not "
                   "decided against each other." % (len(split), len(ids)))
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
