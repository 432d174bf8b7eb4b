#!/usr/bin/python3
"""The report's modules that read a result set, on the small sets committed in
tests/fixtures/result_sets (made by its make_result_sets.py): results.py (records from results.json
or runs/, their accessors, the schema check on python3-jsonschema, the table lines and the device
line), images.py (the images through OpenImageIO), verdict.py (digests that find identical images,
the sentence, its command line), device.py, palette.py and figure_files.py; the checks that refuse
a malformed result set, and staged_folder.py.

    result_set_test.py        (standard library unittest; no hybridlab program needed)"""
import contextlib
import copy
import io
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPORT = os.path.join(HERE, "..", "..", "report")
SETS = os.path.join(HERE, "..", "fixtures", "result_sets")
sys.path.insert(0, REPORT)
import figure_files  # noqa: E402  (first: it selects matplotlib's file backend)
import device  # noqa: E402
import images  # noqa: E402
import numpy as np  # noqa: E402
import palette  # noqa: E402
import results  # noqa: E402
import staged_folder  # noqa: E402
import verdict  # noqa: E402

VERDICT_SET = os.path.join(SETS, "verdict")


def read_text(path):
    with open(path) as f:
        return f.read()


def write_text(path, text):
    with open(path, "w") as f:
        f.write(text)


class Results(unittest.TestCase):
    def test_loads_results_json_and_falls_back_to_the_runs(self):
        records = results.load(VERDICT_SET)
        self.assertEqual([r["technique"] for r in records], ["rt_only", "heuristic_rt", "raster", "layered_em"])
        with tempfile.TemporaryDirectory() as d:
            shutil.copytree(os.path.join(VERDICT_SET, "runs"), os.path.join(d, "runs"))
            write_text(os.path.join(d, "runs", ".tmp-1-0000.json"), "{")  # an interrupted write: not a record
            from_runs = results.sourced_records(d)
            self.assertTrue(results.is_result_set(d))
        self.assertEqual([r for _, r in from_runs], records)
        self.assertEqual(from_runs[2][0], os.path.join(d, "runs", "0002-raster.json"))
        self.assertEqual(results.sourced_records(VERDICT_SET)[1][0], os.path.join(VERDICT_SET, "results.json") + ": record 1")
        self.assertFalse(results.is_result_set(HERE))

    def test_accessors(self):
        (rt, hybrid, raster, _) = results.load(VERDICT_SET)
        self.assertEqual(results.variant(hybrid), "heuristic_rt [budget=0]")
        self.assertEqual(results.variant(rt), "rt_only")
        self.assertEqual(results.backend(dict(hybrid, parameters_text="budget=0 rays=vulkan")), "vulkan")
        self.assertEqual(results.backend(hybrid), "embree")
        self.assertEqual(results.without_backend(dict(hybrid, parameters_text="rays=vulkan budget=0"))["parameters_text"], "budget=0")
        self.assertEqual(sorted(["b=20000", "b=5000", "b=100"], key=results.natural_key), ["b=100", "b=5000", "b=20000"])
        self.assertEqual(results.view_name(rt), "camera")
        self.assertEqual(results.view_name(dict(rt, view="orbit", frame=12)), "orbit@12")
        self.assertEqual(results.resolution(rt), "64x36")
        self.assertEqual(results.metric(raster, "whole", "ssim"), 0.9)
        self.assertEqual(results.metric(raster, "whole", "flip"), 0.09999999999999998)
        self.assertIsNone(results.metric(raster, "masked", "ssim"))
        self.assertEqual(results.fmt(None), "-")
        self.assertEqual(results.fmt(0.5, "%.2f"), "0.50")
        self.assertEqual(results.mean_known([1.0, None, 3.0]), 2.0)
        self.assertIsNone(results.mean_known([None]))

    def test_stages_under_one_vocabulary(self):
        # A record of version 1 (no schema_version) with old stage and counter names, migrated.
        r = results.migrate({"stages": {"rast": {"median": 2.0}, "lighting": {"median": 1.0}, "ray_trace": {"median": 5.0},
                                        "trace.lens_vertices": {"median": 0.5}},
                             "counters": {"vk_gbuffer_upload_input_primitives": 3.0, "rays_total": 7.0}})
        self.assertEqual(r["schema_version"], results.SCHEMA_VERSION)
        self.assertEqual(r["counters"], {"vk_gbuffer.upload_input_primitives": 3.0, "rays_total": 7.0})
        self.assertEqual(results.stages(r), {"raster": 2.0, "lighting": 1.0, "trace": 5.0, "trace.lens_vertices": 0.5})
        self.assertEqual(results.stage_kinds(r), {"raster": 2.0, "lighting": 1.0, "trace": 5.5})
        self.assertEqual(results.stage(r, "trace"), 5.0)
        # Two old names of one stage add up; a current record is left as it is.
        self.assertEqual(results.migrate({"stages": {"rayt": {"median": 1.0, "min": 1.0}, "ray_trace": {"median": 2.0, "min": 1.5}}})["stages"],
                         {"trace": {"median": 3.0, "min": 2.5}})
        current = {"schema_version": results.SCHEMA_VERSION, "stages": {"rast": {"median": 1.0}}}
        self.assertEqual(results.migrate(dict(current)), current)
        self.assertEqual(results.raster_ms(r), 3.0)
        self.assertIsNone(results.raster_ms({"stages": {"trace": {"median": 1.0}}}))
        self.assertEqual(results.kind_order(["trace", "raster", "zzz"])[-1], "zzz")

    def test_pareto_front(self):
        points = [(1.0, 0.9, "a"), (2.0, 0.95, "b"), (3.0, 0.93, "c")]
        self.assertEqual([p[2] for p in results.pareto_front(points, True)], ["a", "b"])

    def test_device_line_and_scale(self):
        line = results.device_line(VERDICT_SET, results.load(VERDICT_SET))
        self.assertEqual(line, "Measured on: llvmpipe [cpu; Mesa 25; Vulkan 1.4], Test CPU x 2 cores, Embree 3.13.5, TBB 2 threads, "
                               "LP_NUM_THREADS 2, Debian 12, hybridlab 0.1.0 (git test)")
        self.assertEqual(results.resolution_scale(VERDICT_SET), 1.0)
        with tempfile.TemporaryDirectory() as d:
            write_text(os.path.join(d, "experiment.json"), json.dumps({"resolution_scale": 0.25}))
            self.assertEqual(results.resolution_scale(d), 0.25)
            self.assertEqual(results.devices(d), [None])
            self.assertIn("rendered at 0.25 of the configured size", results.device_line(d))
            mixed = [dict(r, device=dict(device_record(), vulkan_device=name)) for r, name in zip(results.load(VERDICT_SET), "abab")]
            self.assertTrue(results.device_line(d, mixed).startswith("Measured on MIXED devices"))

    def test_an_h100_or_h200_is_said_to_handicap_the_hybrids_raster_stages(self):
        records = results.load(VERDICT_SET)
        for name, caveat in (("NVIDIA H200", True), ("NVIDIA H100 80GB HBM3", True), ("NVIDIA GH200 480GB", True),
                             ("NVIDIA GeForce RTX 4090", False), ("llvmpipe (LLVM 15.0.6, 256 bits)", False), ("NVIDIA H2000", False)):
            with self.subTest(name=name):
                gpu = [dict(r, device=dict(device_record(), vulkan_device=name, vulkan_device_type="discrete_gpu")) for r in records]
                line = results.device_line(VERDICT_SET, gpu)
                self.assertEqual(line.endswith(". An H100/H200 runs graphics on few of its units (fragment work was measured 30x "
                                               "slower than compute there), which handicaps the hybrids' raster stages against rt_only."),
                                 caveat)
                _, warning = device.lines(VERDICT_SET, gpu)
                self.assertEqual(warning is not None and "30x slower" in warning, caveat)

    def test_write_table_puts_the_device_under_each_table(self):
        with tempfile.TemporaryDirectory() as d:
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                results.write_table(["| a |", "|---|", "| 1 |", "", "text"], os.path.join(d, "t.md"), "Measured on: X")
            self.assertEqual(out.getvalue(), "| a |\n|---|\n| 1 |\n\nMeasured on: X\n\ntext\n")
            self.assertEqual(read_text(os.path.join(d, "t.md")), out.getvalue())

    def test_schema_problems(self):
        for name in sorted(os.listdir(SETS)):
            if os.path.isdir(os.path.join(SETS, name)):
                self.assertEqual(results.results_problems(results.load(os.path.join(SETS, name))), [], name)
        r = results.load(VERDICT_SET)[0]
        for breaks, problem in [(lambda r: r.pop("id"), "$: missing required 'id'"),
                                (lambda r: r.update(width="64"), "$.width: expected integer"),
                                (lambda r: r.update(frame=-2), "$.frame: -2 is below the minimum -1"),
                                (lambda r: r.update(colour=1), "$: unexpected 'colour'"),
                                (lambda r: r["timing"].update(precision=1), "$.timing.precision: 1"),  # the tie band's end
                                (lambda r: r["timing"]["frame_ms_rounds"].__setitem__(0, "x"), "$.timing.frame_ms_rounds[0]: expected number")]:
            broken = copy.deepcopy(r)
            breaks(broken)
            found = results.schema_problems(broken)
            self.assertEqual(len(found), 1, found)
            self.assertTrue(found[0].startswith(problem), (problem, found))
        self.assertEqual(results.results_problems({}), ["results.json: expected an array of records"])

    def test_command_line_validates_a_set(self):
        ok = subprocess.run(["/usr/bin/python3", os.path.join(REPORT, "results.py"), VERDICT_SET], capture_output=True, text=True)
        self.assertEqual((ok.returncode, ok.stdout), (0, ""))
        with tempfile.TemporaryDirectory() as d:
            records = results.load(VERDICT_SET)
            records[1].pop("scene")
            write_text(os.path.join(d, "results.json"), json.dumps(records))
            bad = subprocess.run(["/usr/bin/python3", os.path.join(REPORT, "results.py"), d], capture_output=True, text=True)
        self.assertEqual((bad.returncode, bad.stdout), (1, "record 1: $: missing required 'scene'\n"))


class BadInput(unittest.TestCase):
    """A result set's file that is not as its writer writes it: ResultSetError, one line naming the
    file and the place in it (`hybridlab report`'s exit status 2; tests/cli/test_bad_input_table.cpp
    runs the program on such sets)."""

    def error(self, call, *args):
        with self.assertRaises(results.ResultSetError) as caught:
            call(*args)
        self.assertNotIn("\n", str(caught.exception))
        return str(caught.exception)

    def test_json_a_writer_never_writes(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "x.json")
            for text, problem in (("", "not valid JSON (Expecting value at line 1, column 1)"),
                                  ('{"a": 1,\n}', "at line 2, column 1"),
                                  ('{"a": NaN}', "NaN is not a JSON number"),
                                  ('{"a": 1e400}', "number 1e400 is beyond a double's range"),
                                  ("[" * 100000, "nested too deeply"),
                                  (b"\xff", "not UTF-8 text at byte 0")):
                with open(path, "wb") as f:
                    f.write(text if isinstance(text, bytes) else text.encode())
                message = self.error(results.read_json, path)
                self.assertTrue(message.startswith(path + ": not valid JSON ("), message)
                self.assertIn(problem, message)

    def test_records_checked_where_the_report_relies_on_them(self):
        table = results.BUILT_IN_METRICS
        good = results.load(VERDICT_SET)[1]
        self.assertEqual(results.record_problems(good, table), [])
        for breaks, problem in [(lambda r: r.update(label="L" * 256), "$.label: expected at most 255 characters, got 256"),
                                (lambda r: r["frame_ms"].update(median=0.0, min=0.0), "$.frame_ms.median: expected a number above 0, got 0.0"),
                                (lambda r: r["frame_ms"].update(median=2 * r["frame_ms"]["max"]), "$.frame_ms: expected min <= ci_low <= median <= ci_high <= max in that order, got min 20, ci_low 20, median 40"),
                                (lambda r: r["stages"].update(trace={"median": 1.0, "min": -1.0, "max": 2.0}), "$.stages.trace.min: -1.0 is below the minimum 0"),
                                (lambda r: r["metrics"]["whole"].update(ssim="x"), '$.metrics.whole.ssim: expected number or null, got "x"'),
                                (lambda r: r["metrics"]["whole"].update(ssim={"mean": 0.5}),
                                 "$.metrics.whole.ssim: expected a number (metric 'ssim' of the metric table)"),
                                (lambda r: r.update(schema_version=results.SCHEMA_VERSION + 1), "$.schema_version: %d is newer than this program reads" % (results.SCHEMA_VERSION + 1))]:
            broken = copy.deepcopy(good)
            breaks(broken)
            found = results.record_problems(broken, table)
            self.assertTrue(found and found[0].startswith(problem), (problem, found))

    def test_a_set_names_its_bad_file_and_record(self):
        with tempfile.TemporaryDirectory() as d:
            shutil.copytree(VERDICT_SET, os.path.join(d, "set"))
            d = os.path.join(d, "set")
            table = results.metric_table(d)
            self.assertEqual(len(results.checked_records(d, table)), 4)
            records = json.loads(read_text(os.path.join(d, "results.json")))
            write_text(os.path.join(d, "results.json"), json.dumps({"runs": records}))
            self.assertEqual(self.error(results.checked_records, d, table),
                             os.path.join(d, "results.json") + ': expected an array of records, got {"runs": [{"index": 0, "id": "0000-rt_on...')
            write_text(os.path.join(d, "results.json"), json.dumps(records[:2] + [7]))
            self.assertEqual(self.error(results.checked_records, d, table),
                             os.path.join(d, "results.json") + ": record 2: expected a run's record (an object), got 7")
            del records[3]["images"]
            write_text(os.path.join(d, "results.json"), json.dumps(records))
            self.assertEqual(self.error(results.checked_records, d, table),
                             os.path.join(d, "results.json") + ": record 3: $: missing required 'images'")
            os.remove(os.path.join(d, "results.json"))
            record = json.loads(read_text(os.path.join(d, "runs", "0001-heuristic_rt.json")))
            record["width"] = 0
            write_text(os.path.join(d, "runs", "0001-heuristic_rt.json"), json.dumps(record))
            self.assertEqual(self.error(results.checked_records, d, table),
                             os.path.join(d, "runs", "0001-heuristic_rt.json") + ": $.width: 0 is below the minimum 1")
            shutil.rmtree(os.path.join(d, "runs"))
            os.makedirs(os.path.join(d, "runs"))
            self.assertEqual(self.error(results.checked_records, d, table),
                             os.path.join(d, "runs") + ": holds no records (expected at least one run)")

    def test_experiment_json_where_the_report_reads_it(self):
        with tempfile.TemporaryDirectory() as d:
            self.assertEqual(results.metric_table(d), results.BUILT_IN_METRICS)  # a set older than experiment.json's table
            path = os.path.join(d, "experiment.json")
            table = copy.deepcopy(results.BUILT_IN_METRICS)
            write_text(path, json.dumps({"metric_table": table, "resolution_scale": 0.5}))
            self.assertEqual(results.metric_table(d), table)
            self.assertEqual(results.resolution_scale(d), 0.5)
            for experiment, problem in [({"metric_table": [dict(table[0], digits=-5)]}, "$.metric_table[0].digits: -5 is below the minimum 0"),
                                        ({"metric_table": [dict(table[0], better="more")]}, "$.metric_table[0].better: expected one of"),
                                        ({"metric_table": [dict(table[0], scored=False)]}, "$.metric_table: expected a scored metric"),
                                        ({"resolution_scale": 0}, "$.resolution_scale: expected a number above 0, got 0"),
                                        ({"device": "a GPU"}, '$.device: expected object or null, got "a GPU"'),
                                        ([], "$: expected object, got []")]:
                write_text(path, json.dumps(experiment))
                message = self.error(results.metric_table, d)
                self.assertTrue(message.startswith("%s: %s" % (path, problem)), (problem, message))


class StagedFolder(unittest.TestCase):
    """staged_folder.staged: a report folder written whole or not at all."""

    def test_a_failure_leaves_the_folder_as_it_was(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "report")
            with self.assertRaises(RuntimeError):
                with staged_folder.staged(out) as into:
                    write_text(os.path.join(into, "index.html"), "half")
                    raise RuntimeError("drawing failed")
            self.assertEqual(os.listdir(d), [])
            os.makedirs(os.path.join(out, "figures"))
            write_text(os.path.join(out, "index.html"), "earlier")
            write_text(os.path.join(out, "figures", "old.svg"), "earlier")
            write_text(os.path.join(out, "notes.txt"), "the user's")
            with self.assertRaises(OSError):
                with staged_folder.staged(out) as into:
                    write_text(os.path.join(into, "index.html"), "half")
                    raise OSError(28, "No space left on device")
            self.assertEqual(read_text(os.path.join(out, "index.html")), "earlier")
            # Whole: its entries replace those of their names, the others stay.
            with staged_folder.staged(out) as into:
                os.makedirs(os.path.join(into, "figures"))
                write_text(os.path.join(into, "index.html"), "new")
            self.assertEqual(sorted(os.listdir(d)), ["report"])
            self.assertEqual(sorted(os.listdir(out)), ["figures", "index.html", "notes.txt"])
            self.assertEqual((read_text(os.path.join(out, "index.html")), os.listdir(os.path.join(out, "figures"))), ("new", []))

    def test_a_destination_that_cannot_be_written(self):
        with tempfile.TemporaryDirectory() as d:
            write_text(os.path.join(d, "a-file"), "")
            for out in (os.path.join(d, "a-file"), os.path.join(d, "a-file", "report")):
                with self.assertRaises(OSError) as caught:
                    with staged_folder.staged(out):
                        self.fail("staged into " + out)
                self.assertEqual(caught.exception.filename, out)
            self.assertEqual(os.listdir(d), ["a-file"])

    def test_a_killed_reports_staging_folder_is_removed_by_the_next(self):
        with tempfile.TemporaryDirectory() as d:
            gone = subprocess.Popen(["true"])
            gone.wait()  # its process id is no process's now
            stale = os.path.join(d, ".tmp-%d-report.x1y2" % gone.pid)
            other = os.path.join(d, ".tmp-%d-figures.x1y2" % gone.pid)
            for folder in (stale, other):
                os.makedirs(folder)
                write_text(os.path.join(folder, "index.html"), "half")
            with staged_folder.staged(os.path.join(d, "report")) as staging:
                self.assertTrue(os.path.basename(staging).startswith(".tmp-%d-report." % os.getpid()))
                write_text(os.path.join(staging, "index.html"), "whole")
            self.assertEqual(sorted(os.listdir(d)), [os.path.basename(other), "report"])  # another folder's is its own


def device_record():
    return json.loads(read_text(os.path.join(VERDICT_SET, "experiment.json")))["device"]


class Images(unittest.TestCase):
    def test_reads_the_linear_pixels(self):
        pixels = images.rgb(os.path.join(VERDICT_SET, "images", "1.exr"))
        self.assertEqual(pixels.shape, (4, 8, 3))
        self.assertEqual(pixels.dtype, np.float32)
        self.assertTrue(np.all(pixels == np.float32(0.4)))
        grey = images.rgb(os.path.join(HERE, "..", "fixtures", "image_formats", "files", "luminance.exr"))
        self.assertEqual(grey.shape, (3, 5, 3))
        self.assertTrue(np.array_equal(grey[:, :, 0], grey[:, :, 2]))

    def test_names_an_unreadable_file(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "broken.exr")
            write_text(path, "v/1\x01 not an image")
            with self.assertRaises(images.ImageError) as e:
                images.check(path)
            self.assertIn(path, str(e.exception))


class Verdict(unittest.TestCase):
    def test_digests_find_the_identical_images(self):
        records = results.load(VERDICT_SET)
        digests = [verdict.image_digest(VERDICT_SET, r) for r in records]
        self.assertEqual(len(set(digests)), 3)
        self.assertEqual(digests[2], digests[3])  # raster's and layered_em's images are the same pixels

    def test_the_verdict_of_the_set(self):
        (v,) = verdict.verdicts(results.load(VERDICT_SET), VERDICT_SET)
        self.assertEqual(v.settings["raster"].not_applicable, "every image byte-identical to layered_em's")
        self.assertEqual(v.reference_ms, 100.0)
        self.assertEqual([s.name for s in v.pareto], ["layered_em", "heuristic_rt [budget=0]", "rt_only"])
        sentence = ("On scene at 64x36, the fastest setting reaching SSIM 0.99 on the whole image is heuristic_rt [budget=0] at "
                    "20.0 ms (5.00x (5.00-5.00) the reference's speed, 2.50x (2.50-2.50) rt_only's). The fastest setting of all is "
                    "layered_em at 6.0 ms (SSIM 0.9000); not applicable here: raster.")
        self.assertEqual(v.sentence(), sentence)
        out = subprocess.run(["/usr/bin/python3", os.path.join(REPORT, "verdict.py"), VERDICT_SET], capture_output=True, text=True)
        self.assertEqual((out.returncode, out.stdout), (0, sentence + "\n"))
        page, md = verdict.write([v], lambda run_id: "viewer.html#run=" + run_id)
        self.assertIn('<a href="viewer.html#run=0001-heuristic_rt">heuristic_rt [budget=0]</a>', page)
        self.assertIn("| [raster](viewer.html#run=0002-raster) | every image byte-identical to layered_em's |", md)


class DeviceAndColours(unittest.TestCase):
    def test_device_block(self):
        records = results.load(VERDICT_SET)
        rows, warning = device.lines(VERDICT_SET, records)
        self.assertEqual(rows[0], ("ray backend", "embree"))
        self.assertIn(("Vulkan device", "llvmpipe (cpu)"), rows)
        self.assertIn("software Vulkan device (llvmpipe)", warning)
        page, md = device.write(VERDICT_SET, records)
        self.assertIn("<th>processor</th><td>Test CPU (2 cores)</td>", page)
        self.assertTrue(md[1].startswith("Measured on: ray backend: embree; "))

    def test_one_hue_a_technique_one_shade_a_setting(self):
        records = results.load(VERDICT_SET)
        more = copy.deepcopy(records[1])
        more["parameters_text"] = "budget=5000"
        colours = palette.setting_colours(records + [more])
        self.assertEqual(len(colours), 5)
        dark, light = colours["heuristic_rt [budget=0]"], colours["heuristic_rt [budget=5000]"]
        self.assertLess(sum(dark), sum(light))  # darker first, in name order
        self.assertEqual(palette.shades((0.2, 0.4, 0.6), 1), [(0.2, 0.4, 0.6)])

    def test_figure_files(self):
        records = results.load(VERDICT_SET)
        self.assertIsNone(figure_files.device_note(records))
        mixed = [dict(r, device=dict(device_record(), vulkan_device=name)) for r, name in zip(records, "abab")]
        self.assertTrue(figure_files.device_note(mixed).startswith("MIXED devices: times do not compare across them\n(1) a ["))
        with tempfile.TemporaryDirectory() as d:
            os.makedirs(os.path.join(d, "figures"))
            fig = figure_files.plt.figure()
            fig.gca().plot([0, 1], [0, 1])
            svg = figure_files.save(fig, d, "line")
            self.assertTrue(os.path.isfile(os.path.join(d, "figures", "line.pdf")))
            self.assertIn('<object data="figures/line.svg"', figure_files.embed_html(svg, d))


if __name__ == "__main__":
    unittest.main()
