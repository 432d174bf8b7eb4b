"""The stages of `hybridlab tune` rendered by `hybridlab run`: each stage is an experiment config
(one scene, its camera, one size, the stage's settings and rt_only in one group) written beside
its result set, OUT/stages/NAME/, so that each stage's rounds pair within one timing and any stage
can be read by `report`. A stage whose result set is complete is read back, not rendered again
(`tune --resume`); one that was interrupted is resumed by the runner."""
import json
import os
import subprocess
import sys

import search

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "report"))
import results as rs  # noqa: E402
import timing  # noqa: E402


RUN_ERROR_PREFIX = "hybridlab: error: "


class RunFailed(Exception):
    """`hybridlab run` failed: its exit status (2: bad input, 3: I/O), the stage's folder and the
    runner's own error line, so that tune says the failure on one line."""

    def __init__(self, status, where, message=""):
        super().__init__("hybridlab run on %s: %s" % (where, message) if message else
                         "hybridlab run failed on %s (exit status %d)" % (where, status))
        self.status = status


def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        text = repr(v)
        return text if any(c in text for c in ".en") else text + ".0"
    return json.dumps(v)


def stage_config(name, scene, size, settings, rounds, budget_s, tolerance, metrics, reference_timed, max_rounds=None,
                 warmup_frames=1):
    """The TOML of one stage's experiment (`max_rounds`: the runner's cap, default 30;
    `warmup_frames`: a full stage's warm-up frames a setting, at most)."""
    full = rounds == "full"
    lines = ["# A stage of `hybridlab tune`: %s." % name, "", "[experiment]",
             'name = "tune-%s"' % name,
             'description = "hybridlab tune: stage %s on %s at %dx%d"' % (name, scene, size[0], size[1]),
             "warmup_frames = 1",
             # One frame compiles lavapipe's shaders and fills the caches; a search times every
             # setting in several stages, so it does not wait for frames to agree (the runner's
             # default goes on to 5).
             "max_warmup_frames = %d" % (warmup_frames if full else 1),
             "repeats = %d" % (search.FULL_ROUNDS if full else rounds),
             "precision = %s" % toml_value(float(tolerance)),
             "budget_s = %s" % toml_value(float(max(budget_s, 0.1))),
             "max_rounds = %d" % max_rounds if max_rounds else "",
             "metrics = [%s]" % ", ".join(json.dumps(m) for m in metrics) if metrics else "",
             'keep = []', "", "[reference]", "params = { max_depth = 10 }",
             "timed = %s" % ("true" if reference_timed else "false"), "",
             "[[scenes]]", "scene = %s" % json.dumps(scene), "resolutions = [[%d, %d]]" % size, "[[scenes.views]]"]
    by_technique = {}
    for s in settings:
        by_technique.setdefault(s.technique, []).append(s)
    for technique, group in by_technique.items():
        sets = ", ".join("{ %s }" % ", ".join("%s = %s" % (k, toml_value(v)) for k, v in s.params) for s in group)
        lines += ["", "[[techniques]]", "name = %s" % json.dumps(technique), "param_sets = [ %s ]" % sets]
    return "\n".join(l for l in lines) + "\n"


def normalised(params):
    """Parameters as a record or a Setting holds them, comparable: numbers as floats (a Float
    parameter given as an integer is recorded as one)."""
    def norm(v):
        if isinstance(v, bool) or isinstance(v, str):
            return v
        return float(v)
    return tuple(sorted((k, norm(v)) for k, v in params))


def setting_key(s):
    """What a search.Setting matches a record by (record_key)."""
    return s.technique, normalised(s.params)


def record_key(r):
    return r["technique"], normalised(r["parameters"].items())


def frames_rendered(records):
    """Every frame a result set's runs rendered: each run's warm-up and rounds, and the reference's
    rounds where it was timed (once a group)."""
    frames = sum(r.get("warmup_frames", 0) + (r.get("timing") or {}).get("rounds", 0) for r in records)
    return frames + sum(len((r.get("timing") or {}).get("reference_ms_rounds") or [])
                        for r in {(r.get("timing") or {}).get("timing_id"): r for r in records}.values())


def run_experiment(program, config_file, out, cache=None, quiet=True, log=None):
    """`hybridlab run CONFIG --out OUT`, resuming OUT where an interrupted run left it; nothing
    where OUT is complete (it has its results.json). The runner's own lines go to `log` (a file
    object) where one is given; its progress to the terminal, its error into RunFailed's message."""
    if os.path.exists(os.path.join(out, "results.json")):
        return
    command = [program, "run", config_file, "--out", out] + (["--resume"] if os.path.exists(out) else [])
    command += ["--cache", cache] if cache else []
    command += ["--quiet"] if quiet else []
    errors = []
    with subprocess.Popen(command, stdout=log, stderr=subprocess.PIPE, text=True, errors="replace") as runner:
        for line in runner.stderr:
            if line.startswith(RUN_ERROR_PREFIX):
                errors.append(line[len(RUN_ERROR_PREFIX):].strip())
            else:
                sys.stderr.write(line)
                sys.stderr.flush()
    if runner.returncode != 0:
        raise RunFailed(runner.returncode, out, "; ".join(errors))


class RunnerEvaluator:
    """search.search's evaluator: renders each stage with `hybridlab run` (see the module's text)."""

    def __init__(self, program, out_dir, scene, size, target, region, tolerance, cache=None, quiet=True):
        self.program, self.out_dir, self.scene, self.size = program, out_dir, scene, size
        self.target, self.region, self.tolerance, self.cache = target, region, tolerance, cache
        self.quiet = quiet

    def stage_dir(self, name):
        return os.path.join(self.out_dir, "result" if name == search.FINAL else os.path.join("stages", name))

    def stage(self, name, settings, rounds, budget_s, max_rounds=None):
        d = self.stage_dir(name)
        final = name == search.FINAL
        metrics = None if final else sorted({self.target.metric, "ssim"})
        config = stage_config(name, self.scene, self.size, settings, rounds, budget_s, self.tolerance, metrics,
                              reference_timed=final, max_rounds=max_rounds,
                              warmup_frames=search.warmup_frames(name))
        config_file = os.path.join(self.out_dir, "stages", name + ".toml")
        os.makedirs(os.path.dirname(config_file), exist_ok=True)
        if not os.path.exists(os.path.join(d, "results.json")):
            if os.path.exists(config_file) and os.path.exists(d):
                with open(config_file) as f:
                    if f.read() != config:
                        raise search.SearchError("%s: holds stage %s of another search (its config differs); choose another --out" % (d, name))
            with open(config_file, "w") as f:
                f.write(config)
            with open(os.path.join(self.out_dir, "stages", name + ".log"), "a") as log:
                run_experiment(self.program, config_file, d, self.cache, self.quiet, log)
        return self.read(d, settings)

    def read(self, d, settings):
        records = rs.load(d)
        by_key = {}
        for r in records:
            by_key.setdefault(record_key(r), []).append(r)
        outcomes = {}
        for s in settings:
            runs = by_key.get(setting_key(s), [])
            if not runs:
                raise search.SearchError("%s: no record of %s" % (d, search.setting_name(s)))
            q = [rs.metric(r, self.region, self.target.metric) for r in runs]
            q = [v for v in q if v is not None]
            # Over several runs (views), the worst: the target holds on every one.
            worst = (min(q) if self.target.higher_is_better else max(q)) if q else None
            outcomes[s] = search.Outcome(worst, timing.setting_rounds(runs))
        # The runner's own account of each run's time (its share of the group's, then its scoring):
        # read back alike from a stage rendered now and one resumed.
        seconds = sum(r.get("run_seconds") or 0.0 for r in records)
        return search.Measured(outcomes, seconds, frames_rendered(records))
