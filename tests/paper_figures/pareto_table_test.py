#!/usr/bin/env python3
"""paper_figures/pareto_table.py on a result set of known numbers: per scene, each setting's time
ratio to rt_only at the same view and frame (the median over them), its median SSIM, its rays and
SSR steps a pixel, and which settings are on their family's (label's) time and work fronts; then
the count over the scenes. Also: a set without rt_only is refused, naming it.

    pareto_table_test.py WORK_DIR

Exit status 0 when every expected line is in the table."""
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "..", "paper_figures", "pareto_table.py")


def record(scene, frame, technique, params, ms, ssim, rays, steps=None, label=None):
    counters = {"rays_total": rays}
    if steps is not None:
        counters["ssr_march_steps"] = steps
    return {"scene": scene, "view": "camera" if frame < 0 else "path", "frame": frame, "width": 10, "height": 10,
            "technique": technique, "label": label or technique, "parameters_text": params, "frame_ms": {"median": ms},
            "metrics": {"whole": {"ssim": ssim}}, "counters": counters}


# Scene s, two frames of a path; rt_only takes 100 and 200 ms. Time ratios (per frame, median):
# A 0.5, B 0.7 (0.8 and 0.6), C 0.9, D 0.1. Time front: D, A, B (C is slower and worse than B).
# Work front (rays and SSR steps a pixel): A 1.0 and 3.0, F 1.2 and 0.5 (more rays than A and
# less accurate, but fewer steps), C 1.5 and 1.0, B 2.0 and 1.0 (D's 4.0 rays at the lowest SSIM
# are dominated). G, of the same technique under another label, is its own family: better than
# every hyb setting on everything, it changes none of their fronts.
# Scene t, the camera; rt_only 100 ms: A 3.0 at 0.99, B 2.0 at 0.98, both on both fronts.
RECORDS = [
    record("s", 0, "rt_only", "", 100.0, 1.0, 300.0), record("s", 1, "rt_only", "", 200.0, 1.0, 300.0),
    record("s", 0, "hyb", "k=a", 50.0, 0.90, 100.0, 250.0), record("s", 1, "hyb", "k=a", 100.0, 0.92, 100.0, 350.0),
    record("s", 0, "hyb", "k=b", 80.0, 0.95, 200.0, 100.0), record("s", 1, "hyb", "k=b", 120.0, 0.97, 200.0, 100.0),
    record("s", 0, "hyb", "k=c", 90.0, 0.94, 150.0, 100.0), record("s", 1, "hyb", "k=c", 180.0, 0.94, 150.0, 100.0),
    record("s", 0, "hyb", "k=d", 10.0, 0.50, 400.0, 100.0), record("s", 1, "hyb", "k=d", 20.0, 0.50, 400.0, 100.0),
    record("s", 0, "hyb", "k=f", 95.0, 0.90, 120.0, 50.0), record("s", 1, "hyb", "k=f", 190.0, 0.90, 120.0, 50.0),
    record("s", 0, "hyb", "k=g", 10.0, 0.99, 10.0, 10.0, "hyb2"), record("s", 1, "hyb", "k=g", 20.0, 0.99, 10.0, 10.0, "hyb2"),
    record("t", -1, "rt_only", "", 100.0, 1.0, 300.0),
    record("t", -1, "hyb", "k=a", 300.0, 0.99, 100.0, 100.0), record("t", -1, "hyb", "k=b", 200.0, 0.98, 50.0, 100.0),
]

EXPECTED = [
    "| hyb [k=a] | 0.50 |  | 0.9100 | - | 1.00 | 3.0 | yes | yes |",
    "| hyb [k=b] | 0.70 |  | 0.9600 | - | 2.00 | 1.0 | yes | yes |",
    "| hyb [k=c] | 0.90 |  | 0.9400 | - | 1.50 | 1.0 |  | yes |",
    "| hyb [k=d] | 0.10 |  | 0.5000 | - | 4.00 | 1.0 | yes |  |",
    "| hyb [k=f] | 0.95 |  | 0.9000 | - | 1.20 | 0.5 |  | yes |",
    "| hyb2 [k=g] | 0.10 |  | 0.9900 | - | 0.10 | 0.1 | yes | yes |",
    "| rt_only | 1.00 |  | 1.0000 | - | 3.00 | - | yes | yes |",
    "| hyb [k=a] | 3.00 |  | 0.9900 | - | 1.00 | 1.0 | yes | yes |",
    "| hyb [k=b] | 2.00 |  | 0.9800 | - | 0.50 | 1.0 | yes | yes |",
    # setting | scenes | on time front | on work front | median time ratio | lowest SSIM
    "| hyb [k=a] | 2 | 2 | 2 | 1.75 | 0.9100 |",
    "| hyb [k=b] | 2 | 2 | 2 | 1.35 | 0.9600 |",
    "| hyb [k=c] | 1 | 0 | 1 | 0.90 | 0.9400 |",
    "| rt_only | 2 | 2 | 2 | 1.00 | 1.0000 |",
]


def write_set(folder, records):
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    with open(os.path.join(folder, "results.json"), "w") as f:
        json.dump(records, f)


def main():
    work = sys.argv[1]
    result_set = os.path.join(work, "sweep")
    write_set(result_set, RECORDS)
    out = subprocess.run(["/usr/bin/python3", SCRIPT, result_set], capture_output=True, text=True)
    failures = [] if out.returncode == 0 else ["exit status %d: %s" % (out.returncode, out.stderr)]
    lines = out.stdout.splitlines()
    failures += ["missing line: " + e for e in EXPECTED if e not in lines]
    if sum(line.startswith("**s, 10x10**") or line.startswith("**t, 10x10**") for line in lines) != 2:
        failures.append("not one table per scene")

    without = os.path.join(work, "without_rt_only")
    write_set(without, [r for r in RECORDS if r["technique"] != "rt_only"])
    refused = subprocess.run(["/usr/bin/python3", SCRIPT, without], capture_output=True, text=True)
    if refused.returncode == 0 or "has no rt_only runs" not in refused.stderr or without not in refused.stderr:
        failures.append("a set without rt_only: exit %d, %r" % (refused.returncode, refused.stderr))

    for f in failures:
        print(f)
    if failures:
        print(out.stdout)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
