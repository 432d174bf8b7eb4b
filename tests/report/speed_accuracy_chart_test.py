#!/usr/bin/python3
"""report/report.py's speed-accuracy chart: each setting's bar spans its median's 95% interval
(pooled over its runs) where the records hold intervals, and its best to worst run where they do
not, the axis saying which clock and which bar; a second chart on CPU time where the records hold
timing.cpu_ms. On made-up records (tests/support/synthetic_records.py).

    speed_accuracy_chart_test.py        (standard library unittest; no hybridlab program needed)"""
import os
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "report"))
sys.path.insert(0, os.path.join(HERE, "..", "support"))
import figure_files  # noqa: E402,F401  (selects matplotlib's file backend first)
import matplotlib.collections  # noqa: E402
import report  # noqa: E402
import synthetic_records as sr  # noqa: E402
import timing  # noqa: E402
import verdict  # noqa: E402

verdict.image_digest = lambda result_dir, r: r["id"]  # no images: no two runs identical


def timed_set(with_cpu):
    records = []
    for view, frame in (("camera", -1), ("path", 0)):
        g = sr.Group("scene", sr.drifting_rounds(100.0, 8, 2), view=view, frame=frame)
        for name, ms, ssim in (("a", 20.0, 0.95), ("b", 40.0, 0.99)):
            rounds = sr.drifting_rounds(ms * (1.0 if frame < 0 else 1.3), 8, 2, noise=0.05)
            records.append(sr.timed_record(g, "hyb", "k=" + name, rounds, ssim=ssim,
                                           cpu_rounds=[2.0 * x for x in rounds] if with_cpu else None))
    return records


def bar_extents(ax):
    """The x extents of the error bars drawn on `ax`, left to right."""
    spans = []
    for c in ax.collections:
        if isinstance(c, matplotlib.collections.LineCollection):
            spans += [(min(seg[:, 0]), max(seg[:, 0])) for seg in c.get_segments()]
    return sorted(spans)


class SpeedAccuracyChart(unittest.TestCase):
    def test_bars_span_the_pooled_interval(self):
        (v,) = verdict.verdicts(timed_set(False), "unused")
        fig = report.speed_accuracy_figure(v, "t")
        ax = fig.axes[0]
        self.assertIn("wall time per frame", ax.get_xlabel())
        self.assertIn("bar: 95% interval of the median", ax.get_xlabel())
        expected = []
        for s in sorted(v.applicable(), key=lambda s: s.ms):
            lows = [r["frame_ms"]["ci_low"] for r in s.records]
            highs = [r["frame_ms"]["ci_high"] for r in s.records]
            expected.append((sum(lows) / 2, sum(highs) / 2))  # two runs: the median of each end is their mean
        for (lo, hi), (elo, ehi) in zip(bar_extents(ax), expected):
            self.assertAlmostEqual(lo, elo)
            self.assertAlmostEqual(hi, ehi)

    def test_old_sets_draw_best_to_worst(self):
        records = [sr.old_record("scene", "hyb", "k=a", ms, view="path", frame=f, ssim=0.95) for f, ms in ((0, 10.0), (1, 14.0))]
        (v,) = verdict.verdicts(records, "unused")
        ax = report.speed_accuracy_figure(v, "t").axes[0]
        self.assertIn("bar: best to worst run", ax.get_xlabel())
        self.assertEqual(bar_extents(ax), [(10.0, 14.0)])

    def test_a_cpu_time_chart_where_the_records_hold_it(self):
        for with_cpu, charts in ((False, 1), (True, 2)):
            (v,) = verdict.verdicts(timed_set(with_cpu), "unused")
            with tempfile.TemporaryDirectory() as out:
                os.makedirs(os.path.join(out, "figures"))
                paths = report.speed_accuracy(v, out, "k", "t")
                self.assertEqual(len(paths), charts)
                if with_cpu:
                    self.assertTrue(paths[1].endswith("speed-accuracy-cpu-k.svg"), paths)
        ax = report.speed_accuracy_figure(v, "t", timing.CLOCKS[1]).axes[0]
        self.assertIn("CPU time", ax.get_xlabel())
        # CPU time is twice the wall time in every round here: so are the bars.
        wall = bar_extents(report.speed_accuracy_figure(v, "t").axes[0])
        for (lo, hi), (wlo, whi) in zip(bar_extents(ax), wall):
            self.assertAlmostEqual(lo, 2.0 * wlo)
            self.assertAlmostEqual(hi, 2.0 * whi)

    def test_the_report_names_its_clock(self):
        with_cpu = timing.clock_note(timed_set(True))
        self.assertIn("wall time per frame (the records' frame_ms", with_cpu)
        self.assertIn("CPU time", with_cpu)
        self.assertNotIn("CPU time", timing.clock_note(timed_set(False)))


if __name__ == "__main__":
    unittest.main()
