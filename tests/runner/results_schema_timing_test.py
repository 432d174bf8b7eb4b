#!/usr/bin/python3
"""experiments/results.schema.json's timing fields: a record timed in rounds (frame_ms with its
interval, `timing`, `speedup`) validates, a record of a result set written before rounds still
does, and broken timing fields are refused. On made-up records (tests/support/synthetic_records.py)
through the report's validator (report/results.py, on python3-jsonschema).

    results_schema_timing_test.py        (standard library unittest; no hybridlab program needed)"""
import copy
import os
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "report"))
sys.path.insert(0, os.path.join(HERE, "..", "support"))
import results  # noqa: E402
import synthetic_records as sr  # noqa: E402


def timed():
    g = sr.Group("s", [20.0 + k for k in range(8)])
    sr.timed_record(g, "rt_only", "", [15.0 + k for k in range(8)])
    r = sr.timed_record(g, "hyb", "k=1", [10.0 + k for k in range(8)], cpu_rounds=[30.0 + k for k in range(8)])
    r["timing"]["device_ms"] = dict(r["frame_ms"])
    r["timing"]["device_ms_rounds"] = list(r["timing"]["frame_ms_rounds"])
    r["timing"]["gpu_clocks"] = {"changed": False, "graphics_mhz": 1980}
    return r


class TimingFields(unittest.TestCase):
    def test_a_record_timed_in_rounds_validates(self):
        r = timed()
        self.assertIn("ci_low", r["frame_ms"])
        self.assertIn("rt_only", r["speedup"])
        self.assertEqual(results.schema_problems(r), [])

    def test_a_record_timed_before_timing_ids_validates(self):
        r = timed()
        self.assertRegex(r["timing"]["timing_id"], "^[0-9a-f]{16}$")
        del r["timing"]["timing_id"]
        self.assertEqual(results.schema_problems(r), [])

    def test_a_record_of_fewer_than_6_rounds_validates_without_intervals(self):
        r = sr.timed_record(sr.Group("s", [20.0, 21.0, 22.0]), "hyb", "", [10.0, 10.5, 11.0])
        self.assertNotIn("ci_low", r["frame_ms"])
        self.assertEqual(r["speedup"]["reference"], {"ratio": 2.0})
        self.assertEqual(results.schema_problems(r), [])

    def test_an_old_record_validates(self):
        r = sr.old_record("s", "hyb", "", 10.0)
        self.assertNotIn("timing", r)
        self.assertEqual(results.schema_problems(r), [])

    def test_broken_timing_fields_are_refused(self):
        cases = [
            (lambda r: r["timing"].pop("group"), "$.timing: missing required 'group'"),
            (lambda r: r["timing"].update(frame_ms_rounds=["1"]), "$.timing.frame_ms_rounds[0]: expected number"),
            (lambda r: r["speedup"]["reference"].pop("ratio"), "$.speedup.reference: missing required 'ratio'"),
            (lambda r: r["frame_ms"].update(ci_low="x"), "$.frame_ms.ci_low: expected number"),
            (lambda r: r["timing"].update(steady="yes"), "$.timing.steady: expected boolean"),
            (lambda r: r["timing"].update(timing_id=""), "$.timing.timing_id: "),
            (lambda r: r["timing"].update(timing_id=7), "$.timing.timing_id: expected string"),
        ]
        for breaks, problem in cases:
            r = copy.deepcopy(timed())
            breaks(r)
            found = results.schema_problems(r)
            self.assertTrue(any(p.startswith(problem) for p in found), (problem, found))


if __name__ == "__main__":
    unittest.main()
