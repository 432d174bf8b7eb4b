"""Reading a hybridlab result set (results.json) for the figure and report scripts.

Every script in paper_figures/ reads only results.json / results.csv, never the renderer."""
import json
import os
import sys


def load(result_dir):
    with open(os.path.join(result_dir, "results.json")) as f:
        return json.load(f)


def variant(r):
    """A technique with its parameter set: the unit that gets one colour and one series."""
    return r["label"] + (" [" + r["parameters_text"] + "]" if r["parameters_text"] else "")


def view_name(r):
    return r["view"] + ("@%d" % r["frame"] if r["frame"] >= 0 else "")


def resolution(r):
    return "%dx%d" % (r["width"], r["height"])


def metric(r, region, name):
    """SSIM, RMSE, PSNR (dB) or FLIP mean of a record on 'whole' or 'masked'; None if absent."""
    m = r["metrics"].get(region)
    if not m:
        return None
    if name == "flip":
        return m["flip"]["mean"]
    if name == "psnr":
        return m.get("psnr_db")
    return m.get(name)


def emit(lines, out=None):
    """A table script's Markdown: to standard output, and to the file `out` as well when given."""
    text = "\n".join(lines) + "\n"
    sys.stdout.write(text)
    if out:
        with open(out, "w") as f:
            f.write(text)


def pareto_front(points, higher_is_better):
    """Points (time, value, payload) not dominated by a faster-and-better one, sorted by time."""
    front = []
    best = None
    for t, v, p in sorted(points, key=lambda q: (q[0], -q[1] if higher_is_better else q[1])):
        if best is None or (v > best if higher_is_better else v < best):
            front.append((t, v, p))
            best = v
    return front
