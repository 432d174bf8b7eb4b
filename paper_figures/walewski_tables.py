"""Walewski 2019 Tables 5 and 6 from a result set of experiments/configs/walewski2019.toml.

    /usr/bin/python3 paper_figures/walewski_tables.py RESULT_DIR [--out FILE.md]

Table 5 (one static view per scene, the scene camera): the stage times of `heuristic_rt` (RAST,
HEUR, RAYT, BLEND, FRAME) and the frame time of `rt_only` ("RAYT ONLY FRAME"), with `whitted`'s
frame time and each one's SSIM and FLIP against the reference beside them. Table 6 (along the
scene's camera path): mean frame time with and without the heuristic. Times are the medians over a
run's repeats; means along a path are over its frames. The technique entries are found by label
(heuristic, no-heuristic, rt_only, whitted), as the config names them."""
import argparse
import statistics
import sys

import results

LABELS = {"heuristic": "heuristic", "no_heuristic": "no-heuristic", "rt_only": "rt_only", "whitted": "whitted"}


def stage(r, name):
    s = r["stages"].get(name)
    return s["median"] if s else 0.0


def by_label(rows, label):
    return [r for r in rows if r["label"] == label]


def fmt(x, digits=3):
    return "-" if x is None else ("%.*f" % (digits, x))


def table5(rows, scenes):
    out = ["**Table 5** (static view, the scene camera; ms, medians over repeats)", "",
           "| | " + " | ".join(scenes) + " |", "|---|" + "---|" * len(scenes)]

    def cell(scene, label, fn):
        rs = [r for r in by_label(rows, label) if r["scene"] == scene and r["frame"] < 0]
        return fn(rs[0]) if rs else None

    lines = [
        ("FRAME (heuristic_rt)", "heuristic", lambda r: r["frame_ms"]["median"]),
        ("RAST", "heuristic", lambda r: stage(r, "rast")),
        ("HEUR", "heuristic", lambda r: stage(r, "heur")),
        ("RAYT", "heuristic", lambda r: stage(r, "rayt")),
        ("BLEND", "heuristic", lambda r: stage(r, "blend")),
        ("RAYT ONLY FRAME (rt_only)", "rt_only", lambda r: r["frame_ms"]["median"]),
        ("WHITTED FRAME", "whitted", lambda r: r["frame_ms"]["median"]),
        ("objects selected / visible", "heuristic",
         lambda r: "%d / %d" % (r["counters"].get("objects_selected", 0), r["counters"].get("objects_visible", 0))),
    ]
    for name, label, fn in lines:
        vals = [cell(s, LABELS[label], fn) for s in scenes]
        out.append("| %s | %s |" % (name, " | ".join(v if isinstance(v, str) else fmt(v) for v in vals)))
    for name, label in (("heuristic_rt", "heuristic"), ("rt_only", "rt_only"), ("whitted", "whitted")):
        vals = [cell(s, LABELS[label], lambda r: (results.metric(r, "whole", "ssim"), results.metric(r, "whole", "flip")))
                for s in scenes]
        out.append("| SSIM / FLIP %s | %s |" % (name, " | ".join("-" if v is None else "%.4f / %.4f" % v for v in vals)))
    for name, label in (("rt_only", "rt_only"), ("whitted", "whitted")):
        vals = []
        for s in scenes:
            h = cell(s, LABELS["heuristic"], lambda r: r["frame_ms"]["median"])
            o = cell(s, LABELS[label], lambda r: r["frame_ms"]["median"])
            vals.append(None if h is None or o is None else o / h)
        out.append("| speed-up of heuristic_rt over %s | %s |" % (name, " | ".join(fmt(v, 2) + "x" if v else "-" for v in vals)))
    return out


def table6(rows, scenes):
    out = ["", "**Table 6** (along the camera path; mean over its frames of the median frame time, ms; mean SSIM)", "",
           "| | " + " | ".join(scenes) + " |", "|---|" + "---|" * len(scenes)]
    for name, label in (("with heuristic", "heuristic"), ("no heuristic", "no_heuristic"), ("rt_only", "rt_only"),
                        ("whitted", "whitted")):
        vals = []
        for s in scenes:
            rs = [r for r in by_label(rows, LABELS[label]) if r["scene"] == s and r["frame"] >= 0]
            if not rs:
                vals.append("-")
                continue
            t = statistics.mean(r["frame_ms"]["median"] for r in rs)
            q = statistics.mean(results.metric(r, "whole", "ssim") for r in rs)
            vals.append("%.1f (SSIM %.4f, %d frames)" % (t, q, len(rs)))
        out.append("| %s | %s |" % (name, " | ".join(vals)))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("result_dir")
    ap.add_argument("--out", help="write the tables (Markdown) here as well as to standard output")
    a = ap.parse_args()
    rows = results.load(a.result_dir)
    scenes = sorted({r["scene"] for r in rows})
    if not scenes:
        sys.exit("walewski_tables: %s has no runs" % a.result_dir)
    text = "\n".join(table5(rows, scenes) + table6(rows, scenes)) + "\n"
    sys.stdout.write(text)
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
