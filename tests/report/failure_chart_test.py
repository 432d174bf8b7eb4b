#!/usr/bin/python3
"""report/failures.py's "where methods fail" chart: a setting whose SSIM varies by 1e-6 along its
path gets no worst-frame mark, the panel says that no frame stands out, and its axis reads as plain
numbers (no offset notation such as "1e-6+9.999e-1"); a setting whose SSIM dips by 0.04 at one
frame gets its mark there. On made-up records (tests/support/synthetic_records.py).

    failure_chart_test.py        (standard library unittest; no hybridlab program needed)"""
import os
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "report"))
sys.path.insert(0, os.path.join(HERE, "..", "support"))
import failures  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import palette  # noqa: E402
import synthetic_records as sr  # noqa: E402

STEADY = [10.0, 10.2, 9.9, 10.1, 10.0, 10.3, 9.8, 10.1]


def path_of(technique, ssims):
    """A setting's frames along one path, frame f scored ssims[f], timed steadily."""
    return [sr.timed_record(sr.Group("s", [100.0] * 8, view="walk", frame=f), technique, "", STEADY, ssim=v)
            for f, v in enumerate(ssims)]


def red_marks(ax):
    """(frame, value) of the worst-frame marks drawn on `ax`."""
    return [tuple(p) for c in ax.collections if c.get_label() == failures.WORST_MARK for p in c.get_offsets()]


def chart(records):
    seqs = failures.sequences(records)
    fig = failures.failure_figure(seqs, "t", {}, palette.setting_colours(records))
    fig.canvas.draw()
    return fig


class WorstFrameMarks(unittest.TestCase):
    def test_a_millionth_of_ssim_is_no_worst_frame_and_no_offset(self):
        records = path_of("flat", [0.9999990, 0.9999999, 0.9999970, 0.9999995])
        fig = chart(records)
        ssim_ax = fig.axes[1]
        self.assertEqual(ssim_ax.get_ylabel(), "SSIM")
        self.assertEqual(red_marks(ssim_ax), [])
        self.assertEqual(ssim_ax.yaxis.get_offset_text().get_text(), "")
        labels = [t.get_text() for t in ssim_ax.get_yticklabels() if t.get_text()]
        self.assertTrue(labels)
        for text in labels:
            self.assertRegex(text, r"^[\d.]+$")  # plain decimals: no "e", no "+"
        lo, hi = ssim_ax.get_ylim()
        self.assertGreaterEqual(hi - lo, 1e-3)  # at least the tolerance wide: the millionths draw flat
        notes = [t.get_text() for t in ssim_ax.texts]
        self.assertIn("no frame worse than its median by more than 0.001", notes)
        plt.close(fig)

    def test_a_real_dip_is_marked_at_its_frame(self):
        records = path_of("dips", [0.99, 0.991, 0.95, 0.99])
        fig = chart(records)
        marks = red_marks(fig.axes[1])
        self.assertEqual(len(marks), 1)
        self.assertEqual(marks[0][0], 2)
        self.assertAlmostEqual(marks[0][1], 0.95)
        self.assertEqual([t.get_text() for t in fig.axes[1].texts], [])
        plt.close(fig)

    def test_the_frame_time_panel_says_when_no_spike_is_beyond_the_noise(self):
        fig = chart(path_of("flat", [0.99, 0.99, 0.99, 0.99]))
        self.assertEqual(red_marks(fig.axes[0]), [])
        self.assertIn("no frame time beyond the timing noise", [t.get_text() for t in fig.axes[0].texts])
        plt.close(fig)


if __name__ == "__main__":
    unittest.main()
