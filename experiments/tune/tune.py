"""`hybridlab tune`: the fastest setting of a scene's techniques that reaches a quality target.

    hybridlab tune --scene S --target "ssim>=0.97" [--region whole|refl] [--technique T ...]
                   [--size WxH] [--budget-s N] [--cache DIR] [--resume] --out DIR

Searches the techniques' declared knobs (search.py: a grid screened, the fastest reaching
the target raced, the target's boundary refined, a final timing) on the scene's camera, each stage
rendered and timed by `hybridlab run` beside rt_only. Writes

    DIR/result/       the final stage's result set: `hybridlab report DIR/result`, `hybridlab view`
    DIR/tune.toml     the experiment config that reproduces it (`hybridlab run DIR/tune.toml`)
    DIR/tune.json     every stage's settings, qualities and times, the front, the answer, the renders
    DIR/stages/       the earlier stages' configs and result sets

and prints the answer: the fastest set of the settings reaching the target (one setting, or those
the rounds cannot tell apart, tied or not decided), with each one's time and speed-up over rt_only.
Where nothing reaches the target it says so, with the best quality found and how far it falls
short (exit status 0: that is an answer). Bad input (an unknown scene, technique or metric, a
malformed target or size): one message, exit status 2, nothing written. `--resume` continues an
interrupted search in DIR with the same arguments: finished stages are read back, the interrupted
one is resumed by the runner."""
import argparse
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "report"))
import results as rs  # noqa: E402
import search  # noqa: E402
import stages  # noqa: E402
import timing  # noqa: E402

REGIONS = {"whole": "whole", "refl": "masked"}
ARGUMENTS_FILE = "tune-arguments.json"


def fail(message, status=2):
    sys.stderr.write("hybridlab tune: error: %s\n" % message)
    sys.exit(status)


def parse_size(text):
    try:
        w, h = (int(x) for x in text.lower().split("x"))
    except ValueError:
        fail("--size %r: expected WIDTHxHEIGHT, e.g. 320x180" % text)
    if w < 16 or h < 16 or w > 16384 or h > 16384:
        fail("--size %r: each side between 16 and 16384 pixels" % text)
    return w, h


def techniques_json(program):
    out = subprocess.run([program, "techniques", "--json"], check=True, capture_output=True, text=True).stdout
    return {t["name"]: t for t in json.loads(out)}


def search_spaces(program, names, pixels):
    """The searched techniques' dimensions ({technique: [Dimension]}) and rt_only's anchor setting."""
    known = techniques_json(program)
    searchable = sorted(n for n, t in known.items() if t.get("search"))
    for n in names:
        if n not in known:
            fail("--technique %s: unknown technique (techniques: %s)" % (n, ", ".join(sorted(known))))
        if not known[n].get("search"):
            fail("--technique %s: declares no knobs to search (searchable: %s)" % (n, ", ".join(searchable)))
    spaces = {n: search.dimensions_of(known[n], pixels) for n in (names or searchable)}
    defaults = {p["name"]: p["default"] for p in known[search.RT_ONLY]["parameters"]}
    return spaces, search.rt_only_anchor(spaces, defaults)


def check_scene(program, scene):
    """A scenes/ name or a file; the stage configs name files by absolute path (they live in DIR)."""
    got = subprocess.run([program, "scene-info", scene, "--json"], capture_output=True, text=True)
    if got.returncode != 0:
        fail("--scene %s: %s" % (scene, got.stderr.strip().replace("hybridlab: error: ", "")))
    return os.path.abspath(scene) if os.path.isfile(scene) else scene


def prepare_out(out, arguments, resume):
    """DIR new (or empty), or with --resume one holding a search with the same arguments."""
    if not out:
        fail("--out: expected a folder, got ''")
    recorded = os.path.join(out, ARGUMENTS_FILE)
    if os.path.exists(out) and not (os.path.isdir(out) and not os.listdir(out)):
        if not resume:
            fail("%s: exists; pass --resume to continue the search in it, or choose another --out" % out)
        if not os.path.exists(recorded):
            fail("%s: holds no search of `hybridlab tune` (no %s); choose another --out" % (out, ARGUMENTS_FILE))
        try:
            with open(recorded) as f:
                before = json.load(f)
        except (OSError, ValueError) as e:
            fail("%s: cannot be read as a search's arguments (%s); choose another --out" % (recorded, e))
        if not isinstance(before, dict):
            fail("%s: holds no search's arguments (expected a JSON object); choose another --out" % recorded)
        if before != arguments:
            changed = sorted(k for k in set(before) | set(arguments) if before.get(k) != arguments.get(k))
            fail("%s: holds a search with other arguments (%s there); resume it with the same ones, or choose another --out"
                 % (out, ", ".join("%s: %s" % (k, before.get(k)) for k in changed)))
        return
    try:
        os.makedirs(out, exist_ok=True)
        with open(recorded, "w") as f:
            json.dump(arguments, f, indent=1)
    except OSError as e:  # a file where a folder goes, a read-only parent: the machine's, exit 3
        fail("%s: cannot be written (%s)" % (out, e.strerror or e), 3)


def outcome_json(s, outcome, target):
    t = timing.rounds_time(outcome.rounds)
    return {"setting": search.setting_name(s), "technique": s.technique, "parameters": dict(s.params),
            target.metric: outcome.quality, "reaches": target.met(outcome.quality), "ms": t}


def speedup_text(result, s):
    final = result.stages[-1].outcomes
    iv = timing.median_interval(timing.paired_ratios(final[result.anchor].rounds, final[s].rounds))
    return iv.text("%.2f", "x") + " over rt_only" if iv else "no interval over rt_only"


def write_summary(out, result, target, args, size):
    doc = {"scene": args.scene, "size": list(size), "target": str(target), "region": args.region, "budget_s": args.budget_s,
           "reached": result.reached, "seconds": result.seconds, "renders": result.renders, "over_budget": result.over_budget,
           "choice": [search.setting_name(s) for s in result.choice], "decision": result.decision,
           "rt_only_faster": result.rt_only_faster,
           "front": [search.setting_name(s) for s in result.front],
           "stages": [{"name": st.name, "seconds": st.seconds, "fastest": [search.setting_name(s) for s in st.fastest or []],
                       "settings": [outcome_json(s, st.outcomes[s], target) for s in st.settings if s in st.outcomes]}
                      for st in result.stages]}
    if not result.reached:
        doc["best_quality"] = result.best_quality
        doc["best_quality_setting"] = search.setting_name(result.best_quality_setting) if result.best_quality_setting else None
        doc["shortfall"] = target.shortfall(result.best_quality) if result.best_quality is not None else None
        doc["rt_only_reaches"] = result.rt_only_reaches
    with open(os.path.join(out, "tune.json"), "w") as f:
        json.dump(doc, f, indent=1)
    if result.reached:
        shutil.copyfile(os.path.join(out, "stages", "final.toml"), os.path.join(out, "tune.toml"))


class OneLineArgumentParser(argparse.ArgumentParser):
    """argparse whose refusal is one line, like every other command's, not a usage block."""

    def error(self, message):
        fail("%s (hybridlab tune --help for usage)" % message)


def main(argv):
    ap = OneLineArgumentParser(prog="hybridlab tune", description=__doc__.split("\n\n")[0])
    ap.add_argument("--program", required=True, help=argparse.SUPPRESS)
    ap.add_argument("--scene", required=True, help="a scenes/ name or a scene file")
    ap.add_argument("--target", required=True, help="METRIC>=VALUE or METRIC<=VALUE, e.g. \"ssim>=0.97\", \"flip<=0.05\"")
    ap.add_argument("--region", default="whole", choices=sorted(REGIONS), help="the whole image, or the reflective/refractive pixels")
    ap.add_argument("--technique", action="append", default=[], help="a technique to search (repeatable; default: every one that declares knobs)")
    ap.add_argument("--size", default="320x180", help="WIDTHxHEIGHT (default 320x180)")
    ap.add_argument("--budget-s", type=float, default=120.0, help="seconds the stages' renders may take in all (default 120)")
    ap.add_argument("--cache", help="the reference cache (default: $HYBRIDLAB_CACHE or ~/.cache/hybridlab)")
    ap.add_argument("--resume", action="store_true", help="continue an interrupted search in --out")
    ap.add_argument("--out", required=True, help="the search's folder")
    try:
        args = ap.parse_args(argv)
    except SystemExit as e:
        sys.exit(2 if e.code else 0)
    if not (0 < args.budget_s <= 1e7):
        fail("--budget-s %g: expected a positive number of seconds, at most 1e7" % args.budget_s)
    size = parse_size(args.size)
    try:
        target = search.Target(args.target, rs.BUILT_IN_METRICS)
    except search.SearchError as e:
        fail(str(e))
    spaces, anchor = search_spaces(args.program, list(dict.fromkeys(args.technique)), size[0] * size[1])
    scene = check_scene(args.program, args.scene)
    arguments = {"scene": scene, "target": str(target), "region": args.region, "techniques": sorted(spaces), "size": list(size),
                 "budget_s": args.budget_s}
    prepare_out(args.out, arguments, args.resume)

    grid_settings = sum(len(search.grid(t, d)) for t, d in spaces.items())
    print("tune: %s at %dx%d, %s on the %s, searching %s (%d grid settings), budget %.0f s" % (
        args.scene, size[0], size[1], target, "whole image" if args.region == "whole" else "reflective/refractive pixels",
        ", ".join(sorted(spaces)), grid_settings, args.budget_s), flush=True)
    evaluator = stages.RunnerEvaluator(args.program, args.out, scene, size, target, REGIONS[args.region], timing.DEFAULT_TOLERANCE,
                                       cache=args.cache)
    try:
        result = search.search(spaces, evaluator, target, args.budget_s, progress=lambda line: print("tune: " + line, flush=True),
                               anchor=anchor)
    except stages.RunFailed as e:
        fail(str(e), e.status if e.status in (2, 3) else 1)
    except search.SearchError as e:
        fail(str(e))
    write_summary(args.out, result, target, args, size)

    most = search.Plan().most_frames(grid_settings)
    print("tune: %d frames rendered (the plan's most: %d) in %.0f s%s" % (result.renders, most, result.seconds,
                                                    " (over the %.0f s budget: the stages a decision needs took longer)" % args.budget_s
                                                    if result.over_budget else ""))
    if not result.reached and result.best_quality_setting is None:
        print("tune: not reached: no setting has a %s score on the %s (a region without pixels?)" % (
            target.metric, "whole image" if args.region == "whole" else "reflective/refractive pixels"))
        return 0
    if not result.reached:
        best = result.best_quality_setting
        print("tune: not reached: no setting reaches %s; the best is %s with %s = %.4f, %.4f short" % (
            target, search.setting_name(best), target.metric, result.best_quality, target.shortfall(result.best_quality)))
        if result.rt_only_reaches:
            print("tune: rt_only (not searched) reaches it")
        return 0
    final = result.stages[-1].outcomes
    kind = {timing.SINGLE: "the fastest", timing.TIED: "tied for the fastest",
            timing.NOT_DECIDED: "not decided: the rounds cannot tell these apart"}[result.decision]
    print("tune: %s reaching %s (%s):" % ("the fastest setting" if len(result.choice) == 1 else "the fastest settings", target, kind))
    for s in result.choice:
        print("  %s: %.2f ms, %s = %.4f, %s" % (search.setting_name(s), timing.rounds_time(final[s].rounds), target.metric,
                                               final[s].quality, speedup_text(result, s)))
    if result.rt_only_faster:
        print("tune: rt_only (not searched) reaches %s too, and is faster than the answer (%s: %s)" % (
            target, search.setting_name(result.choice[0]), speedup_text(result, result.choice[0])))
    print("tune: report: hybridlab report %s; reproduce: hybridlab run %s" % (
        os.path.join(args.out, "result"), os.path.join(args.out, "tune.toml")))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
