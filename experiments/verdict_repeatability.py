#!/usr/bin/python3
"""Does the verdict hold from run to run? Runs one experiment several times back to back (the
references cached), optionally with busy loops on every core throughout, and compares the
report's verdict rows: per scene, size and SSIM threshold, the fastest setting (or the settings
the rounds cannot tell from it, tied or not decided) reaching it.

    /usr/bin/python3 experiments/verdict_repeatability.py [--config experiments/configs/quick.toml]
        [--runs 3] [--busy N] [--realtime] [--out DIR] [--program build/hybridlab] [--reuse]

Prints each run's wall time, the load other processes put on the machine while it was timed
(`timing.other_load`), and its rows, then first the contradictions (rows where two runs' fastest
sets share no setting: one run's answer excludes another's), then how many rows name the same
settings in every run, and the mean number of settings a row names (the price of naming only
what the rounds can tell apart).
`--busy N` keeps N busy loops (one process each) running while the experiments run; `--reuse`
reports result sets already in DIR/run-K instead of running them (where some lack their images,
as the GPU campaign's repeats do, no run's images are compared); `--against DIR` also counts the
rows identical to the first run in DIR (say, quiet runs against runs under load); `--speedups
rt_only` also checks every later run's speed-up over rt_only against the first run's interval
(`--config experiments/configs/gbuffer_rays.toml --runs 2 --speedups rt_only`). `--realtime`
passes `run --realtime`: the runner times its rounds at real-time priority while the busy loops
stay at normal priority (run as root or with CAP_SYS_NICE). Run quiet runs on a quiet machine at
normal priority. Under load, wall time ranks settings as the load has them (a parallel frame
waits for its preempted thread, a serial one barely notices): `--busy 2` at normal priority gave
the quiet verdict in 8 to 12 of 18 rows, `--busy 2 --realtime` in 18 of 18. Do not start the
script itself under `chrt`: its busy loops would then be real-time too and starve the thread Mesa
runs at batch priority (lavapipe's shader compiler), stalling a run for minutes. Each run prints
the load other processes put on the machine: near 0 is a quiet run. Exit status 0 whatever
agrees: this is a measurement, not a test."""
import argparse
import functools
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "report"))
import results as rs  # noqa: E402
import timing  # noqa: E402
import verdict  # noqa: E402


@functools.lru_cache(maxsize=None)
def verdicts_of(result_dir):
    """A result set's verdicts, read once (the speed-ups and the rows read the same ones; each
    reading hashes every image of the set)."""
    return verdict.verdicts(rs.load(result_dir), result_dir)


def verdict_rows(result_dir):
    """{(scene, size, region, threshold): (the names of the row's fastest set, its decision)} of
    one result set; no names where nothing reaches the threshold."""
    rows = {}
    for v in verdicts_of(result_dir):
        for region, label, threshold, fastest in v.thresholds:
            rows[(v.scene, v.size, label, threshold)] = (tuple(s.name for s in fastest.settings), fastest.decision)
    return rows


def row_text(row):
    names, decision = row
    if not names:
        return "none"
    return " and ".join(names) + ("" if len(names) == 1 else " (%s)" % decision)


def contradicts(rows):
    """Whether some two of a row's answers over the runs share no setting."""
    sets = [set(names) for names, _ in rows]
    return any(not (a & b) for i, a in enumerate(sets) for b in sets[i + 1:])


def setting_speedups(result_dir, over):
    """{(scene, size, setting): speed-up} of a result set's settings over `over` ("rt_only",
    "reference") as its report computes them (verdict.py: the runner's paired interval where it
    recorded one, else the rounds paired or pooled, else the ratio of the medians)."""
    out = {}
    for v in verdicts_of(result_dir):
        for name, s in v.settings.items():
            ref, rt = v.speedups(s)
            value = rt if over == "rt_only" else ref
            if value is not None and s is not v.rt_only:
                out[(v.scene, v.size, name)] = value
    return out


def speedups_held(first_dir, later_dir, over):
    """Whether each run's speed-up over `over` ("rt_only", "reference") measured in `later_dir`
    lies in the first run's 95% interval, or within 5% of its median: (lines, held, compared)."""
    first, later = setting_speedups(first_dir, over), setting_speedups(later_dir, over)
    lines, held, compared = [], 0, 0
    for key in sorted(set(first) & set(later)):
        a, b = first[key], later[key]
        a_ratio = a.median if isinstance(a, timing.Interval) else a
        b_ratio = b.median if isinstance(b, timing.Interval) else b
        inside = isinstance(a, timing.Interval) and a.low <= b_ratio <= a.high
        close = abs(b_ratio / a_ratio - 1.0) <= 0.05
        compared += 1
        held += inside or close
        lines.append("%s %s %s: %s then %.3fx%s" % (
            key[0], key[1], key[2], a.text("%.3f", "x") if isinstance(a, timing.Interval) else "%.3fx (no interval)" % a, b_ratio,
            "" if inside or close else "   <- outside the interval and over 5% off"))
    return lines, held, compared


def busy_loops(count):
    return [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(count)]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--config", default=os.path.join(HERE, "configs", "quick.toml"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--busy", type=int, default=0, help="busy loops running throughout")
    ap.add_argument("--out", default="results/verdict-repeatability")
    ap.add_argument("--program", default=os.path.join(HERE, "..", "build", "hybridlab"))
    ap.add_argument("--realtime", action="store_true", help="pass --realtime to `hybridlab run`: its timed frames run "
                    "at real-time priority, ahead of the busy loops (which stay at normal priority)")
    ap.add_argument("--reuse", action="store_true", help="report the result sets already in --out")
    ap.add_argument("--against", help="a folder of earlier runs (run-1, ...): count the rows identical to its first")
    ap.add_argument("--speedups", metavar="OVER", help="also compare each run's speed-ups over OVER (rt_only or "
                    "reference) with the first run's: inside its 95%% interval, or within 5%%")
    args = ap.parse_args()

    loops = busy_loops(args.busy)
    tables = []
    if args.reuse and any(not os.path.isdir(os.path.join(args.out, "run-%d" % (k + 1), "images")) for k in range(args.runs)):
        # Runs kept without their images (the GPU campaign's repeats): no run's images are compared
        # (verdict.py marks settings whose images are byte-identical to another's), so that every
        # run's rows are read alike.
        verdict.image_digest = lambda result_dir, r: None
        print("some runs have no images: settings with byte-identical images are not looked for in any run")
    try:
        for k in range(args.runs):
            out = os.path.join(args.out, "run-%d" % (k + 1))
            if not args.reuse:
                if os.path.exists(out):
                    sys.exit("%s: exists; remove it or pass --reuse" % out)
                start = time.monotonic()
                subprocess.run([args.program, "run", args.config, "--out", out, "--quiet"] + (["--realtime"] if args.realtime else []),
                               check=True)
                print("run %d: %.1f s%s" % (k + 1, time.monotonic() - start, " (%d busy loops)" % args.busy if args.busy else ""), flush=True)
            tables.append(verdict_rows(out))
            loads = sorted(r["timing"]["other_load"] for r in rs.load(out) if (r.get("timing") or {}).get("other_load") is not None)
            if loads:
                print("run %d: other processes' load while timed: median %.0f%%, max %.0f%% of the cores"
                      % (k + 1, 100.0 * loads[len(loads) // 2], 100.0 * loads[-1]), flush=True)
    finally:
        for p in loops:
            p.kill()

    keys = sorted(set().union(*tables))
    same = contradictions = 0
    named = []
    for key in keys:
        rows = [t.get(key, ((), "-")) for t in tables]
        agree = len(set(rows)) == 1
        contradiction = contradicts(rows)
        same += agree
        contradictions += contradiction
        named += [len(names) for names, _ in rows if names]
        scene, size, label, threshold = key
        print("%s %s SSIM >= %.2f %s: %s%s" % (scene, size, threshold, label, " | ".join(row_text(r) for r in rows),
                                               "   <- contradicts" if contradiction else "" if agree else "   <- differs"))
    print("%d of %d verdict rows contradict another run's (their fastest sets share no setting)" % (contradictions, len(keys)))
    print("%d of %d verdict rows identical in all %d runs; a row names %.2f settings on average"
          % (same, len(keys), len(tables), sum(named) / max(len(named), 1)))
    if args.speedups:
        first = os.path.join(args.out, "run-1")
        for k in range(1, len(tables)):
            lines, held, compared = speedups_held(first, os.path.join(args.out, "run-%d" % (k + 1)), args.speedups)
            print("\n".join(lines))
            print("run %d: %d of %d speed-ups over %s inside run 1's interval or within 5%% of it" % (k + 1, held, compared, args.speedups))
    if args.against:
        baseline = verdict_rows(os.path.join(args.against, "run-1"))
        for k, t in enumerate(tables):
            agree = sum(t.get(key, "-") == baseline.get(key, "-") for key in keys)
            print("run %d: %d of %d rows identical to %s's first run" % (k + 1, agree, len(keys), args.against))


if __name__ == "__main__":
    main()
