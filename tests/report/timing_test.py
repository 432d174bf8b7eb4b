#!/usr/bin/python3
"""report/timing.py: the median's distribution-free interval, paired comparisons over rounds and
the tie rule, on known numbers and on made-up records (tests/support/synthetic_records.py).

    timing_test.py        (standard library unittest; no hybridlab program needed)"""
import os
import random
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "report"))
sys.path.insert(0, os.path.join(HERE, "..", "support"))
import synthetic_records as sr  # noqa: E402
import timing  # noqa: E402


class MedianInterval(unittest.TestCase):
    def test_endpoints_are_the_binomial_order_statistics(self):
        six = [5.0, 1.0, 4.0, 2.0, 6.0, 3.0]
        self.assertEqual(timing.median_interval(six), (3.5, 1.0, 6.0))  # n = 6: the smallest and the largest
        ten = [float(v) for v in (10, 3, 7, 1, 9, 5, 2, 8, 6, 4)]
        self.assertEqual(timing.median_interval(ten), (5.5, 2.0, 9.0))  # n = 10: x_(2), x_(9)
        seventeen = [float(v) for v in range(17, 0, -1)]
        self.assertEqual(timing.median_interval(seventeen), (9.0, 5.0, 13.0))  # n = 17: x_(5), x_(13)

    def test_too_few_values_have_no_interval(self):
        for n in range(6):
            self.assertIsNone(timing.median_interval([1.0] * n), n)
        self.assertEqual(timing.interval_ranks(6), (1, 6))

    def test_the_narrowest_pair_that_covers_95_percent(self):
        # P(x_(l) <= median <= x_(n+1-l)) = 1 - 2 P(B < l), B ~ binomial(n, 1/2): at least 0.95 at
        # the chosen l and below it at l + 1.
        def coverage(n, l):
            from math import comb
            return 1.0 - 2.0 * sum(comb(n, i) for i in range(l)) / 2 ** n
        for n in range(6, 80):
            l, u = timing.interval_ranks(n)
            self.assertEqual(u, n + 1 - l)
            self.assertGreaterEqual(coverage(n, l), 0.95, n)
            self.assertLess(coverage(n, l + 1), 0.95, n)

    def test_coverage_on_a_skewed_distribution(self):
        # Lognormal(0, 1), whose median is 1: skewed as frame times are (slow outliers only).
        rng = random.Random(20240611)
        for n in (10, 17, 30):
            draws = [timing.median_interval([rng.lognormvariate(0.0, 1.0) for _ in range(n)]) for _ in range(1000)]
            covered = sum(iv.low <= 1.0 <= iv.high for iv in draws) / 1000.0
            self.assertGreaterEqual(covered, 0.93, n)
            self.assertLessEqual(covered, 0.99, n)

    def test_text(self):
        self.assertEqual(timing.Interval(1.7, 1.64, 1.77).text("%.2f", "x"), "1.70x (1.64-1.77)")


class PairedComparison(unittest.TestCase):
    """Two settings of one scene and size, timed in the same rounds of two groups (a view and a
    frame) on a machine whose load drifts by up to 25% from round to round."""

    def settings(self, slower_by, seed=3):
        reference = sr.drifting_rounds(200.0, 8, seed)
        groups = [sr.Group("s", reference, view="camera"), sr.Group("s", reference, view="path", frame=0)]
        a = [sr.timed_record(g, "hyb", "k=a", sr.drifting_rounds(10.0, 8, seed)) for g in groups]
        b = [sr.timed_record(g, "hyb", "k=b", sr.drifting_rounds(10.0 * slower_by, 8, seed)) for g in groups]
        return a, b

    def test_a_ten_percent_difference_is_called(self):
        a, b = self.settings(1.10)
        self.assertEqual(timing.compare(a, b), (timing.FASTER, "paired rounds"))
        self.assertEqual(timing.compare(b, a), (timing.SLOWER, "paired rounds"))
        ratio = timing.paired_ratio(a, b)
        self.assertAlmostEqual(ratio.median, 1.0 / 1.10, delta=0.01)
        self.assertLess(ratio.high, 1.0)
        # The drift alone makes the medians' own intervals overlap: pairing is what calls it.
        ta, tb = timing.setting_time(a), timing.setting_time(b)
        self.assertTrue(ta.is_interval and tb.is_interval)
        self.assertGreater(ta.high, tb.low)

    def test_a_one_percent_difference_is_a_tie(self):
        a, b = self.settings(1.01)
        self.assertEqual(timing.compare(a, b), (timing.TIED, "paired rounds"))
        self.assertEqual(timing.compare(b, a), (timing.TIED, "paired rounds"))

    def test_beyond_the_noise_but_within_the_precision_is_a_tie(self):
        # 2% slower in every round exactly: the interval lies wholly above 1, the median within 3%.
        a, b = self.settings(1.0)
        for r in b:
            r["timing"]["frame_ms_rounds"] = [x * 1.02 for x in r["timing"]["frame_ms_rounds"]]
        ratio = timing.paired_ratio(a, b)
        self.assertLess(ratio.high, 1.0)
        self.assertEqual(timing.compare(a, b, 0.03)[0], timing.TIED)
        self.assertEqual(timing.compare(a, b, 0.01)[0], timing.FASTER)

    def test_rounds_pair_only_within_a_group(self):
        reference = sr.drifting_rounds(200.0, 8, 1)
        a = [sr.timed_record(sr.Group("s", reference, view="camera"), "hyb", "k=a", sr.drifting_rounds(10.0, 8, 1))]
        b = [sr.timed_record(sr.Group("s", reference, view="path", frame=0), "hyb", "k=b", sr.drifting_rounds(20.0, 8, 1))]
        self.assertEqual(timing.round_ratios(a, b), [])
        # No pairing: the medians' intervals decide (here far apart).
        self.assertEqual(timing.compare(a, b), (timing.FASTER, "intervals"))

    def test_without_intervals_the_lower_median_is_faster(self):
        a = [sr.old_record("s", "hyb", "k=a", 10.0)]
        b = [sr.old_record("s", "hyb", "k=b", 10.1)]
        self.assertEqual(timing.compare(a, b), (timing.FASTER, "medians"))
        self.assertEqual(timing.compare(a, [sr.old_record("s", "hyb", "k=c", 10.0)]), (timing.TIED, "medians"))
        self.assertFalse(timing.has_intervals(a + b))
        self.assertEqual(timing.tolerance(a + b), timing.DEFAULT_TOLERANCE)

    def test_fastest_names_a_tie_whatever_the_order(self):
        a, b = self.settings(1.01)
        _, c = self.settings(1.2)
        runs = {"a": a, "b": b, "c": [dict(r, id=r["id"] + "c") for r in c]}
        for order in (["a", "b", "c"], ["c", "b", "a"], ["b", "c", "a"]):
            self.assertEqual(timing.fastest(order, runs.get, key=str), ["a", "b"], order)

    def test_tolerance_is_the_sets_precision(self):
        g = sr.Group("s", [1.0] * 8)
        records = [sr.timed_record(g, "hyb", "", [1.0] * 8, precision=0.05), sr.timed_record(g, "hyb", "x", [1.0] * 8, precision=0.02)]
        self.assertEqual(timing.tolerance(records), 0.05)


class Caveats(unittest.TestCase):
    def test_runs_timed_under_load_are_named(self):
        g = sr.Group("s", [1.0] * 8)
        quiet, busy = sr.timed_record(g, "hyb", "", [1.0] * 8), sr.timed_record(g, "hyb", "x", [1.0] * 8)
        quiet["timing"]["other_load"], busy["timing"]["other_load"] = 0.05, 0.62
        said = " ".join(timing.caveats([quiet, busy]))
        self.assertIn("1 of 2 runs were timed while other processes used more than 20% of the machine's cores (up to 62%)", said)
        quiet["timing"]["other_load"] = busy["timing"]["other_load"] = 0.1
        self.assertNotIn("other processes", " ".join(timing.caveats([quiet, busy])))
        del quiet["timing"]["other_load"], busy["timing"]["other_load"]  # a result set measured before the meter
        self.assertNotIn("other processes", " ".join(timing.caveats([quiet, busy])))

    def test_runs_timed_ahead_of_the_load_are_not_called_loaded(self):
        g = sr.Group("s", [1.0] * 8)
        quiet, busy = sr.timed_record(g, "hyb", "", [1.0] * 8), sr.timed_record(g, "hyb", "x", [1.0] * 8)
        quiet["timing"]["other_load"], busy["timing"]["other_load"] = 0.05, 0.62
        quiet["timing"]["priority"] = busy["timing"]["priority"] = "realtime"
        said = " ".join(timing.caveats([quiet, busy]))
        self.assertIn("2 of 2 runs were timed at real-time priority (run --realtime), ahead of other processes (which used up "
                      "to 62% of the cores meanwhile).", said)
        self.assertNotIn("answer for a loaded machine", said)
        quiet["timing"]["priority"] = busy["timing"]["priority"] = "normal"
        said = " ".join(timing.caveats([quiet, busy]))
        self.assertNotIn("real-time", said)
        self.assertIn("answer for a loaded machine", said)


class SpeedUps(unittest.TestCase):
    def test_one_run_reads_the_records_speedup(self):
        g = sr.Group("s", [20.0, 21.0, 19.0, 22.0, 20.0, 20.5, 19.5, 21.5])
        r = sr.timed_record(g, "hyb", "", [10.0] * 8)
        r["speedup"]["reference"] = {"ratio": 1.7, "low": 1.64, "high": 1.77}
        self.assertEqual(timing.speedup_over_reference([r]).text("%.2f", "x"), "1.70x (1.64-1.77)")

    def test_several_runs_pool_their_rounds(self):
        # Two groups whose reference is 2x and 3x the setting in every round: 16 ratios, 8 of each.
        g1, g2 = sr.Group("s", [20.0] * 8, view="camera"), sr.Group("s", [30.0] * 8, view="path", frame=0)
        runs = [sr.timed_record(g1, "hyb", "", [10.0] * 8), sr.timed_record(g2, "hyb", "", [10.0] * 8)]
        self.assertEqual(timing.speedup_over_reference(runs), (2.5, 2.0, 3.0))

    def test_speedup_cell(self):
        g = sr.Group("s", [1.0] * 8)
        ratios = [1.9, 1.95, 2.0, 2.0, 2.0, 2.0, 2.1, 2.2]
        mine = sr.timed_record(g, "hyb", "", [10.0] * 8)
        other = sr.timed_record(g, "rt_only", "x", [10.0 * q for q in ratios])
        self.assertEqual(timing.speedup_cell([mine], [other], "old"), "2.00x (1.90-2.20)")
        self.assertEqual(timing.speedup_cell([sr.old_record("s", "hyb", "", 10.0)], [sr.old_record("s", "rt_only", "", 20.0)], "2.00x"),
                         "2.00x")


if __name__ == "__main__":
    unittest.main()
