#!/usr/bin/python3
"""Does `hybridlab tune` find what a dense sweep finds, for a third of its renders? A measurement,
not a test (it takes most of an hour on 2 cores):

    /usr/bin/python3 experiments/tune/tune_vs_sweep.py [--program build/hybridlab] [--out DIR]
        [--sweep-config experiments/configs/tune_sweep.toml] [--budget-s 60] [--repeats 3]

1. Runs the dense sweep (configs/tune_sweep.toml: heuristic_rt 63 settings, ssr_fallback 75, on
   three scenes at 320x180), or reads it from DIR/sweep.
2. For each scene, technique and SSIM target (0.95, 0.97 on the whole image) runs tune on that
   technique alone (DIR/tune/SCENE-TECHNIQUE-TARGET).
3. Times each tune answer beside the sweep's best setting of that technique reaching the target
   (the verdict's rule on the sweep's rounds: its fastest set's empirical best) and rt_only, in one
   group (DIR/check/...), in a fixed number of rounds, and compares them by the verdict's rule:
   tune's answer faster, tied, not decided or slower, with the paired ratio's 95% interval; "not
   slower" where the interval lies below the band's top, 1 / (1 - tolerance), which is "faster or
   tied" as one claim.
4. Runs tune `--repeats` times on one case (`--repeat SCENE TECHNIQUE SSIM`, default
   sponza-spheres ssr_fallback 0.97) and says whether their answers are identical, or where two
   share no setting, how their best settings compare timed together (a contradiction is one
   decided faster than the other; tied or not decided is none).

Prints a table: scene, technique, target, the sweep's best and tune's answer with their times, the
comparison, and the frames each rendered (tune's over the sweep's, for that technique: its settings'
warm-ups and rounds, and rt_only's share)."""
import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "report"))
import results as rs  # noqa: E402
import search  # noqa: E402
import stages  # noqa: E402
import timing  # noqa: E402
import verdict  # noqa: E402

SCENES = ("sponza-spheres", "whitted-classic", "cornell-mirror-glass")
TECHNIQUES = ("heuristic_rt", "ssr_fallback")
TARGETS = (0.95, 0.97)
SIZE = (320, 180)
# The check's rounds, fixed in advance (no stop at the runner's precision, which would make the
# number of rounds depend on the data): at 320x180 on 2 cores, 100 rounds left the paired ratio's
# interval about +-3%, as wide as the band that calls two settings tied; 400 halve it.
CHECK_ROUNDS = 400
CHECK_BUDGET_S = 900.0  # a cap that 400 rounds at 320x180 do not reach


def run(command):
    print("$ " + " ".join(command), flush=True)
    subprocess.run(command, check=True)


def sweep_rows(sweep_dir):
    """{(scene, technique): [records]} of the sweep, and the rt_only records by scene."""
    by = {}
    for r in rs.load(sweep_dir):
        by.setdefault((r["scene"], r["technique"]), []).append(r)
    return by


def best_reaching(records, threshold):
    """The sweep's best setting of these records reaching SSIM `threshold` on the whole image, by
    the verdict's rule (the fastest set's empirical best), with its fastest set's size."""
    ok = [r for r in records if (rs.metric(r, "whole", "ssim") or 0.0) >= threshold]
    if not ok:
        return None, 0
    fs = timing.fastest(ok, lambda r: [r])
    return fs.best, len(fs.settings)


def check(program, out, scene, tuned, best, cache):
    """tune's answer and the sweep's best timed in one group beside rt_only: compare_rounds of the
    two (tune's against the sweep's), and that with the paired ratio's interval as text."""
    settings = list(dict.fromkeys([tuned, best, search.setting(search.RT_ONLY)]))
    if len(settings) == 2:
        return timing.TIED, timing.TIED + " (the same setting)"
    config = stages.stage_config("check", scene, SIZE, settings, CHECK_ROUNDS, CHECK_BUDGET_S, timing.DEFAULT_TOLERANCE, ["ssim"], False,
                                 max_rounds=CHECK_ROUNDS)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    with open(out + ".toml", "w") as f:
        f.write(config)
    stages.run_experiment(program, out + ".toml", out, cache)
    rounds = {stages.record_key(r): timing.setting_rounds([r]) for r in rs.load(out)}
    a, b = rounds[stages.setting_key(tuned)], rounds[stages.setting_key(best)]
    order = timing.compare_rounds(a, b, timing.DEFAULT_TOLERANCE)
    iv = timing.median_interval(timing.paired_ratios(a, b))
    if iv is None:
        return order, order
    # "Faster or tied" as one claim: the whole interval below the band's top, 1 / (1 - tolerance)
    # (a one-sided test that tune's answer is not slower; the verdict's rule splits it in two).
    not_slower = iv.high <= 1.0 / (1.0 - timing.DEFAULT_TOLERANCE)
    return order, "%s: %s%s" % (iv.text("%.3f"), order, "; not slower" if not_slower and order != timing.FASTER else "")


def tune(program, out, scene, technique, threshold, budget, cache):
    if not os.path.exists(os.path.join(out, "tune.json")):
        run([program, "tune", "--scene", scene, "--target", "ssim>=%.2f" % threshold, "--technique", technique, "--size", "%dx%d" % SIZE,
             "--budget-s", str(budget), "--cache", cache, "--out", out] + (["--resume"] if os.path.exists(out) else []))
    with open(os.path.join(out, "tune.json")) as f:
        return json.load(f)


def answer_settings(doc):
    final = {s["setting"]: s for s in doc["stages"][-1]["settings"]}
    return [search.setting(final[n]["technique"], final[n]["parameters"]) for n in doc["choice"]]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--program", default=os.path.join(ROOT, "build", "hybridlab"))
    ap.add_argument("--out", default="results/tune-vs-sweep")
    ap.add_argument("--sweep-config", default=os.path.join(ROOT, "experiments", "configs", "tune_sweep.toml"))
    ap.add_argument("--budget-s", type=float, default=60.0)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--scenes", nargs="*", default=list(SCENES))
    ap.add_argument("--repeat", nargs=3, metavar=("SCENE", "TECHNIQUE", "SSIM"), default=["sponza-spheres", "ssr_fallback", "0.97"],
                    help="the search run --repeats times (default: sponza-spheres ssr_fallback 0.97)")
    args = ap.parse_args()
    program = os.path.abspath(args.program)
    cache = os.path.abspath(os.path.join(args.out, "cache"))
    sweep_dir = os.path.join(args.out, "sweep")
    stages.run_experiment(program, args.sweep_config, sweep_dir, cache, quiet=False)
    sweep = sweep_rows(sweep_dir)

    lines = ["| scene | technique | target | sweep's best (ms) | tune's answer (ms) | tune vs sweep | frames: tune / sweep |",
             "|---|---|---|---|---|---|---|"]
    for scene in args.scenes:
        rt_only = sweep.get((scene, "rt_only"), [])
        for technique in TECHNIQUES:
            records = sweep.get((scene, technique), [])
            # The sweep's frames for this technique: its settings' and rt_only's share of the group.
            share = len(records) / max(1, sum(len(v) for (s, _), v in sweep.items() if s == scene) - len(rt_only))
            renders = stages.frames_rendered(records) + share * stages.frames_rendered(rt_only)
            for threshold in TARGETS:
                best, best_set = best_reaching(records, threshold)
                doc = tune(program, os.path.join(args.out, "tune", "%s-%s-%.2f" % (scene, technique, threshold)), scene, technique, threshold,
                           args.budget_s, cache)
                if best is None or not doc["reached"]:
                    lines.append("| %s | %s | %.2f | %s | %s | - | %d / %.0f |" % (
                        scene, technique, threshold, "none reaches" if best is None else rs.variant(best),
                        "not reached (%.4f short)" % doc["shortfall"] if not doc["reached"] else ", ".join(doc["choice"]),
                        doc["renders"], renders))
                    continue
                answer = answer_settings(doc)
                _, order = check(program, os.path.join(args.out, "check", "%s-%s-%.2f" % (scene, technique, threshold)), scene, answer[0],
                                 search.setting(best["technique"], dict(best["parameters"])), cache)
                final = {s["setting"]: s for s in doc["stages"][-1]["settings"]}
                lines.append("| %s | %s | %.2f | %s (%.2f; a set of %d) | %s (%.2f; %s) | %s | %d / %.0f = %.2f |" % (
                    scene, technique, threshold, rs.variant(best), best["frame_ms"]["median"], best_set, " and ".join(doc["choice"]),
                    final[doc["choice"][0]]["ms"], doc["decision"], order, doc["renders"], renders, doc["renders"] / renders))
    print("\n".join(lines))

    scene, technique, threshold = args.repeat[0], args.repeat[1], float(args.repeat[2])
    label = "%s-%s-%.2f" % (scene, technique, threshold)
    docs = []
    for k in range(args.repeats):
        doc = tune(program, os.path.join(args.out, "repeat", label, "run-%d" % (k + 1)), scene, technique, threshold, args.budget_s, cache)
        docs.append(doc)
        print("repeat %d: %s (%s)" % (k + 1, " and ".join(doc["choice"]), doc["decision"]))
    sets = [set(d["choice"]) for d in docs]
    if all(s == sets[0] for s in sets):
        print("repeats of %s: identical" % label)
        return
    # Answers that differ: their best settings timed together, two by two (a contradiction is one
    # decided faster than another; tied or not decided is not one).
    for i in range(len(docs)):
        for j in range(i + 1, len(docs)):
            if sets[i] & sets[j]:
                print("repeats %d and %d share a setting" % (i + 1, j + 1))
                continue
            a, b = answer_settings(docs[i])[0], answer_settings(docs[j])[0]
            order, text = check(program, os.path.join(args.out, "repeat", label, "check-%d-%d" % (i + 1, j + 1)), scene, a, b, cache)
            print("repeats %d and %d: %s against %s: %s%s" % (i + 1, j + 1, search.setting_name(a), search.setting_name(b), text,
                                                           "   <- contradicts" if order in (timing.FASTER, timing.SLOWER) else ""))

if __name__ == "__main__":
    main()
