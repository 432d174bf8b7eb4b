#!/usr/bin/python3
"""The paper-table scripts' speed-up columns: "2.00x (1.90-2.20)", the median and 95% interval of
the per-round ratios, where the records hold the runner's rounds; the ratio of the medians as before
where they do not (walewski_tables, sabino_table3, ssr_speed_table, gbuffer_rays_table,
hakura_tables), and pareto_table's time ratio with its interval and the ties in time. Each script
runs as the README says (Debian's python3, RESULT_DIR) on result sets made up here
(tests/support/synthetic_records.py).

    speedup_columns_test.py        (standard library unittest; no hybridlab program needed)"""
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPTS = os.path.join(HERE, "..", "..", "paper_figures")
sys.path.insert(0, os.path.join(HERE, "..", "support"))
import synthetic_records as sr  # noqa: E402

# The other setting's time over this one's in each of 8 rounds: median 2.00, 95% interval the
# smallest and largest (8 values: ranks 1 and 8).
RATIOS = [1.9, 1.95, 2.0, 2.0, 2.0, 2.0, 2.1, 2.2]
OWN = [10.0, 10.5, 9.8, 10.2, 10.1, 9.9, 10.3, 10.0]
SLOW = [x * q for x, q in zip(OWN, RATIOS)]
RASTER_STAGES = {"gbuffer": {"median": 2.0, "min": 2.0, "max": 2.0}, "trace": {"median": 6.0, "min": 6.0, "max": 6.0},
                 "ssr": {"median": 1.0, "min": 1.0, "max": 1.0}}
COUNTERS = {"rays_total": 1000.0, "rays_lens_pixels": 5000.0, "ssr_hit_rate": 0.5, "fallback_rays": 10.0, "lens_pixels": 100.0}


def pair(scene, own, other, rounds=True, timing_id=None, **kinds):
    """Two runs of one group: `own` = (technique, label) timed OWN, `other` timed SLOW (2x), in a
    timing of their own unless `timing_id` names one that other pairs share (one call of the runner
    timing all of them: only then do their rounds pair)."""
    g = sr.Group(scene, [50.0] * 8, timing_id=timing_id)
    if rounds:
        return [sr.timed_record(g, technique, params, times, label=label, counters=COUNTERS, stages=RASTER_STAGES, **kinds)
                for (technique, label, params), times in ((own, OWN), (other, SLOW))]
    return [sr.old_record(scene, technique, params, ms, label=label, counters=COUNTERS, stages=RASTER_STAGES)
            for (technique, label, params), ms in ((own, 10.0), (other, 20.0))]


def run(script, records):
    with tempfile.TemporaryDirectory() as d:
        sr.write_set(d, records)
        out = subprocess.run(["/usr/bin/python3", os.path.join(SCRIPTS, script), d], capture_output=True, text=True)
    if out.returncode != 0:
        raise AssertionError("%s: exit %d\n%s" % (script, out.returncode, out.stderr))
    return out.stdout


def row(text, start):
    """The cells of the first table line starting with `start`."""
    line = next(l for l in text.splitlines() if l.startswith(start))
    return [c.strip() for c in line.strip("|").split("|")]


class SpeedUpColumns(unittest.TestCase):
    def check(self, script, records_of, start, column, with_rounds, without_rounds):
        self.assertEqual(row(run(script, records_of(True)), start)[column], with_rounds)
        self.assertEqual(row(run(script, records_of(False)), start)[column], without_rounds)

    def test_walewski_tables(self):
        def records(rounds):
            hyb, rt = pair("s", ("heuristic_rt", "heuristic", ""), ("rt_only", "rt_only", ""), rounds, timing_id="s")
            _, whitted = pair("s", ("heuristic_rt", "heuristic", ""), ("whitted", "whitted", ""), rounds, timing_id="s")
            nh, _ = pair("s", ("heuristic_rt", "no-heuristic", "x=1"), ("rt_only", "rt_only", "z"), rounds)
            return [hyb, rt, whitted, nh]
        self.check("walewski_tables.py", records, "| &nbsp;&nbsp;speed-up over rt_only |", 1, "2.00x (1.90-2.20)", "2.00x")
        self.check("walewski_tables.py", records, "| &nbsp;&nbsp;speed-up over whitted |", 1, "2.00x (1.90-2.20)", "2.00x")

    def test_sabino_table3(self):
        self.check("sabino_table3.py", lambda rounds: pair("s", ("heuristic_rt", "hybrid", ""), ("rt_only", "rt", ""), rounds),
                   "| s |", 6, "2.00x (1.90-2.20)", "2.00")

    def test_ssr_speed_table(self):
        self.check("ssr_speed_table.py", lambda rounds: pair("s", ("ssr_fallback", "ssr_fallback", ""), ("whitted", "whitted", ""), rounds),
                   "| s | 64x36 | defaults |", 5, "2.00x (1.90-2.20)", "2.00")

    def test_gbuffer_rays_table(self):
        self.check("gbuffer_rays_table.py", lambda rounds: pair("s", ("heuristic_rt", "hyb", ""), ("rt_only", "rt_only", ""), rounds),
                   "| s | 64x36 | camera | hyb |", 6, "2.00x (1.90-2.20)", "2.00")

    def test_hakura_tables(self):
        def records(rounds):
            return pair("teapot-lens", ("layered_em", "lem-tau3", ""), ("whitted", "two-term-rt", ""), rounds)
        self.check("hakura_tables.py", records, "| **time reduction** (paper 25-45x) |", 2, "2.0x (1.9-2.2)", "2.0")


class ParetoTable(unittest.TestCase):
    """Against rt_only: a setting 2x faster in every round and two 1% apart (tied with each other)."""

    def records(self):
        g = sr.Group("s", [50.0] * 8)
        rt = sr.timed_record(g, "rt_only", "", SLOW, ssim=1.0, counters=COUNTERS)
        a = sr.timed_record(g, "hyb", "k=a", OWN, ssim=0.95, counters=COUNTERS)
        b = sr.timed_record(g, "hyb", "k=b", [x * 1.01 for x in OWN], ssim=0.97, counters=COUNTERS)
        c = sr.timed_record(g, "hyb", "k=c", [x * 1.5 for x in OWN], ssim=0.99, counters=COUNTERS)
        return [rt, a, b, c]

    def test_time_ratio_with_its_interval_and_ties(self):
        text = run("pareto_table.py", self.records())
        cells = {name: row(text, "| %s |" % name) for name in ("hyb [k=a]", "hyb [k=b]", "hyb [k=c]")}
        self.assertRegex(cells["hyb [k=a]"][1], r"^0\.50 \(0\.45-0\.53\)$")
        self.assertEqual([cells[n][2] for n in ("hyb [k=a]", "hyb [k=b]", "hyb [k=c]")], ["", "hyb [k=a]", ""])
        self.assertIn("paired over the rounds, with its 95% interval", text)


if __name__ == "__main__":
    unittest.main()
