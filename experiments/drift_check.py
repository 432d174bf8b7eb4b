#!/usr/bin/python3
"""Has the CPU ray tracer's speed drifted between two commits? Builds both (Release, only the
program) and times them interleaved: N alternations, A then B, then B then A (ABBA), each
measurement of A beside the same measurement of B, so that the machine's drift hits both alike.
Run it before merging anything that touches the Whitted walk (common/shading/whitted_tree.h),
the shading or the ray backends (common/raytrace/, common/device_rays/).

    /usr/bin/python3 experiments/drift_check.py [--base COMMIT] [--head COMMIT | --worktree]
        [--alternations 5] [--size 1280x720] [--repeats 5] [--threads 2] [--realtime] [--quick]
        [--cache DIR]

Each alternation measures, per commit:
  - `hybridlab bench --embree-only` on whitted-classic and on sponza-spheres: the reference
    frame, the same rays through RayScene with every hit resolved and nothing shaded (the
    ceiling), and the same rays through bare Embree (medians over --repeats). A commit whose bench
    lacks --embree-only is stopped after those lines (its output line-buffered by stdbuf), the
    Vulkan device hidden (VK_ICD_FILENAMES) in case it gets further.
  - the steady-state frame of rt_only and the hybrids (heuristic_rt, ssr_fallback; their defaults)
    on sponza-spheres: `hybridlab run` of a config written here, --repeats rounds after the
    runner's warm-up, the reference untimed; rt_only's frame and each hybrid's `trace` stage
    (Embree's rays; medians over the rounds). The hybrids' rasterization runs on the Vulkan device.
Then, per quantity, the paired ratio B/A of each alternation: their median, min-max, and from 6
alternations the median's distribution-free 95% interval (report/timing.py), beside A's and B's
medians. A ratio above 1 is B slower.

The base defaults to BASELINE (below), not to the previous commit, so that a series of small
steps shows its total. Builds go to --cache (default $HYBRIDLAB_DRIFT_CACHE or
~/.cache/hybridlab-drift), one folder per source tree (`git archive` of the commit), reused while
that tree's build is there. ccache shares objects between those folders and other checkouts only
when they lie under its base_dir (on this project's machine: /work). `--worktree` measures the
working tree's tracked files, uncommitted changes included (`git stash create`), as B.
`--realtime` runs each bench under `chrt -f 50` and passes `run --realtime` (the runner raises
only its timed rounds: lavapipe's shader compiler must not be starved); without the permission it
says so and times at normal priority. On a quiet machine, time at normal priority.

Progress goes to stderr, the table to stdout. Exit status 0 whatever the ratios (a measurement,
not a test), 2 for bad options or commits, 1 when a build or a measurement fails."""
import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "report"))
import timing  # noqa: E402

# The last commit before the Embree Whitted tracer's optimization work: every step of it is
# compared with this, so that the series shows its total.
BASELINE = "64e419c"
DEFAULT_SIZE = (1280, 720)
QUICK_SIZE = (160, 90)
BENCH_SCENES = ("whitted-classic", "sponza-spheres")
STEADY_SCENE = "sponza-spheres"
HIDDEN_DEVICE = {"VK_ICD_FILENAMES": "/nonexistent"}
BUILT_MARKER = "drift-check-built"

# The quantities compared, in the table's order: (key, label).
QUANTITIES = [
    ("whitted-classic.reference_ms", "whitted-classic reference frame"),
    ("whitted-classic.resolved_ms", "whitted-classic hits resolved, unshaded"),
    ("whitted-classic.bare_ms", "whitted-classic bare Embree"),
    ("sponza-spheres.reference_ms", "sponza-spheres reference frame"),
    ("sponza-spheres.resolved_ms", "sponza-spheres hits resolved, unshaded"),
    ("sponza-spheres.bare_ms", "sponza-spheres bare Embree"),
    ("steady.rt_only.frame_ms", "sponza-spheres rt_only frame"),
    ("steady.heuristic_rt.trace_ms", "sponza-spheres heuristic_rt trace stage"),
    ("steady.ssr_fallback.trace_ms", "sponza-spheres ssr_fallback trace stage"),
]

# bench's line after those read: an older bench (no --embree-only) is stopped there.
LAST_BENCH_LINE = "resolved / bare Embree"
BENCH_LINES = {
    "reference_ms": "reference frame",
    "bare_ms": "bare Embree, same rays",
    "resolved_ms": "hits resolved, unshaded",
}


class BadInput(Exception):
    """Bad options or commits: one message, exit status 2."""


class Failure(Exception):
    """A build or a measurement that failed: exit status 1."""


def progress(text):
    print("drift_check: " + text, file=sys.stderr, flush=True)


# --- reading what the program prints -------------------------------------------------------------

def parse_bench(text):
    """{reference_ms, bare_ms, resolved_ms}: the medians of `hybridlab bench`'s Embree lines."""
    found = {}
    for key, label in BENCH_LINES.items():
        m = re.search(r"^" + re.escape(label) + r"\s+([0-9.]+) ms median", text, re.MULTILINE)
        if not m:
            raise Failure("bench printed no '%s ... ms median' line:\n%s" % (label, text[-2000:]))
        found[key] = float(m.group(1))
    return found


def parse_steady(records):
    """{rt_only.frame_ms, heuristic_rt.trace_ms, ssr_fallback.trace_ms} from the records of the
    steady-state run (results.json): medians over the runner's rounds."""
    by_label = {r["label"]: r for r in records}
    missing = [name for name in ("rt_only", "heuristic_rt", "ssr_fallback") if name not in by_label]
    if missing:
        raise Failure("the steady-state run recorded no %s" % ", ".join(missing))
    found = {"rt_only.frame_ms": by_label["rt_only"]["frame_ms"]["median"]}
    for name in ("heuristic_rt", "ssr_fallback"):
        stages = by_label[name]["stages"]
        if "trace" not in stages:
            raise Failure("%s recorded no trace stage (stages: %s)" % (name, ", ".join(sorted(stages))))
        found[name + ".trace_ms"] = stages["trace"]["median"]
    return found


def steady_config(width, height, repeats):
    """The experiment that times rt_only and the hybrids' steady-state frames: exactly `repeats`
    rounds, scored by RMSE alone (the cheapest score) and no optional images."""
    return """[experiment]
name = "drift-check-steady"
warmup_frames = 1
repeats = %d
max_rounds = %d
metrics = ["rmse"]
keep = []

[reference]
timed = false

[[scenes]]
scene = "%s"
resolutions = [[%d, %d]]
views = [{}]

[[techniques]]
name = "rt_only"

[[techniques]]
name = "heuristic_rt"

[[techniques]]
name = "ssr_fallback"
""" % (repeats, repeats, STEADY_SCENE, width, height)


# --- statistics ----------------------------------------------------------------------------------

def paired_ratios(a_values, b_values):
    """B/A of each alternation, where both were measured."""
    return [b / a for a, b in zip(a_values, b_values) if a > 0.0]


def summarize(a_values, b_values):
    """{a, b: medians; ratio: median of the paired B/A; low, high: their min and max; interval:
    timing.Interval or None (fewer than 6 alternations)}."""
    ratios = paired_ratios(a_values, b_values)
    if not ratios:
        return None
    return {"a": statistics.median(a_values), "b": statistics.median(b_values), "ratio": statistics.median(ratios),
            "low": min(ratios), "high": max(ratios), "interval": timing.median_interval(ratios), "n": len(ratios)}


def table(measured):
    """The comparison as lines: `measured` is {quantity key: ([A values], [B values])}."""
    lines = ["%-42s %10s %10s %7s %15s %15s" % ("quantity (ms, medians)", "A", "B", "B/A", "min-max", "95% interval")]
    for key, label in QUANTITIES:
        a, b = measured.get(key, ([], []))
        s = summarize(a, b)
        if s is None:
            lines.append("%-42s %10s %10s %7s" % (label, "-", "-", "-"))
            continue
        interval = s["interval"]
        lines.append("%-42s %10.2f %10.2f %7.3f %15s %15s" % (
            label, s["a"], s["b"], s["ratio"], "%.3f-%.3f" % (s["low"], s["high"]),
            "%.3f-%.3f" % (interval.low, interval.high) if interval else "(n < 6)"))
    return lines


def alternation_order(k):
    """ABBA: alternation 0 runs A first, 1 runs B first, and so on."""
    return ("A", "B") if k % 2 == 0 else ("B", "A")


# --- options, commits and builds ----------------------------------------------------------------

def parse_size(text):
    m = re.fullmatch(r"(\d+)x(\d+)", text)
    if not m or not (16 <= int(m.group(1)) <= 16384 and 16 <= int(m.group(2)) <= 16384):
        raise BadInput("--size %s: expected WIDTHxHEIGHT, each 16 to 16384 (say 1280x720)" % text)
    return int(m.group(1)), int(m.group(2))


def git(repo, *args, check=True):
    done = subprocess.run(["git", "-C", repo] + list(args), capture_output=True, text=True)
    if check and done.returncode != 0:
        raise Failure("git %s: %s" % (" ".join(args), done.stderr.strip()))
    return done


def resolve_commit(repo, name, option):
    done = git(repo, "rev-parse", "--verify", "--quiet", name + "^{commit}", check=False)
    if done.returncode != 0:
        raise BadInput("%s %s: not a commit of %s" % (option, name, repo))
    return done.stdout.strip()


def worktree_commit(repo):
    """A commit of the working tree's tracked files as they are (HEAD's when nothing changed)."""
    stashed = git(repo, "stash", "create").stdout.strip()
    return stashed or git(repo, "rev-parse", "HEAD").stdout.strip()


def build(repo, commit, cache):
    """The program built from `commit`'s tree (exported under `cache`, built once); its path."""
    tree = git(repo, "rev-parse", commit + "^{tree}").stdout.strip()
    folder = os.path.join(cache, tree[:12])
    build_dir = os.path.join(folder, "build")
    program = os.path.join(build_dir, "hybridlab")
    if os.path.exists(os.path.join(build_dir, BUILT_MARKER)) and os.access(program, os.X_OK):
        progress("%s: built in %s" % (commit[:12], folder))
        return program
    if not os.path.exists(os.path.join(folder, "CMakeLists.txt")):
        os.makedirs(cache, exist_ok=True)
        export = tempfile.mkdtemp(prefix=tree[:12] + ".", dir=cache)
        archive = subprocess.Popen(["git", "-C", repo, "archive", commit], stdout=subprocess.PIPE)
        subprocess.run(["tar", "-x", "-C", export], stdin=archive.stdout, check=True)
        if archive.wait() != 0:
            raise Failure("git archive %s failed" % commit)
        os.rename(export, folder)
    progress("%s: building in %s (a few minutes; log: %s)" % (commit[:12], folder, os.path.join(folder, "build.log")))
    # The export is no checkout: git must not describe the repository around the cache instead.
    env = dict(os.environ, GIT_CEILING_DIRECTORIES=os.path.dirname(os.path.abspath(folder)))
    launcher = ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"] if shutil.which("ccache") else []
    steps = [["cmake", "-S", folder, "-B", build_dir, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release"] + launcher,
             ["cmake", "--build", build_dir, "-j", str(os.cpu_count() or 1), "--target", "hybridlab"]]
    with open(os.path.join(folder, "build.log"), "a") as log:
        for step in steps:
            if subprocess.run(["nice", "-n", "10"] + step, stdout=log, stderr=subprocess.STDOUT, env=env).returncode != 0:
                raise Failure("building %s failed: see %s" % (commit[:12], os.path.join(folder, "build.log")))
    with open(os.path.join(build_dir, BUILT_MARKER), "w") as marker:
        marker.write(commit + "\n")
    return program


def realtime_permitted():
    return shutil.which("chrt") is not None and subprocess.run(["chrt", "-f", "50", "true"], capture_output=True).returncode == 0


# --- measuring -----------------------------------------------------------------------------------

class Program:
    """One commit's program and how it is measured."""

    def __init__(self, name, commit, path):
        self.name, self.commit, self.path = name, commit, path
        helped = subprocess.run([path, "bench", "--help"], capture_output=True, text=True, env=dict(os.environ, **HIDDEN_DEVICE))
        self.embree_only = "--embree-only" in helped.stdout
        self.other_loads = []  # the runner's timing.other_load of each steady-state run

    def bench(self, scene, args):
        command = [self.path, "bench", "--scene", scene, "--width", str(args.width), "--height", str(args.height),
                   "--threads", str(args.threads), "--repeats", str(args.repeats)]
        if self.embree_only:
            command.append("--embree-only")
        else:
            # An older bench goes on to its one-thread split (seconds a repeat at 1280x720): its
            # output line-buffered, so that it is stopped once the lines read here are out.
            command = ["stdbuf", "-oL"] + command
        if args.realtime:
            command = ["chrt", "-f", "50"] + command
        bench = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                 env=dict(os.environ, **HIDDEN_DEVICE))
        lines, stopped = [], False
        for line in bench.stdout:
            lines.append(line)
            if not self.embree_only and line.startswith(LAST_BENCH_LINE):
                bench.terminate()
                stopped = True
                break
        _, errors = bench.communicate()
        if bench.returncode != 0 and not stopped:
            raise Failure("%s failed (exit %d): %s" % (" ".join(command), bench.returncode, errors.strip()[-2000:]))
        return parse_bench("".join(lines))

    def steady(self, args, scratch):
        config = os.path.join(scratch, "steady.toml")
        with open(config, "w") as f:
            f.write(steady_config(args.width, args.height, args.repeats))
        out = os.path.join(scratch, "steady-%s" % self.name)
        shutil.rmtree(out, ignore_errors=True)
        # References cached beside the program: each commit scores against its own.
        cache = os.path.join(os.path.dirname(self.path), "drift-check-references")
        command = [self.path, "run", config, "--out", out, "--cache", cache, "--quiet"] + (["--realtime"] if args.realtime else [])
        done = subprocess.run(command, capture_output=True, text=True)
        if done.returncode != 0:
            raise Failure("%s failed (exit %d): %s" % (" ".join(command), done.returncode, done.stderr.strip()[-2000:]))
        with open(os.path.join(out, "results.json")) as f:
            records = json.load(f)
        shutil.rmtree(out, ignore_errors=True)
        self.other_loads += [r["timing"]["other_load"] for r in records[:1] if (r.get("timing") or {}).get("other_load") is not None]
        return parse_steady(records)


def measure(programs, args):
    """{quantity key: ([A values], [B values])} over the alternations."""
    measured = {key: ([], []) for key, _ in QUANTITIES}
    side = {"A": 0, "B": 1}
    with tempfile.TemporaryDirectory(prefix="drift-check.") as scratch:
        for k in range(args.alternations):
            order = alternation_order(k)
            steps = [(scene, lambda p, s=scene: p.bench(s, args)) for scene in BENCH_SCENES]
            steps.append(("steady", lambda p: p.steady(args, scratch)))
            for prefix, step in steps:
                for name in order:
                    start = time.monotonic()
                    values = step(programs[name])
                    for key, value in values.items():
                        measured["%s.%s" % (prefix, key)][side[name]].append(value)
                    progress("alternation %d/%d, %s %s: %s (%.0f s)" % (
                        k + 1, args.alternations, name, prefix, ", ".join("%s %.2f" % kv for kv in sorted(values.items())),
                        time.monotonic() - start))
    return measured


def options(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--base", default=BASELINE, help="commit A (default %(default)s, the baseline)")
    heads = ap.add_mutually_exclusive_group()
    heads.add_argument("--head", default="HEAD", help="commit B (default: HEAD)")
    heads.add_argument("--worktree", action="store_true", help="B: the working tree's tracked files, uncommitted changes included")
    ap.add_argument("--alternations", type=int, default=None, help="A-B pairs, in ABBA order (default 5; --quick 2)")
    ap.add_argument("--size", default=None, help="WIDTHxHEIGHT (default 1280x720; --quick 160x90)")
    ap.add_argument("--repeats", type=int, default=None, help="bench repeats and the runner's rounds (default 5; --quick 3)")
    ap.add_argument("--threads", type=int, default=2, help="bench's worker threads (default 2; the runner uses every core)")
    ap.add_argument("--realtime", action="store_true", help="bench under chrt -f 50, run --realtime (when permitted)")
    ap.add_argument("--quick", action="store_true", help="a smoke test: 160x90, 2 alternations, 3 repeats")
    ap.add_argument("--cache", default=os.environ.get("HYBRIDLAB_DRIFT_CACHE") or os.path.expanduser("~/.cache/hybridlab-drift"),
                    help="where the commits are exported and built (default: $HYBRIDLAB_DRIFT_CACHE or %(default)s)")

    ap.error = lambda message: (_ for _ in ()).throw(BadInput(message))
    args = ap.parse_args(argv)
    args.alternations = args.alternations if args.alternations is not None else 2 if args.quick else 5
    args.repeats = args.repeats if args.repeats is not None else 3 if args.quick else 5
    args.width, args.height = parse_size(args.size) if args.size else QUICK_SIZE if args.quick else DEFAULT_SIZE
    if args.alternations < 1:
        raise BadInput("--alternations %d: expected at least 1" % args.alternations)
    if not 1 <= args.repeats <= 1000:
        raise BadInput("--repeats %d: expected 1 to 1000" % args.repeats)
    if not 1 <= args.threads <= 1024:
        raise BadInput("--threads %d: expected 1 to 1024" % args.threads)
    return args


def main(argv):
    args = options(argv)
    repo = os.path.abspath(os.path.join(HERE, ".."))  # the checkout this script is in
    base = resolve_commit(repo, args.base, "--base")
    head = worktree_commit(repo) if args.worktree else resolve_commit(repo, args.head, "--head")
    if args.realtime and not realtime_permitted():
        progress("--realtime: chrt -f 50 is not permitted here (needs root, CAP_SYS_NICE or RLIMIT_RTPRIO >= 50); "
                 "timing at normal priority")
        args.realtime = False
    programs = {"A": Program("A", base, build(repo, base, args.cache)), "B": Program("B", head, build(repo, head, args.cache))}
    for p in programs.values():
        if not p.embree_only:
            progress("%s (%s): bench has no --embree-only; it is stopped after the lines read" % (p.name, p.commit[:12]))
    load = os.getloadavg()[0]
    start = time.monotonic()
    measured = measure(programs, args)
    print("A = %s (--base %s), B = %s (%s)" % (base[:12], args.base, head[:12], "working tree" if args.worktree else "--head " + args.head))
    print("%dx%d, %d alternations (ABBA), %d repeats, bench on %d threads, %s priority; load average %.1f before, %.1f after; %.0f s"
          % (args.width, args.height, args.alternations, args.repeats, args.threads, "real-time" if args.realtime else "normal", load,
             os.getloadavg()[0], time.monotonic() - start))
    loads = sorted(programs["A"].other_loads + programs["B"].other_loads)
    if loads:
        # Load slows settings unequally, which no pairing cancels (experiments/README.md, Timing).
        print("other processes' load while the runner timed the steady frames: median %.0f%%, max %.0f%% of the cores%s"
              % (100.0 * statistics.median(loads), 100.0 * loads[-1],
                 "; a busy machine: ratios spread, take them with their min-max" if loads[-1] > timing.BUSY_MACHINE else ""))
    print("\n".join(table(measured)))
    print("B/A: the median over the alternations of B's time over A's in the same alternation (above 1: B slower)")


if __name__ == "__main__":
    try:
        main(sys.argv[1:])
    except BadInput as e:
        print("drift_check: %s" % e, file=sys.stderr)
        sys.exit(2)
    except Failure as e:
        print("drift_check: %s" % e, file=sys.stderr)
        sys.exit(1)
