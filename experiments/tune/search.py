"""The search of `hybridlab tune`: the fastest setting of a scene's techniques that reaches a
quality target, and the front of time against quality, found without a full sweep.

Rendering is not done here: an evaluator renders and times a stage's settings (stages.py renders
them with `hybridlab run`; tests/tune/tune_search_test.py uses a synthetic cost and quality
model), so that the search can be checked against a known optimum.

The stages, each one group of settings timed in interleaved rounds beside rt_only (the runner's
protocol, so that every comparison is a paired interval within one timing):

1. screen: every point of each technique's grid (its declared search space: techniques declare the
   knobs worth searching and their ranges, `hybridlab techniques --json`), rendered once for its
   quality and timed in one round after a warm-up frame for a rough time. Quality is deterministic
   (a render is), so one render decides which settings reach the target; two frames a setting let
   the grid be fine (successive halving's first rung).
2. race: the settings reaching the target whose rough time is fastest (a third of them, at least
   two, at most `race_size`; generous, because one round is noisy) are timed in full rounds; their fastest set (report/timing.py's rule: a confidence set for
   the fastest, Bonferroni over its comparisons) keeps what the rounds cannot tell from the best.
3. refine: the numeric knobs stepped towards the target's boundary, between a setting that reaches
   the target and the nearest tried value of one knob on either side that does not but is faster
   than the best so far by more than the tolerance (where the two qualities, interpolated on the
   knob's scale, cross the target, a tenth back towards the one that reaches it: regula falsi kept
   on the reaching side), and half-way to the nearest tried values around the best (geometric for a
   knob searched on a log scale); timed beside the fastest set, which is recomputed over this
   stage's rounds. Repeated while the budget allows, up to `refinements` times, or until no new
   setting is left.
4. final: the fastest set with the front (the settings no other is both faster and better than,
   from the screen) and rt_only, timed once more: the result set `report` reads, and the config that
   reproduces it. Its fastest set of the settings reaching the target is tune's answer.

The answer is among the searched techniques' settings (rt_only's too where it is searched, as it
is by default): where rt_only is not searched but reaches the target faster, the result says so
(the final result set's verdict, over all its settings, then names rt_only)."""
import collections
import itertools
import math
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "report"))
import results as rs  # noqa: E402
import timing  # noqa: E402

RT_ONLY = "rt_only"
# The fewest rounds of a full stage (the runner's `repeats`; it times at least the rounds the
# verdict needs for the stage's settings, timing.rounds_for_decision).
FULL_ROUNDS = 6
# A full stage's warm-up frames a setting (stages.py): one for the race and the refinements, whose
# fastest sets only steer the search (the median of their rounds absorbs a slow first round), two
# for the final stage, whose rounds give the answer.
WARMUP_FRAMES = 1
FINAL_WARMUP_FRAMES = 2
FINAL = "final"


def warmup_frames(stage_name):
    """A full stage's warm-up frames a setting."""
    return FINAL_WARMUP_FRAMES if stage_name == FINAL else WARMUP_FRAMES


def fewest_rounds(settings):
    """The rounds a full stage of `settings` settings times at least (the runner's rule)."""
    return max(timing.rounds_for_decision(settings), FULL_ROUNDS)


class SearchError(Exception):
    """Bad input to the search (an unknown technique or metric, a malformed target): exit status 2."""


# A setting: a technique and its parameters ((name, value) pairs, sorted by name).
Setting = collections.namedtuple("Setting", "technique params")


def setting(technique, params=None):
    return Setting(technique, tuple(sorted((params or {}).items())))


def value_text(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return ("%.6g" % v)
    return str(v)


def setting_name(s):
    """"ssr_fallback [max_steps=64 thickness=0.5]": how the progress lines and tune.json name it."""
    return s.technique + (" [" + " ".join("%s=%s" % (k, value_text(v)) for k, v in s.params) + "]" if s.params else "")


def names_text(settings, most=2):
    """"a and b", or "a and b and 3 more": a progress line's set."""
    names = [setting_name(s) for s in settings]
    return " and ".join(names[:most]) + (" and %d more" % (len(names) - most) if len(names) > most else "")


# A knob of a technique's search space: its grid (`values`, in order), whether refinement may
# step between them (`scale`: "log", "linear" or None for a choice), and the parameter's type.
Dimension = collections.namedtuple("Dimension", "parameter values scale integer")


def dimensions_of(technique_json, pixels):
    """The Dimensions a technique declares (`hybridlab techniques --json`'s "search"), their values
    scaled by the frame's pixel count where the knob counts per pixel (a ray budget)."""
    dims = []
    for d in technique_json.get("search", []):
        scale = d.get("scale")
        integer = d.get("type") == "int"
        values = d["values"]
        if d.get("per_pixel"):
            values = [v * pixels if v else v for v in values]
            values = [int(round(v)) if integer else float(v) for v in values]
        dims.append(Dimension(d["parameter"], list(values), scale, integer))
    return dims


def rt_only_anchor(spaces, defaults):
    """rt_only at its defaults (`defaults`: its parameters' default values), the anchor every stage
    times: where rt_only is searched, written with the searched knobs at their defaults, so that the
    grid's point there is that same setting (as two settings the runner would refuse the stage,
    which would list one run twice)."""
    if RT_ONLY not in spaces:
        return setting(RT_ONLY)
    return setting(RT_ONLY, {d.parameter: defaults[d.parameter] for d in spaces[RT_ONLY]})


def grid(technique, dims):
    """Every point of the grid (the Cartesian product of the dimensions' values)."""
    names = [d.parameter for d in dims]
    return [setting(technique, dict(zip(names, combo))) for combo in itertools.product(*[d.values for d in dims])]


def between(a, b, dim):
    """Half-way from `a` to `b` on the dimension's scale (geometric on a log scale, when both are
    positive), rounded for an integer knob; None where nothing lies between."""
    if dim.scale == "log" and a > 0 and b > 0:
        m = math.sqrt(a * b)
    else:
        m = 0.5 * (a + b)
    return strictly_between(int(round(m)) if dim.integer else m, a, b, dim)


def strictly_between(m, a, b, dim):
    """`m` as the knob's type where it lies strictly between `a` and `b`, else None."""
    if dim.integer:
        return m if min(a, b) < m < max(a, b) else None
    return float(m) if m not in (a, b) else None


def sides(s, parameter, tried):
    """The nearest values of `parameter` tried below and above the value `s` has, with every other
    knob as in `s` (none, one or two)."""
    v = dict(s.params)[parameter]
    line = line_of(s, parameter, tried)
    lower = [x for x in line if x < v]
    upper = [x for x in line if x > v]
    return ([lower[-1]] if lower else []) + ([upper[0]] if upper else [])


def neighbours(s, dims, tried):
    """The settings one half-step from `s` along each numeric dimension, towards the nearest value
    of that knob already tried (with the other knobs as in `s`) on each side; none already tried."""
    params = dict(s.params)
    out = []
    for d in dims:
        if d.scale is None or d.parameter not in params:
            continue
        v = params[d.parameter]
        for side in sides(s, d.parameter, tried):
            m = between(v, side, d)
            if m is not None:
                n = setting(s.technique, dict(params, **{d.parameter: m}))
                if n not in tried and n not in out:
                    out.append(n)
    return out


class Target:
    """"ssim>=0.97": a metric of the result set's metric table, its direction and the value."""

    def __init__(self, text, metric_table):
        m = re.fullmatch(r"\s*(\w+)\s*(>=|<=)\s*([-+0-9.eE]+)\s*", text or "")
        if not m:
            raise SearchError("--target %r: expected METRIC>=VALUE or METRIC<=VALUE (e.g. \"ssim>=0.97\", \"flip<=0.05\")" % text)
        self.metric, self.op, self.text = m.group(1), m.group(2), m.group(3)
        try:
            self.value = float(m.group(3))
        except ValueError:
            raise SearchError("--target %r: %r is not a number" % (text, m.group(3)))
        if not math.isfinite(self.value):
            raise SearchError("--target %r: %r is not a finite number" % (text, m.group(3)))
        known = {t["key"]: t for t in metric_table}
        if self.metric not in known:
            raise SearchError("--target %r: unknown metric %r (metrics: %s)" % (text, self.metric, ", ".join(sorted(known))))
        self.higher_is_better = known[self.metric]["better"] == "higher"
        if (self.op == ">=") != self.higher_is_better:
            raise SearchError("--target %r: %s is better %s, so a target reads %s%s%g" % (
                text, self.metric, "higher" if self.higher_is_better else "lower", self.metric,
                ">=" if self.higher_is_better else "<=", self.value))
        low, high = known[self.metric]["range"]
        if (low is not None and self.value < low) or (high is not None and self.value > high):
            raise SearchError("--target %r: %s lies in [%s, %s]" % (text, self.metric, low, high))

    def met(self, quality):
        return quality is not None and (quality >= self.value if self.higher_is_better else quality <= self.value)

    def better(self, a, b):
        """Whether quality `a` is better than `b`."""
        return a > b if self.higher_is_better else a < b

    def shortfall(self, quality):
        return abs(self.value - quality)

    def __str__(self):
        return "%s%s%s" % (self.metric, self.op, self.text)


# What an evaluator measured of one setting in one stage: its quality (the target's metric on the
# searched region) and its rounds ({timing id: [ms, ...]}, report/timing.py's setting_rounds).
Outcome = collections.namedtuple("Outcome", "quality rounds")
# One stage as an evaluator measured it: {setting: Outcome}, the seconds it took and the frames it
# rendered (warm-ups, rounds, and the reference's where it was timed).
Measured = collections.namedtuple("Measured", "outcomes seconds renders")

# One stage as the search ran it.
Stage = collections.namedtuple("Stage", "name settings outcomes seconds fastest")


class Plan:
    """How the search spends its renders (successive halving): a fine grid screened cheaply, then few
    settings a stage, each stage timed in the fewest rounds its decision needs (the budget buys
    stages, not rounds), the final one in up to `final_rounds` times that."""
    screen_rounds = 1      # the screen's rounds after its warm-up frame: a rough time
    race_size = 4          # the most settings the race times in full
    refine_around = 1      # the fastest set's members whose neighbours are tried (besides the boundary)
    refinements = 2        # refinement stages at most
    boundary_size = 3      # settings on the target's boundary tried in a refinement stage, at most
    new_settings = 4       # new settings a refinement stage tries, at most (the boundary's first)
    margin = 1.25          # a stage's estimated cost times this must fit in the budget left
    front_size = 2         # front settings timed in the final stage, besides the fastest set
    carry = 2              # the fastest set's members carried into the next stage, at most (the fastest)
    final_rounds = 1.5     # the final stage's rounds, at most, in multiples of the fewest

    def final_round_cap(self, settings):
        """The final stage's rounds at most, with `settings` settings (rt_only among them): a cap in
        rounds, not only in seconds, because the times a stage's seconds are estimated from (the
        screen's single rounds) run slow, and a budget in seconds would buy more rounds than planned."""
        return math.ceil(self.final_rounds * fewest_rounds(settings))

    def most_frames(self, grid_settings):
        """The most frames a search of a grid of `grid_settings` settings renders: the screen's, then
        every later stage at its largest (rt_only in each), the final one at its cap with the
        reference timed in its rounds. Successive halving: the screen's frames and a fixed number
        besides, whatever the budget."""
        screen = (grid_settings + 1) * (1 + self.screen_rounds)
        full = lambda n: n * (WARMUP_FRAMES + fewest_rounds(n))  # noqa: E731
        race = full(self.race_size + 1)
        refine = self.refinements * full(self.carry + self.new_settings + 1)
        n = self.carry + self.front_size + 1
        final = n * FINAL_WARMUP_FRAMES + (n + 1) * self.final_round_cap(n)
        return screen + race + refine + final


def rough_time(outcome):
    t = timing.rounds_time(outcome.rounds)
    return t if t is not None else math.inf


def front(settings, outcomes, target):
    """The settings that no faster one is at least as good as (by rough time and the target's
    metric: results.pareto_front, the report's own front); fastest first."""
    points = [(rough_time(outcomes[s]), outcomes[s].quality, s) for s in settings if outcomes[s].quality is not None]
    return [s for _, _, s in rs.pareto_front(points, target.higher_is_better)]


def fastest_set(candidates, outcomes, tolerance):
    """timing.fastest_of_rounds over `candidates`' rounds in one stage: (members, decision)."""
    if not candidates:
        return [], timing.NOT_DECIDED
    members, best, decision, _ = timing.fastest_of_rounds([outcomes[c].rounds for c in candidates], tolerance)
    ordered = [candidates[best]] + [candidates[i] for i in members if i != best]
    return ordered, decision


class Result:
    def __init__(self):
        self.anchor = None          # rt_only at its defaults, timed in every stage
        self.stages = []
        self.choice = []            # the final fastest set reaching the target (best first)
        self.decision = None        # timing.SINGLE, TIED or NOT_DECIDED
        self.reached = False
        self.best_quality = None    # where the target is not reached: the best any setting got
        self.best_quality_setting = None
        self.front = []
        self.renders = 0
        self.seconds = 0.0
        self.over_budget = False    # the stages a decision needs took longer than the budget
        self.rt_only_faster = False  # rt_only (not searched) reaches the target and is faster than the answer
        self.rt_only_reaches = False  # rt_only (not searched) reaches a target no searched setting does


def line_of(s, parameter, tried):
    """The values of `parameter` tried with every other knob of `s` as in `s`, sorted."""
    others = {k: v for k, v in s.params if k != parameter}
    return sorted({dict(t.params)[parameter] for t in tried
                   if t.technique == s.technique and parameter in dict(t.params) and {k: v for k, v in t.params if k != parameter} == others})


def toward(a, b, t, dim):
    """The value a fraction `t` of the way from `a` to `b` on the dimension's scale (geometric on a
    log scale, where both are positive), rounded towards `a` for an integer knob; None where that
    is `a` or `b`."""
    if dim.scale == "log" and a > 0 and b > 0:
        m = a * (b / a) ** t
    else:
        m = a + (b - a) * t
    if dim.integer:
        m = int(math.floor(m)) if b > a else int(math.ceil(m))
    return strictly_between(m, a, b, dim)


def boundary_points(reaching, dims_of, tried, quality_of, target, time_of, faster_than):
    """Settings on the target's boundary: between a setting that reaches the target and the nearest
    tried value of one knob on either side that does not, where that one's time is below
    `faster_than` (the boundary runs between them, and a setting on it may be faster than the best
    so far). Each is where the two qualities, interpolated on the knob's scale, cross the target,
    pulled a tenth of the way back towards the one that reaches it (regula falsi, kept on the
    reaching side; at least a tenth and at most nine tenths of the way, so that each step shrinks
    the gap). Ordered by the other one's time."""
    out = []
    for p in reaching:
        params = dict(p.params)
        for d in dims_of(p):
            if d.scale is None or d.parameter not in params:
                continue
            v = params[d.parameter]
            for side in sides(p, d.parameter, tried):
                q = setting(p.technique, dict(params, **{d.parameter: side}))
                qp, qq = quality_of(p), quality_of(q)
                if qq is None or target.met(qq) or time_of(q) >= faster_than:
                    continue
                crossing = (qp - target.value) / (qp - qq) if qp != qq else 0.5
                m = toward(v, side, min(0.9, max(0.1, 0.9 * crossing)), d)
                if m is None:
                    continue
                n = setting(p.technique, dict(params, **{d.parameter: m}))
                if n not in tried:
                    out.append((time_of(q), n))
    ordered = []
    for _, n in sorted(out, key=lambda x: x[0]):
        if n not in ordered:
            ordered.append(n)
    return ordered


def search(spaces, evaluator, target, budget_s, tolerance=timing.DEFAULT_TOLERANCE, plan=Plan(), progress=lambda line: None,
           anchor=None):
    """Runs the stages (see the module's text). `spaces`: {technique: [Dimension]}, each with at
    least one dimension; `evaluator.stage(name, settings, rounds, budget_s, max_rounds)` renders
    and times the settings (rt_only among them) in one group, `rounds` a number (exactly that many
    rounds after a warm-up frame, no interval: the screen) or "full" (the runner's protocol within
    `budget_s`, and at most `max_rounds` rounds where that is not None), and returns a Measured.
    `anchor`: rt_only at its defaults, timed in every stage (default: setting(RT_ONLY); where rt_only
    is searched, its grid's point at the defaults, rt_only_anchor). Returns a Result."""
    result = Result()
    anchor = anchor or setting(RT_ONLY)
    result.anchor = anchor
    tried = set()
    quality = {}
    time_of = {}  # each setting's time in the last stage that timed it

    def met(s):
        return target.met(quality.get(s))

    def run(name, settings, rounds, stage_budget, max_rounds=None):
        """Renders and times a stage (rt_only added) and records it in the result; the Stage."""
        settings = list(dict.fromkeys(settings + [anchor]))
        how = "timed in full" if rounds == "full" else "%d round%s each: a rough time" % (rounds, "" if rounds == 1 else "s")
        progress("stage %s: %d settings (%s), %.0f s of the %.0f s budget spent" % (name, len(settings), how, result.seconds, budget_s))
        measured = evaluator.stage(name, settings, rounds, stage_budget, max_rounds)
        result.seconds += measured.seconds
        result.renders += measured.renders
        for s, o in measured.outcomes.items():
            quality[s] = o.quality
            time_of[s] = rough_time(o)
        tried.update(settings)
        result.stages.append(Stage(name, settings, measured.outcomes, measured.seconds, None))
        return result.stages[-1]

    def decided(stage, candidates):
        """The fastest set of a stage's candidates, recorded with the stage: (members, decision)."""
        members, decision = fastest_set(candidates, stage.outcomes, tolerance)
        result.stages[-1] = stage._replace(fastest=members)
        progress("%s: fastest %s (%s)" % (stage.name, names_text(members), decision))
        return members, decision

    candidates = [s for technique, dims in spaces.items() for s in grid(technique, dims)]
    screen = run("screen", candidates, plan.screen_rounds, 0.0)
    reaching = [s for s in candidates if met(s)]
    result.front = front(screen.settings, screen.outcomes, target)
    if not reaching:
        # The best of the searched settings, and how far it falls short (rt_only is said apart where
        # it is not searched: it is the chart's end, not an answer).
        scored = [s for s in candidates if quality.get(s) is not None]
        best = max(scored, key=lambda s: quality[s] if target.higher_is_better else -quality[s]) if scored else None
        result.best_quality_setting, result.best_quality = best, quality.get(best)
        result.rt_only_reaches = anchor.technique not in spaces and met(anchor)
        progress("no setting reaches %s: the best is %s with %s = %s" % (target, setting_name(best) if best else "none", target.metric,
                                                                          "-" if best is None else "%.4g" % quality[best]))
        return result

    # A stage's least cost in seconds: its settings' warm-up and the fewest full rounds, at their
    # times so far (a setting not yet timed: the median of its technique's screen times), and what
    # a stage costs besides its frames (loading the scene, scoring each setting), a setting's share
    # as the screen took it.
    screen_times = {}
    for s in candidates:
        screen_times.setdefault(s.technique, []).append(time_of[s])
    def guess(s):
        times = sorted(screen_times.get(s.technique, [0.0]))
        return time_of.get(s, times[len(times) // 2])
    screen_frames_s = (1 + plan.screen_rounds) * sum(guess(s) for s in screen.settings) / 1000.0
    overhead_s = max(0.0, screen.seconds - screen_frames_s) / len(screen.settings)
    def estimate(settings, frames_only=False, warmup=WARMUP_FRAMES):
        """The stage's seconds; `frames_only`: its frames' alone (the runner's budget for its rounds)."""
        settings = list(dict.fromkeys(settings + [anchor]))
        rounds = warmup + fewest_rounds(len(settings))
        return sum(rounds * guess(s) / 1000.0 + (0.0 if frames_only else overhead_s) for s in settings)

    reaching.sort(key=lambda s: time_of[s])
    race = reaching[:max(2, min(plan.race_size, math.ceil(len(reaching) / 3)))]
    final_front = [s for s in result.front if s != anchor][:plan.front_size]
    final_reserve = estimate(race[:plan.refine_around] + final_front, warmup=FINAL_WARMUP_FRAMES)
    def carried(members):
        """The fastest set's members the next stage times again: where the rounds cannot tell many
        apart (a flat stretch of the space), the fastest few by their last stage's times."""
        return sorted(members, key=lambda s: time_of[s])[:plan.carry] if len(members) > plan.carry else members

    # The candidates: the searched techniques' settings that reach the target (rt_only, timed in
    # every stage, among them where it is searched).
    eligible = lambda settings: [s for s in dict.fromkeys(settings + [anchor]) if s.technique in spaces and met(s)]  # noqa: E731
    members, decision = decided(run("race", race, "full", 0.0), eligible(race))

    for level in range(plan.refinements):
        # Only where a setting past the boundary is faster than the best by more than the tolerance
        # can one on it be decided faster.
        best_time = (1.0 - tolerance) * time_of[members[0]]
        new = boundary_points([s for s in tried if met(s) and s.technique in spaces], lambda p: spaces[p.technique], tried,
                              quality.get, target, lambda q: time_of.get(q, math.inf), best_time)[:plan.boundary_size]
        for s in members[:plan.refine_around]:
            new += [n for n in neighbours(s, spaces.get(s.technique, []), tried) if n not in new]
        new = new[:plan.new_settings]
        if not new:
            break
        stage_settings = carried(members) + new
        stage_cost = estimate(stage_settings)
        if result.seconds + plan.margin * (stage_cost + final_reserve) > budget_s:
            progress("refine: stopped; the %.0f s of the budget left hold no stage of %d settings (about %.0f s) and the final one"
                     % (budget_s - result.seconds, len(stage_settings) + 1, stage_cost))
            break
        members, decision = decided(run("refine-%d" % (level + 1), stage_settings, "full", 0.0), eligible(stage_settings))

    final = list(dict.fromkeys(carried(members) + final_front))
    least = estimate(final, frames_only=True, warmup=FINAL_WARMUP_FRAMES)
    overhead = estimate(final, warmup=FINAL_WARMUP_FRAMES) - least
    last = run(FINAL, final, "full", max(least, min(budget_s - result.seconds - overhead, plan.final_rounds * least)),
               max_rounds=plan.final_round_cap(len(dict.fromkeys(final + [anchor]))))
    result.choice, result.decision = decided(last, eligible(final))
    result.reached = True
    # rt_only not searched but reaching the target faster than the answer: worth saying.
    if anchor.technique not in spaces and met(anchor) and result.choice:
        outcomes = last.outcomes
        result.rt_only_faster = timing.compare_rounds(outcomes[anchor].rounds, outcomes[result.choice[0]].rounds, tolerance) == timing.FASTER
    result.over_budget = result.seconds > budget_s
    return result
