#!/usr/bin/env python3
"""The report's speed-accuracy charts place their point labels without overlap.

    chart_labels_test.py HYBRIDLAB_BIN WORK_DIR [RESULT_DIR]

Without RESULT_DIR, runs the quick experiment's settings (experiments/configs/quick.toml: every
technique and parameter set) on its scenes' cameras at 64x36 with one repeat, so that the charts
hold the quick experiment's points at a test's cost. Then, for every scene and size, draws the
speed-accuracy figure as report.py does and checks, in display pixels after drawing: every
applicable setting has one numbered label in every panel where it has a score, and no two labels'
boxes overlap (matplotlib's get_window_extent). Exit status 0 when all hold."""
import os
import subprocess
import sys
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "report"))

import figure_files  # noqa: E402,F401  (selects matplotlib's file backend first)
import matplotlib.pyplot as plt  # noqa: E402
import point_labels  # noqa: E402
import report  # noqa: E402
import results as rs  # noqa: E402
import verdict  # noqa: E402

QUICK = os.path.join(HERE, "..", "..", "experiments", "configs", "quick.toml")


def toml_value(v):
    if isinstance(v, str):
        return '"%s"' % v
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join("%s = %s" % (k, toml_value(x)) for k, x in v.items()) + " }"
    return repr(v)


def small_quick_config():
    """quick.toml's techniques on its scenes' cameras at 64x36, one repeat."""
    with open(QUICK, "rb") as f:
        quick = tomllib.load(f)
    lines = ['[experiment]', 'name = "quick-64x36"', 'warmup_frames = 0', 'repeats = 1', "",
             "[reference]", "params = %s" % toml_value(quick["reference"]["params"]), ""]
    for scene in quick["scenes"]:
        lines += ["[[scenes]]", 'scene = "%s"' % scene["scene"], "resolutions = [[64, 36]]", "[[scenes.views]]", ""]
    for t in quick["techniques"]:
        lines.append("[[techniques]]")
        lines += ["%s = %s" % (k, toml_value(v)) for k, v in t.items()]
        lines.append("")
    return "\n".join(lines)


def label_boxes(fig):
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    return [(ax, [(t.get_text(), t.get_window_extent(renderer)) for t in ax.texts if t.get_label() == point_labels.LABEL])
            for ax in fig.axes]


def check(result_dir):
    records = rs.load(result_dir)
    failures, checked = [], 0
    for v in verdict.verdicts(records, result_dir):
        fig = report.speed_accuracy_figure(v, "%s at %s" % (v.scene, v.size))
        expected = len(v.applicable())
        for ax, boxes in label_boxes(fig):
            if not boxes:
                continue
            name = "%s %s: %s" % (v.scene, v.size, ax.get_ylabel())
            texts = sorted(t for t, _ in boxes)
            if len(boxes) != len(ax.points) or len(set(texts)) != len(texts):
                failures.append("%s: %d labels for %d points" % (name, len(boxes), len(ax.points)))
            if len(ax.points) > expected:
                failures.append("%s: %d points for %d applicable settings" % (name, len(ax.points), expected))
            for i, (ta, a) in enumerate(boxes):
                for tb, b in boxes[i + 1:]:
                    if point_labels.overlaps(a, b, pad=0.0):
                        failures.append("%s: labels %s and %s overlap (%s, %s)" % (name, ta, tb, a.bounds, b.bounds))
            checked += len(boxes)
        plt.close(fig)
    return checked, failures


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: chart_labels_test.py HYBRIDLAB_BIN WORK_DIR [RESULT_DIR]")
    hybridlab, work = sys.argv[1], os.path.abspath(sys.argv[2])
    result_dir = sys.argv[3] if len(sys.argv) > 3 else None
    if result_dir is None:
        os.makedirs(work, exist_ok=True)
        config = os.path.join(work, "quick-64x36.toml")
        with open(config, "w") as f:
            f.write(small_quick_config())
        result_dir = os.path.join(work, "results")
        r = subprocess.run([hybridlab, "run", config, "--out", result_dir, "--cache", os.path.join(work, "cache"), "--resume"],
                           capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit("hybridlab run failed:\n%s\n%s" % (r.stdout, r.stderr))
    checked, failures = check(result_dir)
    for f in failures:
        print("FAIL: " + f)
    print("%d point labels checked, %d failures" % (checked, len(failures)))
    if checked == 0:
        sys.exit("no point labels drawn")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
