#!/usr/bin/python3
"""Every table script in paper_figures/, run as the README says (Debian's python3, RESULT_DIR) on its
small result set committed in tests/fixtures/result_sets (make_result_sets.py says how each number
was chosen), gives the cells worked out by hand: gbuffer_rays_table, sabino_table3,
walewski_tables, macedo_tables, ssr_speed_table, hakura_tables and pareto_table; and each names the
device under its tables and writes --out as it prints.

    table_scripts_test.py        (standard library unittest; no hybridlab program needed)"""
import json
import os
import shutil
import subprocess
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPTS = os.path.join(HERE, "..", "..", "paper_figures")
SETS = os.path.join(HERE, "..", "fixtures", "result_sets")


def run(script, result_set, *extra):
    out = subprocess.run(["/usr/bin/python3", os.path.join(SCRIPTS, script), os.path.join(SETS, result_set)] + list(extra),
                         capture_output=True, text=True)
    if out.returncode != 0:
        raise AssertionError("%s: exit %d\n%s" % (script, out.returncode, out.stderr))
    return out.stdout


def row(text, start):
    """The cells of the first table line starting with `start`."""
    line = next((l for l in text.splitlines() if l.startswith(start)), None)
    if line is None:
        raise AssertionError("no line starting with %r in\n%s" % (start, text))
    return [c.strip() for c in line.strip("|").split("|")]


class TableScripts(unittest.TestCase):
    def test_gbuffer_rays_table(self):
        out = run("gbuffer_rays_table.py", "gbuffer_rays")
        # scene, size, view, technique, setting, ms, speed-up, SSIM, FLIP, rays/pixel, rasterizer, gbuffer.rays, lighting.cpu, ssr, trace
        self.assertEqual(row(out, "| s | 64x36 | camera | rt_only |"),
                         ["s", "64x36", "camera", "rt_only", "defaults", "20.0", "1.00", "0.9900", "0.0100", "2.00", "", "", "", "", "18"])
        self.assertEqual(row(out, "| s | 64x36 | camera | heuristic_rt | gbuffer=raster |")[5:],
                         ["10.0", "2.00", "0.9700", "0.0300", "1.50", "4", "-", "-", "-", "5"])
        self.assertEqual(row(out, "| s | 64x36 | camera | heuristic_rt | gbuffer=rays |")[5:],
                         ["8.0", "2.50", "0.9600", "0.0400", "3.00", "1", "2", "-", "-", "4"])
        self.assertIn("\nMeasured on: llvmpipe [cpu; Mesa 25; Vulkan 1.4], Test CPU x 2 cores", out)

    def test_sabino_table3(self):
        out = run("sabino_table3.py", "sabino")
        self.assertEqual(row(out, "| a |"), ["a", "100", "50", "4.0", "30.0", "12.0", "2.50", "0.9800 / 0.9950"])
        self.assertEqual(row(out, "| b |"), ["b", "100", "50", "8.0", "60.0", "24.0", "2.50", "0.9800 / 0.9950"])

    def test_walewski_tables(self):
        out = run("walewski_tables.py", "walewski")
        self.assertEqual(row(out, "| FRAME heuristic_rt |"), ["FRAME heuristic_rt", "10.000"])
        for stage, ms in (("RAST", "2.000"), ("HEUR", "1.000"), ("RAYT", "6.000"), ("BLEND", "1.000")):
            self.assertEqual(row(out, "| &nbsp;&nbsp;%s |" % stage)[1], ms)
        self.assertEqual(row(out, "| &nbsp;&nbsp;objects selected / visible |")[1], "2 / 5")
        self.assertEqual(row(out, "| &nbsp;&nbsp;speed-up over rt_only |")[1], "2.50x")
        self.assertEqual(row(out, "| &nbsp;&nbsp;speed-up over whitted |")[1], "4.00x")
        self.assertEqual(row(out, "| WHITTED FRAME |")[1], "40.000")
        # Table 6: the means over the path's two frames (11 and 13 ms; 41 and 43).
        self.assertEqual(row(out, "| with heuristic [] |")[1], "12.0 (SSIM 0.9700, 2 frames)")
        self.assertEqual(row(out, "| whitted |")[1], "42.0 (SSIM 1.0000, 2 frames)")

    def test_walewski_tables_of_one_device_backend_with_raster(self):
        # The GPU campaign's set: every ray on the device, and raster, which has no backend.
        with open(os.path.join(SETS, "walewski", "results.json")) as f:
            records = json.load(f)
        for r in records:
            r["parameters_text"] = ("rays=vulkan " + r["parameters_text"]).strip()
        raster = dict(records[-1], technique="raster", label="raster", parameters_text="", id=records[-1]["id"] + "-raster")
        with tempfile.TemporaryDirectory() as d:
            shutil.copy(os.path.join(SETS, "walewski", "experiment.json"), d)
            with open(os.path.join(d, "results.json"), "w") as f:
                json.dump(records + [raster], f)
            out = subprocess.run(["/usr/bin/python3", os.path.join(SCRIPTS, "walewski_tables.py"), d], capture_output=True, text=True)
        self.assertEqual(out.returncode, 0, out.stderr)
        self.assertIn("### rays = vulkan", out.stdout)
        self.assertNotIn("### rays = embree", out.stdout)
        self.assertEqual(row(out.stdout, "| WHITTED FRAME |")[1], "40.000")

    def test_macedo_tables(self):
        out = run("macedo_tables.py", "macedo")
        self.assertEqual(row(out, "| heuristic_rt | 5 |"),
                         ["heuristic_rt", "5", "10.0", "5.0", "12.0 +/- 2.0", "10.0, 14.0", "-", "1.00 +/- 0.00", "0.9700 +/- 0.0100 (0.9600)",
                          "0.0300 +/- 0.0100 (0.0400)"])  # no CPU time: records without the runner's rounds
        self.assertEqual(row(out, "| heuristic_rt | 10 |")[2:4], ["20.0", "10.0"])
        self.assertIn("`bvh_update` of heuristic_rt: 0.2 ms per 1000 dynamic triangles (+ 0 ms), correlation 1.000, largest N / smallest 2.00x "
                      "over N = 5, 10", out)
        self.assertNotIn("Table II", out)  # no teapots-deforming-N runs

    def test_ssr_speed_table(self):
        out = run("ssr_speed_table.py", "ssr_speed")
        self.assertEqual(row(out, "| s | 64x36 | defaults |"),
                         ["s", "64x36", "defaults", "30.0", "12.0", "2.50", "0.9700", "0.750", "40", "2.0", "1.0", "8.0", "0.0", "1.0"])
        self.assertEqual(row(out, "| s | 64x36 | fallback=none |"),
                         ["s", "64x36", "fallback=none", "30.0", "2.0", "1.0", "3.0", "0.10", "5.00", "15.00"])

    def test_hakura_tables(self):
        out = run("hakura_tables.py", "hakura")
        self.assertEqual(row(out, "| **total** |")[1:], ["50.0", "2.0", "2.5"])
        self.assertEqual(row(out, "| **time reduction** (paper 25-45x) |")[1:], ["-", "25.0", "20.0"])
        self.assertEqual(row(out, "| **ray reduction** (paper 6-10.8x) |")[1:], ["-", "10.0", "12.5"])
        self.assertEqual(row(out, "| SSIM (lens pixels) |")[1:], ["-", "0.9500", "0.9300"])
        self.assertEqual(row(out, "| approach@0 |")[1:], ["0.1000 / 0.9000", "0.3000 / 0.7000"])
        self.assertEqual(row(out, "| mean FLIP |")[1:], ["0.1000", "0.3000"])
        self.assertNotIn("Figure 8", out)  # no single-layer runs

    def test_pareto_table(self):
        out = run("pareto_table.py", "pareto")
        self.assertEqual(row(out, "| ssr [max_steps=64] | 0.50 |"),
                         ["ssr [max_steps=64]", "0.50", "", "0.9700", "-", "1.00", "-", "yes", "yes"])
        self.assertEqual(row(out, "| ssr [max_steps=512] | 0.80 |")[-2:], ["", ""])
        self.assertEqual(row(out, "| ssr [max_steps=512] | 1 |"), ["ssr [max_steps=512]", "1", "0", "0", "0.80", "0.9600"])

    def test_out_file_holds_what_is_printed(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "t.md")
            printed = run("sabino_table3.py", "sabino", "--out", path)
            with open(path) as f:
                self.assertEqual(f.read(), printed)

    def test_a_folder_without_runs_is_named(self):
        with tempfile.TemporaryDirectory() as d:
            out = subprocess.run(["/usr/bin/python3", os.path.join(SCRIPTS, "gbuffer_rays_table.py"), d], capture_output=True, text=True)
        self.assertEqual(out.returncode, 1)
        self.assertEqual(out.stderr, "gbuffer_rays_table: %s: not a result set (no results.json, no runs/)\n" % d)


if __name__ == "__main__":
    unittest.main()
