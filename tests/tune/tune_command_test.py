#!/usr/bin/python3
"""`hybridlab tune` end to end at 64x36: a search of ssr_fallback on whitted-classic writes a result
set the report reads, whose verdict names tune's answer, and a config `run` accepts; --resume of a
finished search renders nothing and answers alike; a target nothing reaches is said with its
shortfall; bad input exits 2 and writes nothing.

    tune_command_test.py PROGRAM WORK_DIR"""
import contextlib
import io
import json
import os
import shutil
import subprocess
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "report"))
import results as rs  # noqa: E402
import verdict  # noqa: E402

sys.path.insert(0, os.path.join(HERE, "..", "..", "experiments", "tune"))
import stages  # noqa: E402

PROGRAM, WORK = None, None


def tune(*args, out):
    size = [] if "--size" in args else ["--size", "64x36"]
    return subprocess.run([PROGRAM, "tune", "--scene", "whitted-classic", "--cache", os.path.join(WORK, "cache"), "--out", out] + size + list(args),
                          capture_output=True, text=True)


class TuneCommandTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = os.path.join(WORK, "search")
        shutil.rmtree(cls.out, ignore_errors=True)
        cls.first = tune("--target", "ssim>=0.95", "--technique", "ssr_fallback", "--budget-s", "20", out=cls.out)

    def test_a_search_writes_its_answer_a_result_set_and_a_config(self):
        got = self.first
        self.assertEqual(got.returncode, 0, got.stderr + got.stdout)
        with open(os.path.join(self.out, "tune.json")) as f:
            doc = json.load(f)
        self.assertTrue(doc["reached"])
        self.assertEqual([s["name"] for s in doc["stages"]][:2], ["screen", "race"])
        self.assertEqual(doc["stages"][-1]["name"], "final")
        self.assertTrue(doc["choice"])
        # The progress lines name each stage and the answer.
        self.assertIn("tune: stage screen: 51 settings (1 round each: a rough time)", got.stdout)
        self.assertIn("reaching ssim>=0.95", got.stdout)
        # Every setting named reaches the target, on the final stage's own records.
        result = os.path.join(self.out, "result")
        final = {s["setting"]: s for s in doc["stages"][-1]["settings"]}
        for name in doc["choice"]:
            self.assertGreaterEqual(final[name]["ssim"], 0.95, name)
        # The result set's verdict at SSIM 0.95 over ssr_fallback's settings names the same ones (the
        # report's own rule; rt_only, not searched, may be faster at this size).
        records = rs.load(result)
        v = verdict.verdicts(records, result)[0]
        searched = {name: s for name, s in v.settings.items() if s.technique == "ssr_fallback"}
        row = verdict.fastest_reaching(searched, "whole", 0.95, v.tolerance)
        self.assertEqual(sorted(s.name for s in row.settings), sorted(doc["choice"]))
        self.assertTrue(all(s.startswith("ssr_fallback [") for s in doc["choice"]), doc["choice"])
        # The config that reproduces it is one `run` accepts, with the same settings.
        plan = subprocess.run([PROGRAM, "run", os.path.join(self.out, "tune.toml"), "--dry-run"], capture_output=True, text=True)
        self.assertEqual(plan.returncode, 0, plan.stderr)
        self.assertEqual(len(records), len(doc["stages"][-1]["settings"]))

    def test_resuming_a_finished_search_renders_nothing_and_answers_alike(self):
        again = tune("--target", "ssim>=0.95", "--technique", "ssr_fallback", "--budget-s", "20", "--resume", out=self.out)
        self.assertEqual(again.returncode, 0, again.stderr)
        answer = lambda text: text[text.index("tune: the fastest"):]  # noqa: E731
        self.assertEqual(answer(again.stdout), answer(self.first.stdout))
        # Other arguments in the same folder are refused.
        other = tune("--target", "ssim>=0.97", "--technique", "ssr_fallback", "--budget-s", "20", "--resume", out=self.out)
        self.assertEqual(other.returncode, 2)
        self.assertIn("holds a search with other arguments (target: ssim>=0.95 there)", other.stderr)

    def test_an_unreachable_target_says_how_far_it_falls_short(self):
        out = os.path.join(WORK, "unreachable")
        shutil.rmtree(out, ignore_errors=True)
        got = tune("--target", "ssim>=0.9999999", "--technique", "ssr_fallback", "--budget-s", "10", out=out)
        self.assertEqual(got.returncode, 0, got.stderr)
        self.assertRegex(got.stdout, r"not reached: no setting reaches ssim>=0.9999999; the best is .* with ssim = [0-9.]+, [0-9.]+ short")
        with open(os.path.join(out, "tune.json")) as f:
            doc = json.load(f)
        self.assertFalse(doc["reached"])
        self.assertGreater(doc["shortfall"], 0.0)
        self.assertFalse(os.path.exists(os.path.join(out, "tune.toml")))

    def test_rt_only_searched_is_timed_once_as_its_own_anchor(self):
        # rt_only's grid holds its defaults, the setting every stage times as its anchor: one
        # setting, not two (the runner refuses a stage that lists one run twice).
        out = os.path.join(WORK, "rt_only")
        shutil.rmtree(out, ignore_errors=True)
        got = tune("--target", "ssim>=0.5", "--technique", "rt_only", "--size", "32x18", "--budget-s", "2", out=out)
        self.assertEqual(got.returncode, 0, got.stderr + got.stdout)
        self.assertIn("tune: stage screen: 12 settings", got.stdout)
        with open(os.path.join(out, "tune.json")) as f:
            doc = json.load(f)
        self.assertTrue(doc["reached"])
        self.assertTrue(all(s.startswith("rt_only") for s in doc["choice"]), doc["choice"])

    def test_bad_input_exits_2_and_writes_nothing(self):
        out = os.path.join(WORK, "bad")
        cases = [(["--target", "ssim>0.9"], "expected METRIC>=VALUE"),
                 (["--target", "sharpness>=0.9"], "unknown metric 'sharpness'"),
                 (["--target", "ssim>=0.9", "--technique", "nope"], "--technique nope: unknown technique"),
                 (["--target", "ssim>=0.9", "--technique", "layered_em"], "declares no knobs to search"),
                 (["--target", "ssim>=0.9", "--size", "64by36"], "expected WIDTHxHEIGHT"),
                 (["--target", "ssim>=0.9", "--budget-s", "0"], "expected a positive number"),
                 (["--target", "ssim>=0.9", "--budget-s", "nan"], "expected a positive number"),
                 (["--target", "ssim>=0.9", "--budget-s", "inf"], "expected a positive number"),
                 (["--target", "psnr>=1e400"], "is not a finite number"),
                 (["--target", "ssim>=0.9", "--region", "bogus"], "argument --region: invalid choice: 'bogus'")]
        for args, says in cases:
            shutil.rmtree(out, ignore_errors=True)
            got = tune(*args, out=out)
            self.assertEqual(got.returncode, 2, (args, got.stderr))
            self.assertIn(says, got.stderr, args)
            self.assertEqual(got.stderr.count("\n"), 1, got.stderr)
            self.assertFalse(os.path.exists(out), args)
        got = subprocess.run([PROGRAM, "tune", "--scene", "no-such-scene", "--target", "ssim>=0.9", "--out", out], capture_output=True, text=True)
        self.assertEqual(got.returncode, 2)
        self.assertIn("--scene no-such-scene", got.stderr)
        self.assertFalse(os.path.exists(out))
        # Folders that cannot hold a search: exit 3 under a file, 2 for an empty name or a broken
        # record of the arguments.
        blocker = os.path.join(WORK, "a-file")
        with open(blocker, "w") as f:
            f.write("x")
        got = tune("--target", "ssim>=0.9", out=os.path.join(blocker, "sub"))
        self.assertEqual(got.returncode, 3, got.stderr)
        self.assertIn("cannot be written", got.stderr)
        self.assertEqual(got.stderr.count("\n"), 1, got.stderr)
        got = tune("--target", "ssim>=0.9", out="")
        self.assertEqual(got.returncode, 2, got.stderr)
        self.assertIn("--out: expected a folder", got.stderr)
        broken = os.path.join(WORK, "broken-arguments")
        shutil.rmtree(broken, ignore_errors=True)
        os.makedirs(broken)
        with open(os.path.join(broken, "tune-arguments.json"), "w") as f:
            f.write("{")
        got = tune("--target", "ssim>=0.9", "--resume", out=broken)
        self.assertEqual(got.returncode, 2, got.stderr)
        self.assertIn("cannot be read as a search's arguments", got.stderr)
        self.assertEqual(got.stderr.count("\n"), 1, got.stderr)
        # An existing folder without --resume.
        got = tune("--target", "ssim>=0.95", out=self.out)
        self.assertEqual(got.returncode, 2)
        self.assertIn("exists; pass --resume", got.stderr)

    def test_a_stages_runner_that_fails_is_said_on_tunes_one_line(self):
        # A stand-in for `hybridlab run`: a progress line, then its error, exit 3.
        program = os.path.join(WORK, "failing-run")
        with open(program, "w") as f:
            f.write("#!/bin/sh\necho 'runs 1-2/6' >&2\necho 'hybridlab: error: /cache: cannot create folder (Not a directory)' >&2\nexit 3\n")
        os.chmod(program, 0o755)
        terminal = io.StringIO()
        with contextlib.redirect_stderr(terminal), self.assertRaises(stages.RunFailed) as failed:
            stages.run_experiment(program, "screen.toml", os.path.join(WORK, "no-stage-yet"))
        self.assertEqual(failed.exception.status, 3)
        self.assertEqual(str(failed.exception), "hybridlab run on %s: /cache: cannot create folder (Not a directory)" % (
            os.path.join(WORK, "no-stage-yet")))
        self.assertEqual(terminal.getvalue(), "runs 1-2/6\n")  # the progress still reaches the terminal


if __name__ == "__main__":
    PROGRAM, WORK = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    os.makedirs(WORK, exist_ok=True)
    unittest.main(argv=sys.argv[:1])
