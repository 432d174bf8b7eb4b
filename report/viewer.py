"""The side-by-side technique viewer of a report: viewer.html, and viewer/ beside it holding the
viewer's ES modules (report/viewer/*.js), its styles and settings.json (what the report knows that
the records do not: the title, the reference's parameters, the settings found not applicable, the
report's colour of each setting, the metric table (the result set's, or the built-in one for a set
older than that), the steps that read older records as current ones (results.migrations.json),
the error maps' colour tables, and where the result set lies).

The viewer reads the result set itself: results.json, and the images the records name (EXR
decoded in the browser, PNG natively), with no second copy, so its own files are the same few
hundred kilobytes whatever the set's size. A browser lets a page read files (and load modules)
only from a web server: `hybridlab view RESULTS` (serve.py) serves the result set and its report
on 127.0.0.1; opened from the file system, the viewer says so."""
import json
import os
import shutil
import tomllib

import matplotlib

import results as rs

VIEWER_SOURCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "viewer")
# zlib for the EXRs' ZIP blocks (exr.js): Debian's node-pako, as an ES module; copied as .js, the
# type every static server gives a script.
PAKO = "/usr/share/nodejs/pako/dist/pako.esm.mjs"
STYLES = "viewer.css"
PAGE = "viewer.html"
# Says the modules are ES modules, for a Node.js that reads the report's copies (Debian's 18 does not
# guess it from their import statements); a browser goes by the script tag and never reads it.
MODULE_TYPE = "package.json"


def missing():
    """What the viewer needs from the system and this machine lacks, in a sentence; None when
    nothing is missing."""
    if not os.path.isfile(PAKO):
        return "%s is missing (Debian's node-pako, which ./setup.sh installs): the viewer inflates EXRs with it" % PAKO
    return None


def colour_table(name):
    cmap = matplotlib.colormaps[name].resampled(256)
    return [[round(255 * c) for c in cmap(i)[:3]] for i in range(256)]


def reference_parameters(result_dir):
    """The reference's parameters from the config the result set was run with, as `k=v k=v`; ""
    for a set without one. rs.ResultSetError where config.toml is not TOML or its reference's
    parameters are not a table."""
    path = os.path.join(result_dir, "config.toml")
    if not os.path.exists(path):
        return ""
    with open(path, "rb") as f:
        try:
            config = tomllib.load(f)
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
            raise rs.ResultSetError("%s: not valid TOML (%s)" % (path, e)) from None
    reference = config.get("reference", {})
    params = reference.get("params", {}) if isinstance(reference, dict) else None
    if not isinstance(params, dict):
        raise rs.ResultSetError("%s: reference.params: expected a table of the reference's parameters" % path)
    return " ".join("%s=%s" % (k, v if isinstance(v, str) else json.dumps(v, default=str)) for k, v in sorted(params.items()))


def serve_command(result_dir, out_dir):
    """The command that serves this report's viewer: `hybridlab view RESULTS`, with `--report` where
    the report is not RESULTS/report."""
    command = "hybridlab view %s" % result_dir
    if os.path.realpath(out_dir) != os.path.realpath(os.path.join(result_dir, "report")):
        command += " --report %s" % out_dir
    return command


def write_viewer(records, out_dir, result_dir, title, not_applicable, colours, metric_table, reference, into):
    """viewer.html and viewer/ for the report in `out_dir` on the result set in `result_dir`,
    written into the folder `into` (the report's, before it is moved to `out_dir`);
    `not_applicable`: {(scene, size, setting name): why} for the settings the verdict left out;
    `colours`: {setting name: "#rrggbb"}, the report's; `metric_table`: results.metric_table's;
    `reference`: reference_parameters'."""
    viewer_dir = os.path.join(into, "viewer")
    os.makedirs(viewer_dir)
    settings = {
        "title": title,
        "result_set": os.path.relpath(result_dir, out_dir).replace(os.sep, "/"),
        "serve_command": serve_command(result_dir, out_dir),
        "reference_parameters": reference,
        "not_applicable": [[scene, size, name, why] for (scene, size, name), why in sorted(not_applicable.items())],
        "colours": colours,
        "metrics": metric_table,
        "migrations": rs.MIGRATIONS,
        # The runner's error maps' colour tables (OpenCV takes its viridis and magma from
        # matplotlib): the viewer reads a map's values back from its colours and draws its own.
        "colormaps": {name: colour_table(name) for name in ("viridis", "magma")},
    }
    with open(os.path.join(viewer_dir, "settings.json"), "w") as f:
        json.dump(settings, f, separators=(",", ":"))
    shutil.copyfile(PAKO, os.path.join(viewer_dir, "pako.js"))
    for name in sorted(os.listdir(VIEWER_SOURCE)):
        if name.endswith(".js") or name in (STYLES, MODULE_TYPE):
            shutil.copyfile(os.path.join(VIEWER_SOURCE, name), os.path.join(viewer_dir, name))
    with open(os.path.join(VIEWER_SOURCE, PAGE)) as f:
        page = f.read().replace("@SERVE_COMMAND@", settings["serve_command"].replace("\\", "\\\\").replace("'", "\\'"))
    with open(os.path.join(into, PAGE), "w") as f:
        f.write(page)


def link(run_id, from_dir=""):
    """The viewer opened on one run, from a page in `from_dir` (relative to the report folder)."""
    return os.path.join(os.path.relpath(".", from_dir or "."), PAGE).removeprefix("./") + "#run=" + run_id
