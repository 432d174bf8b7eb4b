"""Result records made up in a test, in the layout of experiments/results.schema.json: runs timed in
interleaved rounds (frame_ms with its interval, `timing`, `speedup`), and the same without them as
result sets written before rounds have them. For the report's and the table scripts' tests, which
run without the hybridlab program.

    group = Group("s", rounds=[...reference's time per round...])
    a = timed_record(group, "whitted", "max_depth=2", [...time per round...], ssim=0.99)
    b = old_record(...)                      # frame_ms {median, min, max} only

Records get consecutive indices and ids; write_set(folder, records) writes results.json."""
import itertools
import json
import os
import random
import statistics
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "report"))
import timing  # noqa: E402

_index = itertools.count()
_timing = itertools.count()


class Group:
    """One scene, view, frame and size, timed in rounds by one call of the runner (`timing_id`, a
    new one for each Group unless given): the reference's time in each round."""

    def __init__(self, scene, reference_rounds, view="camera", frame=-1, size=(64, 36), timing_id=None):
        self.scene, self.view, self.frame, self.size = scene, view, frame, size
        self.reference_rounds = list(reference_rounds)
        self.name = "%s|%s|%d|%dx%d" % (scene, view, frame, size[0], size[1])
        self.timing_id = timing_id or "%016x" % (0x5eed0000 + next(_timing))
        self.rt_only_rounds = None  # the default rt_only's, once a record of it is made


def drifting_rounds(base_ms, rounds, seed, drift=0.25, noise=0.01):
    """Per-round times of a machine whose load drifts: round k takes base_ms x d_k x (1 + e_k), d_k
    one shared drift (the same seed gives every setting the same d_k) up to `drift`, e_k the
    setting's own noise up to `noise` (drawn from `seed` + the base, so settings differ)."""
    shared = random.Random(seed)
    d = [1.0 + drift * shared.random() for _ in range(rounds)]
    own = random.Random(seed * 7919 + int(base_ms * 1000))
    return [base_ms * dk * (1.0 + noise * (2.0 * own.random() - 1.0)) for dk in d]


def spread(values, with_interval=True):
    s = {"median": statistics.median(values), "min": min(values), "max": max(values)}
    iv = timing.median_interval(values) if with_interval else None
    if iv:
        s.update(ci_low=iv.low, ci_high=iv.high)
    return s


def _base(scene, view, frame, size, technique, params_text, ssim, label, reference_ms, counters, stages):
    i = next(_index)
    w, h = size
    return {
        "index": i, "id": "%04d-%s" % (i, technique), "scene": scene,
        "scene_stats": {"objects": 3, "vertices": 100, "triangles": 50, "lights": 1, "reflective": 1, "refractive": 1},
        "view": view, "frame": frame, "time": 0.0, "width": w, "height": h, "technique": technique, "label": label or technique,
        "parameters": {}, "parameters_text": params_text, "sequence": "%s|%s|%s" % (scene, view, params_text),
        "stages": stages or {}, "counters": dict(counters or {}),
        "metrics": {"whole": {"pixels": w * h, "ssim": ssim, "flip": {"mean": 1.0 - ssim}}, "masked": None,
                    "reference": "references/r.png", "test": "images/%d.png" % i, "width": w, "height": h},
        "reference": {"key": "ref", "exr": "references/r.exr", "png": "references/r.png", "frame_ms": reference_ms, "cache_hit": False},
        "images": {"exr": "images/%d.exr" % i, "png": "images/%d.png" % i, "maps": None},
    }


def timed_record(group, technique, params_text, ms_rounds, ssim=0.95, label=None, precision=0.03, cpu_rounds=None,
                 counters=None, stages=None):
    """A run timed in the rounds of `group`, with its interval, timing and speed-ups as the runner
    writes them. A default rt_only (no parameters) becomes the group's rt_only for records made
    after it."""
    r = _base(group.scene, group.view, group.frame, group.size, technique, params_text, ssim, label,
              statistics.median(group.reference_rounds), counters, stages)
    r["frame_ms"] = spread(ms_rounds)
    r["timing"] = {"group": group.name, "timing_id": group.timing_id, "rounds": len(ms_rounds), "frame_ms_rounds": list(ms_rounds),
                   "reference_ms_rounds": list(group.reference_rounds), "precision": precision, "precision_reached": True,
                   "warmup_frames": 2, "warmup_ms": 1.0, "steady": True}
    if cpu_rounds:
        r["timing"]["cpu_ms"] = spread(cpu_rounds)
        r["timing"]["cpu_ms_rounds"] = list(cpu_rounds)
    if technique == "rt_only" and not params_text:
        group.rt_only_rounds = list(ms_rounds)
    r["speedup"] = {"reference": ratio_interval(group.reference_rounds, ms_rounds)}
    if group.rt_only_rounds:
        r["speedup"]["rt_only"] = ratio_interval(group.rt_only_rounds, ms_rounds)
    return r


def ratio_interval(other, own):
    """The runner's paired speed-up: its interval only from 6 rounds on."""
    ratios = [o / x for o, x in zip(other, own)]
    iv = timing.median_interval(ratios)
    return {"ratio": iv.median, "low": iv.low, "high": iv.high} if iv else {"ratio": statistics.median(ratios)}


def old_record(scene, technique, params_text, ms, ssim=0.95, reference_ms=100.0, label=None, view="camera", frame=-1, size=(64, 36),
               counters=None, stages=None):
    """A run as result sets written before rounds hold it: frame_ms {median, min, max} alone."""
    r = _base(scene, view, frame, size, technique, params_text, ssim, label, reference_ms, counters, stages)
    r["frame_ms"] = {"median": ms, "min": ms * 0.98, "max": ms * 1.05}
    return r


def write_set(folder, records):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "results.json"), "w") as f:
        json.dump(records, f)
    return folder
