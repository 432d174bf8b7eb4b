#!/usr/bin/python3
"""report/verdict.py with timed rounds: a threshold row names settings tied in time together, the
same whatever the records' order; speed-ups carry their intervals; the Pareto table marks ties and
shows the median's interval; a result set written before rounds still gets its verdict, saying it
has no intervals. On made-up records (tests/support/synthetic_records.py).

    verdict_test.py        (standard library unittest; no hybridlab program needed)"""
import os
import random
import re
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "report"))
sys.path.insert(0, os.path.join(HERE, "..", "support"))
import results as rs  # noqa: E402
import synthetic_records as sr  # noqa: E402
import timing  # noqa: E402
import verdict  # noqa: E402

# The records have no images: each run's own id stands for its pixels' digest (no two identical).
pixels_digest = verdict.image_digest
verdict.image_digest = lambda result_dir, r: r["id"]

DEPTH = "whitted-depth [max_depth=2]"
CUTOFF = "whitted-cutoff [importance_cutoff=0.2]"
INTERVAL = re.compile(r"^\d+\.\d\dx \(\d+\.\d\d-\d+\.\d\d\)$")


def timed_set(seed=5):
    """One scene at one size, two views timed in 8 rounds each: two settings 1% apart reaching SSIM
    0.99 (a tie), one 30% faster reaching only 0.95, one 25% slower reaching 0.99, and rt_only."""
    reference = sr.drifting_rounds(100.0, 8, seed)
    records = []
    for view, frame in (("camera", -1), ("path", 0)):
        g = sr.Group("scene", reference, view=view, frame=frame)
        records.append(sr.timed_record(g, "rt_only", "", sr.drifting_rounds(60.0, 8, seed), ssim=0.999))
        records.append(sr.timed_record(g, "whitted", "max_depth=2", sr.drifting_rounds(40.0, 8, seed), ssim=0.992, label="whitted-depth"))
        records.append(sr.timed_record(g, "whitted", "importance_cutoff=0.2", sr.drifting_rounds(40.4, 8, seed), ssim=0.993,
                                       label="whitted-cutoff"))
        records.append(sr.timed_record(g, "raster", "", sr.drifting_rounds(28.0, 8, seed), ssim=0.95))
        records.append(sr.timed_record(g, "hyb", "k=slow", sr.drifting_rounds(50.0, 8, seed), ssim=0.995))
    return records


def verdict_of(records):
    (v,) = verdict.verdicts(records, "unused")
    return v


def row(v, threshold, region="whole image"):
    """The threshold table's row that answers SSIM >= threshold on the region (rows whose answer is
    the same settings are one row)."""
    header, rows = verdict.threshold_table(v)
    (found,) = [cells for (covers, _), cells in zip(v.threshold_rows(), rows) if (region, threshold) in covers]
    return dict(zip(header, found))


def plain(cell):
    return cell.text() if isinstance(cell, verdict.Tie) else cell.name if isinstance(cell, verdict.Setting) else cell


class TiedRows(unittest.TestCase):
    def test_a_tie_is_named_together_whatever_the_record_order(self):
        records = timed_set()
        texts = set()
        for seed in range(6):
            shuffled = list(records)
            random.Random(seed).shuffle(shuffled)
            v = verdict_of(shuffled)
            cells = row(v, 0.99)
            texts.add((plain(cells["fastest setting"]), v.sentence().split(". The fastest")[0].split(" (")[0]))
            self.assertEqual([s.name for s in cells["fastest setting"].settings], [CUTOFF, DEPTH])
        self.assertEqual(len(texts), 1, texts)
        name, _ = texts.pop()
        self.assertEqual(name, "%s and %s, tied within 3%%" % (CUTOFF, DEPTH))

    def test_the_row_gives_each_tied_settings_time_and_speedups(self):
        cells = row(verdict_of(timed_set()), 0.99)
        self.assertEqual(len(cells["frame ms"].split(" / ")), 2)
        for column in ("x ref.", "x rt_only"):
            parts = cells[column].split(" / ")
            self.assertEqual(len(parts), 2)
            for p in parts:
                self.assertRegex(p, INTERVAL)

    def test_a_clear_winner_stands_alone(self):
        v = verdict_of(timed_set())
        self.assertEqual(plain(row(v, 0.95)["fastest setting"]), "raster")
        self.assertIn("The fastest setting of all is raster at ", v.sentence())

    def test_the_sentence_names_the_tie(self):
        s = verdict_of(timed_set()).sentence()
        self.assertIn("the fastest settings reaching SSIM 0.99 on the whole image are %s and %s, tied within 3%% (" % (
            CUTOFF, DEPTH), s)
        self.assertRegex(s, r"%s: \d+\.\d ms, \d+\.\d\dx \(\d+\.\d\d-\d+\.\d\d\) the reference's speed" % re.escape(DEPTH))

    def test_markdown_links_each_tied_setting(self):
        v = verdict_of(timed_set())
        lines = verdict.markdown_table(verdict.threshold_table(v), verdict.setting_link(lambda i: "viewer.html#run=" + i, True))
        (line,) = [l for l in lines if l.startswith("| SSIM >= 0.99 and >= 0.97, whole image |")]
        self.assertRegex(line, r"\| \[%s\]\(viewer\.html#run=\S+\) and \[%s\]\(viewer\.html#run=\S+\), tied within 3%% \|"
                         % (re.escape(CUTOFF), re.escape(DEPTH)))


class SpeedUpsAndPareto(unittest.TestCase):
    def test_speedups_over_the_reference_pool_the_rounds(self):
        v = verdict_of(timed_set())
        depth = v.settings[DEPTH]
        ref, rt = v.speedups(depth)
        self.assertEqual(ref, timing.median_interval(timing.reference_ratios(depth.records)))
        self.assertAlmostEqual(ref.median, 100.0 / 40.0, delta=0.05)
        self.assertAlmostEqual(rt.median, 60.0 / 40.0, delta=0.05)
        self.assertLess(ref.low, ref.median)

    def test_pareto_table_shows_the_interval_and_the_tie(self):
        v = verdict_of(timed_set())
        header, rows = verdict.pareto_table(v)
        self.assertEqual(header[:6], ["setting", "frame ms (median)", "95% interval ms", "tied in time with", "x ref.", "x rt_only"])
        by_name = {cells[0].name: dict(zip(header, cells)) for cells in rows}
        self.assertEqual(list(by_name), ["raster", DEPTH, CUTOFF, "hyb [k=slow]", "rt_only"])
        tied = {name: plain(cells["tied in time with"]) for name, cells in by_name.items()}
        # The cut-off is the slower of the tied two by its median; it names the faster.
        self.assertEqual(tied, {"raster": "", DEPTH: "", CUTOFF: DEPTH, "hyb [k=slow]": "", "rt_only": ""})
        depth = v.settings[DEPTH]
        self.assertEqual(by_name[DEPTH]["95% interval ms"], "%.2f-%.2f" % (depth.time.low, depth.time.high))
        self.assertLess(depth.time.low, depth.ms)
        self.assertRegex(by_name[DEPTH]["x ref."], INTERVAL)

    def test_the_intro_says_which_test_decides_ties(self):
        html, md = verdict.write([verdict_of(timed_set())], lambda i: "viewer.html#run=" + i)
        intro = md[3]
        self.assertIn("ratio of their times in the same round of the same timing", intro)
        self.assertIn("95% interval lies wholly below 0.97 (the set's precision, 3%) and A's median time too", intro)
        self.assertIn("tied when both lie inside 0.97-1.03; otherwise not decided", intro)
        self.assertIn("each comparison at 1 - 0.05 / (k - 1)", intro)


class TooFewRoundsOrSplitGroups(unittest.TestCase):
    """Rows the rounds cannot decide say so, and name no setting faster."""

    def records(self, views):
        """repeats = 3: rt_only and whitted-depth 20% apart in every round."""
        reference = [100.0, 104.0, 98.0]
        records = []
        for view in views:
            g = sr.Group("scene", reference, view=view)
            records.append(sr.timed_record(g, "rt_only", "", [60.0, 62.4, 58.8], ssim=0.999))
            records.append(sr.timed_record(g, "whitted", "max_depth=2", [48.0, 49.9, 47.0], ssim=0.992, label="whitted-depth"))
        return records

    def test_three_rounds_name_no_setting_faster(self):
        v = verdict_of(self.records(["camera"]))
        cells = row(v, 0.99)
        self.assertEqual(plain(cells["fastest setting"]),
                         "rt_only and %s, not decided: the rounds cannot tell them apart" % DEPTH)
        self.assertEqual(cells["in words"], "not decided against the reference (too few rounds or too wide an interval)")
        self.assertIn("no setting reaching SSIM 0.99 on the whole image is decided faster than the reference", v.sentence())
        self.assertFalse(v.beats_rt_only(v.settings[DEPTH]))
        # Two views of 3 rounds pool 6 pairs: enough for two settings (not for three: 7).
        v = verdict_of(self.records(["camera", "path"]))
        self.assertEqual(plain(row(v, 0.99)["fastest setting"]), DEPTH)
        self.assertTrue(v.beats_rt_only(v.settings[DEPTH]))

    def test_a_group_split_over_two_processes_pairs_what_it_can(self):
        # raster and rt_only timed by one call, whitted-depth by another (--max-runs, then --resume):
        # same group, as many rounds, no pairs.
        reference = sr.drifting_rounds(100.0, 10, 2)
        first, second = sr.Group("scene", reference), sr.Group("scene", reference)
        records = [sr.timed_record(first, "rt_only", "", sr.drifting_rounds(60.0, 10, 2, noise=0.002), ssim=0.999),
                   sr.timed_record(first, "raster", "", sr.drifting_rounds(30.0, 10, 2, noise=0.002), ssim=0.999),
                   sr.timed_record(second, "whitted", "max_depth=2", sr.drifting_rounds(50.0, 10, 7, noise=0.002), ssim=0.999,
                                   label="whitted-depth")]
        cells = row(verdict_of(records), 0.99)
        self.assertEqual(plain(cells["fastest setting"]), "raster and %s, not decided: the rounds cannot tell them apart (1 timed "
                         "in other processes, not paired)" % DEPTH)


class OldResultSets(unittest.TestCase):
    """Records without intervals, rounds or speed-ups: the verdict as before, saying so."""

    def records(self):
        return [sr.old_record("scene", "rt_only", "", 60.0, ssim=0.999),
                sr.old_record("scene", "whitted", "max_depth=2", 40.0, ssim=0.992, label="whitted-depth"),
                sr.old_record("scene", "whitted", "importance_cutoff=0.2", 40.4, ssim=0.993, label="whitted-cutoff"),
                sr.old_record("scene", "raster", "", 28.0, ssim=0.95)]

    def test_the_verdict_is_todays(self):
        v = verdict_of(self.records())
        cells = row(v, 0.99)
        self.assertEqual(plain(cells["fastest setting"]), DEPTH)  # the lower median, however close
        self.assertEqual(cells["frame ms"], "40.00")
        self.assertEqual(cells["x ref."], "2.50")
        self.assertEqual(cells["x rt_only"], "1.50")
        self.assertIn("is %s at 40.0 ms (2.50x the reference's speed, 1.50x rt_only's)" % DEPTH, v.sentence())
        header, rows = verdict.pareto_table(v)
        self.assertIn("best-worst ms", header)
        self.assertEqual(rows[0][2], "28.00-28.00")

    def test_the_report_says_the_set_has_no_intervals(self):
        _, md = verdict.write([verdict_of(self.records())], lambda i: "viewer.html#run=" + i)
        self.assertIn("This result set has no intervals", md[3])


class ImagesDropped(unittest.TestCase):
    """A result set whose images were dropped (the GPU campaign drops its larger sets' to fit a
    transfer) still gets its verdict, the same as with images none of which is byte-identical to
    another's: missing images are not compared (two missing ones are not "identical")."""

    def test_the_verdict_without_images_is_the_verdict_with_distinct_ones(self):
        records = timed_set()
        with_images = verdict_of(records)
        verdict.image_digest = pixels_digest
        try:
            self.assertIsNone(verdict.image_digest("/nonexistent", records[0]))
            without = verdict_of(records)
        finally:
            verdict.image_digest = lambda result_dir, r: r["id"]
        self.assertEqual([s.name for s in without.settings.values() if s.not_applicable], [])
        def rows(v):
            return [[plain(cell) for cell in cells] for cells in verdict.threshold_table(v)[1]]
        self.assertEqual(rows(without), rows(with_images))


class NothingBeatsTheReference(unittest.TestCase):
    """A small committed result set (tests/fixtures/report/nothing_beats_reference, timed rounds) in
    which the reference (13.6 ms) is faster than every setting that reaches any threshold: rt_only
    (15.9 ms, SSIM 0.9995) is the fastest reaching each, heuristic_rt reaches 0.99 at 35.6 ms."""

    def verdict(self):
        return verdict_of(rs.load(os.path.join(HERE, "..", "fixtures", "report", "nothing_beats_reference")))

    def test_the_sentence_says_nothing_beats_the_reference(self):
        s = self.verdict().sentence()
        self.assertIn("On whitted-classic at 64x36, nothing reaching SSIM 0.99 on the whole image beats the reference (13.6 ms): "
                      "the fastest, rt_only at 15.9 ms (0.85x (0.85-0.86) the reference's speed)", s)
        self.assertNotIn("rt_only's", s)

    def test_rows_naming_the_same_setting_are_one_row_saying_so(self):
        header, rows = verdict.threshold_table(self.verdict())
        self.assertEqual(len(rows), 1)
        cells = dict(zip(header, rows[0]))
        self.assertEqual(cells["quality reached"], "SSIM >= 0.99, >= 0.97 and >= 0.95, whole image")
        self.assertEqual(plain(cells["fastest setting"]), "rt_only")
        self.assertEqual(cells["in words"], "nothing reaching it beats the reference")

    def test_a_hybrid_that_beats_the_reference_but_not_rt_only_says_so(self):
        reference = sr.drifting_rounds(100.0, 8, 3)
        records = []
        for view in ("a", "b"):
            g = sr.Group("scene", reference, view=view)
            records.append(sr.timed_record(g, "rt_only", "", sr.drifting_rounds(60.0, 8, 3), ssim=0.999))
            records.append(sr.timed_record(g, "hyb", "k=slow", sr.drifting_rounds(80.0, 8, 3), ssim=0.995))
        v = verdict_of(records)
        hyb = v.settings["hyb [k=slow]"]
        self.assertTrue(v.beats_reference(hyb))
        self.assertFalse(v.beats_rt_only(hyb))
        self.assertEqual(v.beaten([hyb]), "beats the reference; nothing reaching it beats rt_only")


if __name__ == "__main__":
    unittest.main()
