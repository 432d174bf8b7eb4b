#!/usr/bin/python3
"""The results record's schema (experiments/results.schema.json) against its writer and a reader.

1. The validator (report/results.py, on python3-jsonschema) refuses records broken in known ways.
2. The C++ writer (experiments/runner/run_record.h's toJson): `hybridlab run` on a small
   experiment (a camera path's two frames, so that temporal errors are added; debug images and
   error maps kept; a technique that ray traces and a hybrid with debug images) writes results.json
   and runs/<id>.json records that all validate; so do the same experiment's two shards, and their
   merge as if measured on two devices (each record then holds its "device").
3. report/results.py reads those records: every accessor the report scripts use works.

usage: results_schema_test.py HYBRIDLAB_BINARY SCRATCH_DIR
"""
import copy
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "report"))
import results  # noqa: E402
import timing  # noqa: E402

CONFIG = """
[experiment]
name = "schema"
repeats = 6
max_rounds = 6
warmup_frames = 0
keep = ["debug_images", "error_maps"]

[[scenes]]
scene = "whitted-classic"
resolutions = [[24, 16]]
[[scenes.views]]
path = "orbit"
frames = [0, 1]

[[techniques]]
name = "ssr_fallback"

[[techniques]]
name = "rt_only"
params = { max_depth = [1, 3] }
"""


def check(condition, message):
    if not condition:
        sys.exit("FAILED: " + message)


def check_refusals(record):
    """Each mutation must produce the one problem named (a validator that accepts anything fails)."""
    def mutated(change):
        r = copy.deepcopy(record)
        change(r)
        return results.schema_problems(r)

    cases = [
        (lambda r: r.pop("id"), "$: missing required 'id'"),
        (lambda r: r.__setitem__("width", "24"), "$.width: expected integer"),
        (lambda r: r.__setitem__("frame", -2), "$.frame: -2 is below the minimum -1"),
        (lambda r: r["frame_ms"].pop("median"), "$.frame_ms: missing required 'median'"),
        (lambda r: r.__setitem__("colour", 1), "$: unexpected 'colour'"),
        (lambda r: r["reference"].__setitem__("cache_hit", 1), "$.reference.cache_hit: expected boolean"),
        (lambda r: r["counters"].__setitem__("rays_total", "many"), "$.counters.rays_total: expected number"),
        (lambda r: r["metrics"]["whole"].__setitem__("pixels", -1), "$.metrics.whole.pixels: -1 is below the minimum 0"),
    ]
    for change, expected in cases:
        found = mutated(change)
        check(len(found) == 1 and found[0].startswith(expected), f"expected [{expected}...], got {found}")
    # What the schema allows: no finite PSNR (identical images), no masked pixels, no maps.
    allowed = [
        lambda r: r["metrics"]["whole"].__setitem__("psnr_db", None),
        lambda r: r["metrics"].__setitem__("masked", None),
        lambda r: r["images"].__setitem__("maps", None),
    ]
    for change in allowed:
        found = mutated(change)
        check(found == [], f"a valid variant refused: {found}")
    print(f"validator: {len(cases)} broken records refused, {len(allowed)} valid variants accepted")


def check_intervals_agree(records):
    """The runner's intervals (C++, experiments/runner/timing_statistics.h) equal the report's
    (report/timing.py) on the same rounds: one statistic written twice, held equal here."""
    for r in records:
        t = r["timing"]
        check(t["rounds"] == 6 and len(t["frame_ms_rounds"]) == 6, f"{r['id']}: expected 6 rounds, got {t['rounds']}")
        iv = timing.median_interval(t["frame_ms_rounds"])
        check((iv.median, iv.low, iv.high) == (r["frame_ms"]["median"], r["frame_ms"]["ci_low"], r["frame_ms"]["ci_high"]),
              f"{r['id']}: the runner's interval {r['frame_ms']} is not the report's {iv}")
        ratios = [ref / ms for ref, ms in zip(t["reference_ms_rounds"], t["frame_ms_rounds"])]
        iv = timing.median_interval(ratios)
        s = r["speedup"]["reference"]
        check(abs(iv.median - s["ratio"]) <= 1e-12 * s["ratio"] and (iv.low, iv.high) == (s["low"], s["high"]),
              f"{r['id']}: the runner's speed-up {s} is not the report's {iv}")
    print(f"intervals: the runner's and the report's agree on {len(records)} records")


def validate_set(folder):
    """The problems of a result set's results.json and runs/<id>.json records, and its records."""
    records = results.load(folder)
    problems = results.results_problems(records)
    for name in sorted(os.listdir(os.path.join(folder, "runs"))):
        with open(os.path.join(folder, "runs", name)) as f:
            problems += [f"runs/{name}: {p}" for p in results.schema_problems(json.load(f))]
    return records, problems


def check_sharded_and_mixed(binary, config, scratch, env, runs):
    """The experiment as two shards, the second as if measured on another device, merged with
    --allow-mixed-devices: the shards' records and the merged ones (each with its "device") validate."""
    shards = []
    for i in range(2):
        shard = os.path.join(scratch, f"shard{i}")
        done = subprocess.run([binary, "run", config, "--out", shard, "--shard", f"{i}/2", "--quiet"], env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
        check(done.returncode == 0, f"hybridlab run --shard {i}/2 failed:\n" + done.stdout)
        records, problems = validate_set(shard)
        check(not problems, f"shard {i}/2's records break the schema:\n  " + "\n  ".join(problems))
        shards.append(shard)
    meta_file = os.path.join(shards[1], "experiment.json")
    with open(meta_file) as f:
        meta = json.load(f)
    meta["device"]["vulkan_device"] = "Imaginary GPU 9000"
    with open(meta_file, "w") as f:
        json.dump(meta, f, indent=1)
    merged = os.path.join(scratch, "merged")
    done = subprocess.run([binary, "merge", "--allow-mixed-devices", "--out", merged] + shards, env=env,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
    check(done.returncode == 0, "hybridlab merge --allow-mixed-devices failed:\n" + done.stdout)
    records, problems = validate_set(merged)
    check(not problems, "the merged records break the schema:\n  " + "\n  ".join(problems))
    check(len(records) == runs, f"expected {runs} merged records, got {len(records)}")
    devices = {r["device"]["vulkan_device"] for r in records}
    check(len(devices) == 2 and "Imaginary GPU 9000" in devices, f"expected each record's device, two in all: {devices}")
    check(any("temporal_error" in r for r in records), "the merged set has no temporal error")
    print(f"writer: 2 shards and their merge from two devices ({len(records)} records, each with its device) validate")


def main():
    binary, scratch = sys.argv[1], os.path.abspath(sys.argv[2])
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    config = os.path.join(scratch, "schema.toml")
    with open(config, "w") as f:
        f.write(CONFIG)
    out = os.path.join(scratch, "results")
    env = dict(os.environ, HYBRIDLAB_CACHE=os.path.join(scratch, "cache"), HYBRIDLAB_VULKAN_DEVICE="llvmpipe")
    done = subprocess.run([binary, "run", config, "--out", out], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=600)
    if done.returncode == 77 or "no Vulkan device" in done.stdout:
        print(done.stdout)
        sys.exit(77)
    check(done.returncode == 0, "hybridlab run failed:\n" + done.stdout)

    records, problems = validate_set(out)
    check(len(records) == 6, f"expected 6 records (2 frames x 3 settings), got {len(records)}")
    check(not problems, "records break the schema:\n  " + "\n  ".join(problems))
    check(any("temporal_error" in r for r in records), "no record has a temporal error (the path's second frame should)")
    check(any(r["images"].get("debug") for r in records), "no record lists debug images")
    print(f"writer: {len(records)} records of results.json and runs/ validate")

    check_intervals_agree(records)
    check_sharded_and_mixed(binary, config, scratch, env, len(records))
    check_refusals(records[-1])

    for r in records:
        check(isinstance(results.variant(r), str) and results.view_name(r).startswith("orbit@"), "results.py names")
        check(results.resolution(r) == "24x16", "results.resolution")
        for region in ("whole", "masked"):
            for name in ("ssim", "flip", "flip_hdr", "psnr", "rmse"):
                value = results.metric(r, region, name)
                check(value is None or isinstance(value, (int, float)), f"results.metric({region}, {name}) = {value!r}")
        check(isinstance(results.metric(r, "whole", "ssim"), float), "every record has a whole-image SSIM")
    print("results.py: every record read")
    shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
