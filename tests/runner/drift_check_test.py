#!/usr/bin/python3
"""experiments/drift_check.py without building anything: bench's text and the runner's records
read, the paired ratios and their table, the ABBA order, the steady-state config, the working
tree's commit, and bad options refused with exit status 2 before any build.

    drift_check_test.py        (standard library unittest; no hybridlab program needed)"""
import os
import subprocess
import sys
import tempfile
import tomllib
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "..", "experiments", "drift_check.py")
sys.path.insert(0, os.path.dirname(SCRIPT))
import drift_check as dc  # noqa: E402

# `hybridlab bench` as a commit without --embree-only prints it with the device hidden.
BENCH_TEXT = """scene whitted-classic, 320x180, view camera, 2 threads, 3 repeats
bvh build                      0.41 ms
rays per frame               151234 (primary 57600, shadow 60000, reflection 20000, refraction 13634); logged 151234
reference frame               21.37 ms median (min 20.90, max 23.02)      7.077 Mrays/s
bare Embree, same rays         9.85 ms median (min 9.60, max 10.40)     15.354 Mrays/s
hits resolved, unshaded       12.40 ms median (min 12.11, max 13.00)    12.196 Mrays/s
reference / bare Embree        46.1 %
resolved / bare Embree         79.4 % (the reference's ceiling: every hit resolved, nothing shaded)
one thread: reference frame 40.10 ms = 17.00 ms inside Embree's calls (42.4 %) + 23.10 ms around them; the same rays bare 17.50 ms; the frame without the clock 39.80 ms
vulkan: not measured (no usable Vulkan device: the Vulkan loader found none)
device traces: not measured (no usable Vulkan device: the Vulkan loader found none)
"""


def record(label, frame_ms, stages):
    spread = lambda v: {"median": v, "min": v, "max": v}  # noqa: E731
    return {"label": label, "technique": label, "frame_ms": spread(frame_ms), "stages": {k: spread(v) for k, v in stages.items()}}


STEADY_RECORDS = [
    record("rt_only", 80.0, {"gbuffer.rays": 30.0, "trace": 50.0}),
    record("heuristic_rt", 60.0, {"gbuffer": 20.0, "heuristic": 1.0, "trace": 25.5, "blend": 2.0}),
    record("ssr_fallback", 70.0, {"gbuffer": 20.0, "ssr": 10.0, "trace": 31.25, "blend": 2.0}),
]


class ReadingTheProgram(unittest.TestCase):
    def test_bench_medians(self):
        self.assertEqual(dc.parse_bench(BENCH_TEXT), {"reference_ms": 21.37, "bare_ms": 9.85, "resolved_ms": 12.40})

    def test_bench_without_a_line_fails(self):
        text = "\n".join(line for line in BENCH_TEXT.splitlines() if not line.startswith("hits resolved"))
        with self.assertRaisesRegex(dc.Failure, "hits resolved, unshaded"):
            dc.parse_bench(text)

    def test_one_thread_line_is_not_read_as_the_reference(self):
        # "one thread: reference frame" must not match the reference frame's own line.
        text = "\n".join(line for line in BENCH_TEXT.splitlines() if not line.startswith("reference frame"))
        with self.assertRaisesRegex(dc.Failure, "reference frame"):
            dc.parse_bench(text)

    def test_steady_frames_and_trace_stages(self):
        self.assertEqual(dc.parse_steady(STEADY_RECORDS),
                         {"rt_only.frame_ms": 80.0, "heuristic_rt.trace_ms": 25.5, "ssr_fallback.trace_ms": 31.25})

    def test_steady_without_a_hybrid_or_its_trace_fails(self):
        with self.assertRaisesRegex(dc.Failure, "ssr_fallback"):
            dc.parse_steady(STEADY_RECORDS[:2])
        untraced = STEADY_RECORDS[:2] + [record("ssr_fallback", 70.0, {"gbuffer": 20.0})]
        with self.assertRaisesRegex(dc.Failure, "no trace stage"):
            dc.parse_steady(untraced)

    def test_steady_config_times_exactly_the_repeats(self):
        config = tomllib.loads(dc.steady_config(320, 180, 4))
        self.assertEqual(config["experiment"]["repeats"], 4)
        self.assertEqual(config["experiment"]["max_rounds"], 4)
        self.assertFalse(config["reference"]["timed"])
        self.assertEqual(config["scenes"][0]["resolutions"], [[320, 180]])
        self.assertEqual([t["name"] for t in config["techniques"]], ["rt_only", "heuristic_rt", "ssr_fallback"])


class PairedRatios(unittest.TestCase):
    def test_median_and_spread_of_the_ratios(self):
        s = dc.summarize([10.0, 10.0, 20.0, 10.0, 10.0], [11.0, 9.0, 20.0, 12.0, 10.0])
        self.assertAlmostEqual(s["ratio"], 1.0)
        self.assertAlmostEqual(s["low"], 0.9)
        self.assertAlmostEqual(s["high"], 1.2)
        self.assertEqual((s["a"], s["b"]), (10.0, 11.0))  # the absolute medians, each over its own side
        self.assertIsNone(s["interval"])  # five alternations: no 95% interval of a median

    def test_paired_not_pooled(self):
        # A drift that slows both alike in one alternation cancels in its ratio.
        s = dc.summarize([10.0, 20.0, 40.0, 10.0, 20.0, 40.0], [11.0, 22.0, 44.0, 11.0, 22.0, 44.0])
        self.assertAlmostEqual(s["low"], 1.1)
        self.assertAlmostEqual(s["high"], 1.1)
        self.assertAlmostEqual(s["interval"].low, 1.1)  # six alternations: the interval is x_(1), x_(6)

    def test_table_rows(self):
        measured = {"whitted-classic.reference_ms": ([20.0, 21.0], [22.0, 21.0])}
        lines = dc.table(measured)
        self.assertEqual(len(lines), 1 + len(dc.QUANTITIES))
        row = next(line for line in lines if line.startswith("whitted-classic reference frame"))
        self.assertIn("1.050", row)  # the median of 1.1 and 1.0
        self.assertIn("1.000-1.100", row)
        self.assertIn("(n < 6)", row)
        self.assertTrue(any(line.startswith("sponza-spheres bare Embree") and line.rstrip().endswith("-") for line in lines))

    def test_abba_order(self):
        self.assertEqual([dc.alternation_order(k) for k in range(4)], [("A", "B"), ("B", "A"), ("A", "B"), ("B", "A")])


class WorktreeCommit(unittest.TestCase):
    def test_uncommitted_changes_make_a_commit_of_their_own(self):
        with tempfile.TemporaryDirectory() as repo:
            def git(*args):
                return subprocess.run(["git", "-C", repo, "-c", "user.name=t", "-c", "user.email=t@t"] + list(args), check=True,
                                      capture_output=True, text=True).stdout.strip()
            git("init", "-q")
            with open(os.path.join(repo, "walk.h"), "w") as f:
                f.write("before\n")
            git("add", "walk.h")
            git("commit", "-q", "-m", "one")
            head = git("rev-parse", "HEAD")
            self.assertEqual(dc.worktree_commit(repo), head)  # nothing changed: HEAD itself
            with open(os.path.join(repo, "walk.h"), "w") as f:
                f.write("after\n")
            changed = dc.worktree_commit(repo)
            self.assertNotEqual(changed, head)
            self.assertEqual(git("show", changed + ":walk.h"), "after")
            self.assertEqual(git("status", "--porcelain"), "M walk.h")  # the working tree left as it was


class BadOptions(unittest.TestCase):
    def refused(self, *args):
        done = subprocess.run([sys.executable, SCRIPT] + list(args), capture_output=True, text=True, timeout=60)
        self.assertEqual(done.returncode, 2, done.stderr)
        self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)
        self.assertEqual(done.stdout, "")
        return done.stderr

    def test_bad_options_exit_2_before_building(self):
        self.assertIn("--size 12x7", self.refused("--size", "12x7"))
        self.assertIn("--size 1280", self.refused("--size", "1280"))
        self.assertIn("--alternations 0", self.refused("--alternations", "0"))
        self.assertIn("--repeats 0", self.refused("--repeats", "0"))
        self.assertIn("--no-such-option", self.refused("--no-such-option"))
        self.assertIn("--worktree", self.refused("--head", "HEAD", "--worktree"))

    def test_a_commit_that_is_not_one(self):
        self.assertIn("--base no-such-commit-here", self.refused("--base", "no-such-commit-here", "--cache", os.devnull))


if __name__ == "__main__":
    unittest.main()
