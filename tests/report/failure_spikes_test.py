#!/usr/bin/python3
"""report/failures.py's frame-time spike "beyond noise" along a path: with intervals, the slowest
frame's interval must lie wholly above the path's median (above the median of the frames' upper
ends); without them, the slowest frame must exceed the median by more than its own repeats' spread.
On made-up records (tests/support/synthetic_records.py).

    failure_spikes_test.py        (standard library unittest; no hybridlab program needed)"""
import os
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "report"))
sys.path.insert(0, os.path.join(HERE, "..", "support"))
import failures  # noqa: E402
import synthetic_records as sr  # noqa: E402


def path_of(frame_rounds):
    """A setting's frames along one path, frame f timed in the rounds frame_rounds[f]."""
    return [sr.timed_record(sr.Group("s", [100.0] * len(rounds), view="walk", frame=f), "hyb", "", rounds)
            for f, rounds in enumerate(frame_rounds)]


STEADY = [10.0, 10.2, 9.9, 10.1, 10.0, 10.3, 9.8, 10.1]


class SpikeBeyondNoise(unittest.TestCase):
    def test_a_slow_frame_whose_interval_clears_the_median(self):
        rows = path_of([STEADY, STEADY, [x * 1.5 for x in STEADY], STEADY])
        self.assertTrue(failures.sequence_summary(rows)["spike_beyond_noise"])

    def test_a_slow_frame_within_the_noise(self):
        # Frame 2's median is the slowest, but its rounds reach down to the others': noise.
        noisy = [10.0, 8.0, 16.0, 9.5, 15.0, 10.6, 12.0, 11.0]
        rows = path_of([STEADY, STEADY, noisy, STEADY])
        s = failures.sequence_summary(rows)
        self.assertGreater(s["spike"], 1.02)
        self.assertFalse(s["spike_beyond_noise"])

    def test_without_intervals_the_repeats_spread_decides(self):
        rows = [sr.old_record("s", "hyb", "", ms, view="walk", frame=f) for f, ms in enumerate((10.0, 10.0, 13.0, 10.0))]
        # old_record's spread: -2% .. +5% of the median, 0.91 ms at 13 ms, under the 3 ms spike.
        self.assertTrue(failures.sequence_summary(rows)["spike_beyond_noise"])
        rows[2]["frame_ms"].update(min=9.0, max=14.0)
        self.assertFalse(failures.sequence_summary(rows)["spike_beyond_noise"])


if __name__ == "__main__":
    unittest.main()
