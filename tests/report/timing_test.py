#!/usr/bin/python3
"""report/timing.py: the median's distribution-free interval, paired comparisons over rounds and
the tie rule, on known numbers and on made-up records (tests/support/synthetic_records.py).

    timing_test.py        (standard library unittest; no hybridlab program needed)"""
import json
import math
import os
import random
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "report"))
sys.path.insert(0, os.path.join(HERE, "..", "support"))
import synthetic_records as sr  # noqa: E402
import timing  # noqa: E402

CASES = os.path.join(HERE, "..", "fixtures", "fastest_set_cases.json")


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
        # Nothing pairs: not decided, however far apart the medians (they were timed at different
        # moments, under whatever load each had).
        self.assertEqual(timing.compare(a, b), (timing.NOT_DECIDED, "paired rounds"))

    def test_rounds_pair_only_within_a_timing(self):
        # One group (the same name, as many rounds) timed by two processes: no pairs.
        reference = sr.drifting_rounds(200.0, 8, 1)
        first, second = sr.Group("s", reference), sr.Group("s", reference)
        self.assertEqual(first.name, second.name)
        a = [sr.timed_record(first, "hyb", "k=a", sr.drifting_rounds(10.0, 8, 1))]
        b = [sr.timed_record(second, "hyb", "k=b", sr.drifting_rounds(20.0, 8, 1))]
        self.assertEqual(timing.round_ratios(a, b), [])
        self.assertEqual(timing.compare(a, b), (timing.NOT_DECIDED, "paired rounds"))
        # A set written before timing ids pairs by group name and count, as it did.
        for r in a + b:
            del r["timing"]["timing_id"]
        self.assertEqual(len(timing.round_ratios(a, b)), 8)
        self.assertEqual(timing.compare(a, b), (timing.FASTER, "paired rounds"))

    def test_without_intervals_the_lower_median_is_faster(self):
        a = [sr.old_record("s", "hyb", "k=a", 10.0)]
        b = [sr.old_record("s", "hyb", "k=b", 10.1)]
        self.assertEqual(timing.compare(a, b), (timing.FASTER, "medians"))
        self.assertEqual(timing.compare(a, [sr.old_record("s", "hyb", "k=c", 10.0)]), (timing.TIED, "medians"))
        self.assertFalse(timing.has_intervals(a + b))
        self.assertEqual(timing.tolerance(a + b), timing.DEFAULT_TOLERANCE)

    def test_fastest_names_a_tie_whatever_the_order(self):
        reference = sr.drifting_rounds(200.0, 30, 3)
        g = sr.Group("s", reference)
        runs = {name: [sr.timed_record(g, "hyb", "k=" + name, sr.drifting_rounds(ms, 30, 3, noise=0.002))]
                for name, ms in (("a", 10.0), ("b", 10.05), ("c", 12.0))}
        for order in (["a", "b", "c"], ["c", "b", "a"], ["b", "c", "a"]):
            found = timing.fastest(order, runs.get, key=str)
            self.assertEqual(found.settings, ["a", "b"], order)
            self.assertEqual((found.best, found.decision, found.basis), ("a", timing.TIED, timing.PAIRED))

    def test_tolerance_is_the_sets_precision(self):
        g = sr.Group("s", [1.0] * 8)
        records = [sr.timed_record(g, "hyb", "", [1.0] * 8, precision=0.05), sr.timed_record(g, "hyb", "x", [1.0] * 8, precision=0.02)]
        self.assertEqual(timing.tolerance(records), 0.05)


class SharedTable(unittest.TestCase):
    """tests/fixtures/fastest_set_cases.json, which the runner's C++ answers too
    (tests/runner/test_fastest_set.cpp)."""

    def table(self):
        with open(CASES) as f:
            return json.load(f)

    def test_every_fastest_set_case(self):
        cases = self.table()["fastest_set"]
        self.assertGreaterEqual(len(cases), 10)
        for c in cases:
            with self.subTest(c["name"]):
                names = [s["name"] for s in c["settings"]]
                rounds = [s["timings"] for s in c["settings"]]
                members, best, decision, unpaired = timing.fastest_of_rounds(rounds, c["tolerance"])
                self.assertEqual({"members": [names[i] for i in members], "best": names[best], "decision": decision,
                                  "unpaired": unpaired}, c["expected"])
                by_name = dict(zip(names, rounds))
                for a, b, order in c["pairs"]:
                    self.assertEqual(timing.compare_rounds(by_name[a], by_name[b], c["tolerance"]), order, (a, b))

    def test_every_case_from_records(self):
        """The same cases as result records, one per setting and timing (a timing's group named by
        the case, so that the split group's two timings share a group name and a round count)."""
        for c in self.table()["fastest_set"]:
            with self.subTest(c["name"]):
                groups, runs = {}, {}
                for s in c["settings"]:
                    for key, ms in s["timings"].items():
                        g = groups.setdefault(key, sr.Group("scene", ms, view="camera", timing_id=key))
                        runs.setdefault(s["name"], []).append(sr.timed_record(g, "hyb", "k=" + s["name"], ms, precision=c["tolerance"]))
                found = timing.fastest(list(runs), runs.get, timing.tolerance([r for v in runs.values() for r in v]))
                self.assertEqual((found.settings, found.best, found.decision, found.unpaired),
                                 (c["expected"]["members"], c["expected"]["best"], c["expected"]["decision"],
                                  c["expected"]["unpaired"]))

    def test_interval_ranks_and_rounds(self):
        table = self.table()
        for r in table["interval_ranks"]:
            ranks = timing.interval_ranks(r["n"], r["confidence"])
            self.assertEqual(ranks[0] if ranks else 0, r["rank"], r)
        for r in table["rounds_for_decision"]:
            self.assertEqual(timing.rounds_for_decision(r["settings"]), r["rounds"], r)

    def test_log_space_ranks_agree_with_exact_integers(self):
        def exact(n, confidence):
            below, best = 0, 0
            for l in range(1, (n + 1) // 2 + 1):
                below += math.comb(n, l - 1)
                if 1 - 2 * below / 2 ** n < confidence:
                    break
                best = l
            return best
        for n in list(range(1, 200)) + [1074, 1075, 1076, 2000]:
            for confidence in (0.95, 0.975, 1 - 0.05 / 15):
                ranks = timing.interval_ranks(n, confidence)
                self.assertEqual(ranks[0] if ranks else 0, exact(n, confidence), (n, confidence))

    def test_2000_rounds_keep_their_interval(self):
        # 2^-2000 is 0 as a double: summed so, the interval collapsed to the median.
        iv = timing.median_interval([float(v) for v in range(2000, 0, -1)])
        self.assertEqual(iv, (1000.5, 956.0, 1045.0))


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

    def test_groups_timed_by_two_calls_are_named(self):
        reference = [1.0] * 8
        first, second, other = sr.Group("s", reference), sr.Group("s", reference), sr.Group("s", reference, view="path")
        records = [sr.timed_record(first, "hyb", "", [1.0] * 8), sr.timed_record(second, "hyb", "x", [1.0] * 8),
                   sr.timed_record(other, "hyb", "", [1.0] * 8), sr.timed_record(other, "hyb", "x", [1.0] * 8)]
        self.assertIn("1 of 2 groups were timed by more than one call of the runner", " ".join(timing.caveats(records)))
        self.assertNotIn("more than one call", " ".join(timing.caveats(records[2:])))

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
