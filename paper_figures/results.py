"""Reading a hybridlab result set (results.json) for the figure and report scripts.

Every script in paper_figures/ reads only results.json / results.csv, never the renderer."""
import argparse
import json
import os
import re
import sys


def load(result_dir):
    with open(os.path.join(result_dir, "results.json")) as f:
        return json.load(f)


def variant(r):
    """A technique with its parameter set: the unit that gets one colour and one series."""
    return r["label"] + (" [" + r["parameters_text"] + "]" if r["parameters_text"] else "")


def backend(r):
    """The ray backend of a run: its `rays` parameter ("embree", the CPU, where it has none, as the
    techniques' default; "vulkan", the ray-tracing Vulkan device)."""
    m = re.search(r"(?:^| )rays=(\S+)", r["parameters_text"])
    return m.group(1) if m else "embree"


def without_backend(r):
    """The record with `rays=...` taken out of its parameters_text, for tables split by backend."""
    return dict(r, parameters_text=re.sub(r"(?:^| )rays=\S+", "", r["parameters_text"]).strip())


def natural_key(value):
    """A sort key that orders the numbers inside names by value, so that "budget=5000" comes before
    "budget=20000" (plain string order puts it after); tuples of names are keyed element by element."""
    if isinstance(value, tuple):
        return tuple(natural_key(v) for v in value)
    parts = re.split(r"(\d+(?:\.\d+)?)", str(value))
    return [float(p) if i % 2 else p for i, p in enumerate(parts)]


def view_name(r):
    return r["view"] + ("@%d" % r["frame"] if r["frame"] >= 0 else "")


def resolution(r):
    return "%dx%d" % (r["width"], r["height"])


# The names the tables give the metrics: FLIP on the display images and HDR-FLIP on the linear
# ones (Andersson et al. 2021) are told apart wherever both are shown.
METRIC_LABELS = {"ssim": "SSIM", "flip": "FLIP (LDR)", "flip_hdr": "HDR-FLIP", "psnr": "PSNR dB"}


def metric(r, region, name):
    """SSIM, RMSE, PSNR (dB), FLIP or HDR-FLIP mean of a record on 'whole' or 'masked'; None if
    absent (the region, or the metric: a config's `metrics` may leave it out, and result sets
    written before HDR-FLIP have none)."""
    m = r["metrics"].get(region)
    if not m:
        return None
    if name in ("flip", "flip_hdr"):
        return m[name]["mean"] if name in m else None
    if name == "psnr":
        return m.get("psnr_db")
    return m.get(name)


def fmt(value, spec="%.3f", missing="-"):
    """A table cell: `value` formatted by `spec`, or `missing` where the run has no such value."""
    return missing if value is None else spec % value


# One name per kind of work across techniques; result sets written before the techniques used
# these names carry the old ones, read here under the new.
STAGE_NAMES = {"rast": "raster", "heur": "heuristic", "rayt": "trace", "ray_trace": "trace"}


def stage_name(name):
    return STAGE_NAMES.get(name, name)


def stages(r):
    """A record's median stage times (ms) by their names in the one vocabulary."""
    out = {}
    for name, s in r["stages"].items():
        out[stage_name(name)] = out.get(stage_name(name), 0.0) + s["median"]
    return out


def stage(r, name, missing=None):
    """The median time (ms) of a record's stage `name` (either vocabulary); `missing` if the
    technique has no such stage."""
    return stages(r).get(stage_name(name), missing)


def result_link(out_dir, result_dir, path):
    """A result set's file (`path` relative to `result_dir`, as the records name them) as a link from `out_dir`."""
    return os.path.relpath(os.path.join(result_dir, path), out_dir)


def pareto_front(points, higher_is_better):
    """Points (time, value, payload) not dominated by a faster-and-better one, sorted by time."""
    front = []
    best = None
    for t, v, p in sorted(points, key=lambda q: (q[0], -q[1] if higher_is_better else q[1])):
        if best is None or (v > best if higher_is_better else v < best):
            front.append((t, v, p))
            best = v
    return front


def mean_known(values):
    """The mean of the values that are not None; None if there are none."""
    known = [v for v in values if v is not None]
    return sum(known) / len(known) if known else None


def table_script(doc, name, extra_arguments=()):
    """The command line every table script shares: RESULT_DIR [--out FILE.md] plus `extra_arguments`
    (argparse add_argument argument tuples, keyword dicts). Returns the parsed arguments and the
    result set's rows; exits with a message naming the folder when it holds no runs."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("result_dir")
    ap.add_argument("--out", help="write the table(s) (Markdown) here as well as to standard output")
    for args, kwargs in extra_arguments:
        ap.add_argument(*args, **kwargs)
    a = ap.parse_args()
    if not os.path.isfile(os.path.join(a.result_dir, "results.json")):
        sys.exit("%s: %s is not a result set (no results.json)" % (name, a.result_dir))
    rows = load(a.result_dir)
    if not rows:
        sys.exit("%s: %s has no runs" % (name, a.result_dir))
    return a, rows


def device_summary(d):
    """One line for a device record (experiment.json's "device"; DESIGN.md "Experiments and results")."""
    if not d:
        return "unknown device (recorded before result sets named theirs)"
    g = lambda k: str(d.get(k, "?"))
    return "%s [%s; %s; Vulkan %s], %s x %s cores, Embree %s, TBB %s threads, LP_NUM_THREADS %s, %s, hybridlab %s" % (
        g("vulkan_device"), g("vulkan_device_type"), g("vulkan_driver"), g("vulkan_api_version"), g("cpu_model"), g("cpu_cores"),
        g("embree_version"), g("tbb_threads"), g("lp_num_threads"), g("os"), g("program_version"))


def devices(result_dir, rows=()):
    """The devices a result set was measured on: each run's own where a merge kept them (shards from
    several devices), else experiment.json's one; [None] when the set predates device records."""
    own = []
    for r in rows:
        if "device" in r and r["device"] not in own:
            own.append(r["device"])
    if own:
        return own
    try:
        with open(os.path.join(result_dir, "experiment.json")) as f:
            return [json.load(f).get("device")]
    except (OSError, ValueError):
        return [None]


def device_line(result_dir, rows=()):
    """The line printed under a table: the device the times were measured on, or the devices, marked mixed."""
    ds = devices(result_dir, rows)
    if len(ds) == 1:
        return "Measured on: " + device_summary(ds[0])
    return "Measured on MIXED devices (times do not compare across them): " + "; ".join(
        "(%d) %s" % (i + 1, device_summary(d)) for i, d in enumerate(ds))


def write_table(lines, out_path=None, device=None):
    """A table script's Markdown lines to standard output, and to `out_path` if given; with `device`
    (device_line's), that line under each table."""
    if device:
        with_device = []
        for i, line in enumerate(lines):
            with_device.append(line)
            if line.startswith("|") and (i + 1 == len(lines) or not lines[i + 1].startswith("|")):
                with_device += ["", device]
        lines = with_device
    text = "\n".join(lines) + "\n"
    sys.stdout.write(text)
    if out_path:
        with open(out_path, "w") as f:
            f.write(text)
