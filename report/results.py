"""Reading a hybridlab result set (results.json, else runs/) for the figure and report scripts, and
checking its records against their JSON Schema (experiments/results.schema.json) with Debian's
python3-jsonschema, and against what the report relies on beyond it; experiment.json's parts that
the report reads are checked alike. A file that is not as its writer writes it raises
ResultSetError, naming the file and the place in it.

Every script of the report and of paper_figures/ reads only the records, never the renderer.

    results.py RESULT_DIR      validates the set's records; exit status 1 with the problems"""
import argparse
import json
import math
import os
import re
import sys

import jsonschema

SCHEMA_PATH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "experiments", "results.schema.json")
MIGRATIONS_PATH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "experiments", "results.migrations.json")


def migrations():
    """The steps that take an older record to the current schema_version (results.migrations.json)."""
    with open(MIGRATIONS_PATH) as f:
        return json.load(f)["steps"]


MIGRATIONS = migrations()
SCHEMA_VERSION = MIGRATIONS[-1]["to"]


class ResultSetError(Exception):
    """A result set's file that is not as its writer writes it: the message names the file, the
    place in it (record, key, line) and what was expected. `hybridlab report` says it on one line,
    exit status 2."""


def _cut(text, limit=40):
    """`text` cut to `limit` characters: a message quotes what it found, never all of it."""
    return text if len(text) <= limit else text[:limit] + "..."


def _shown(value, limit=40):
    """`value` as JSON, _cut."""
    return _cut(json.dumps(value), limit)


def _finite(text):
    value = float(text)
    if not math.isfinite(value):
        raise ValueError("number %s is beyond a double's range" % text)
    return value


def _no_constant(name):
    raise ValueError("%s is not a JSON number" % name)


def read_json(path):
    """The JSON value in `path`. ResultSetError where it is not JSON, with the line and column (NaN,
    Infinity and numbers beyond a double's range included: no writer of a result set writes them);
    OSError where it cannot be read."""
    with open(path, "rb") as f:
        data = f.read()
    try:
        return json.loads(data.decode("utf-8"), parse_float=_finite, parse_constant=_no_constant)
    except json.JSONDecodeError as e:
        raise ResultSetError("%s: not valid JSON (%s at line %d, column %d)" % (path, e.msg, e.lineno, e.colno)) from None
    except UnicodeDecodeError as e:
        raise ResultSetError("%s: not valid JSON (not UTF-8 text at byte %d)" % (path, e.start)) from None
    except ValueError as e:
        raise ResultSetError("%s: not valid JSON (%s)" % (path, e)) from None
    except RecursionError:
        raise ResultSetError("%s: not valid JSON (nested too deeply)" % path) from None


def _renamed(values, rename, prefixes):
    """`values` (a record's stages or counters) with its keys renamed; values that meet under one
    name add up, number by number."""
    out = {}
    for key, value in values.items():
        key = rename.get(key, key)
        for old, new in prefixes.items():
            if key.startswith(old):
                key = new + key[len(old):]
        if key in out and isinstance(value, dict):
            out[key] = {k: out[key].get(k, 0.0) + v for k, v in value.items()}
        elif key in out:
            out[key] += value
        else:
            out[key] = value
    return out


def migrate(record):
    """The record as the current schema_version has it: the one place old result sets' names are
    read (each step of results.migrations.json in turn, from the record's version; none is version 1)."""
    version = record.get("schema_version", 1)
    if type(version) is not int:
        return record  # not a version: record_problems says so
    for step in MIGRATIONS:
        if step["from"] < version:
            continue
        for field in set(step.get("rename", {})) | set(step.get("rename_prefixes", {})):
            if isinstance(record.get(field), dict):
                record[field] = _renamed(record[field], step.get("rename", {}).get(field, {}), step.get("rename_prefixes", {}).get(field, {}))
        version = step["to"]
    record["schema_version"] = version
    return record


def is_result_set(result_dir):
    """Whether `result_dir` holds a result set: results.json, or the records of a set whose runner
    has not written it (still running, or killed)."""
    return os.path.isfile(os.path.join(result_dir, "results.json")) or os.path.isdir(os.path.join(result_dir, "runs"))


def sourced_records(result_dir):
    """(where, record) for each record of a result set, migrated to the current schema_version,
    ordered by run index, `where` naming its file (and its place in results.json): results.json,
    or where the runner has not written it (still running, or killed), the records in runs/
    themselves, which lack only what needs the whole set (temporal errors); `hybridlab report` or
    `hybridlab run --resume` writes results.json. ResultSetError for a file that is not JSON, a
    results.json that is not an array of records, a folder that is no result set."""
    path = os.path.join(result_dir, "results.json")
    if os.path.isfile(path):
        records = read_json(path)
        if not isinstance(records, list):
            raise ResultSetError("%s: expected an array of records, got %s" % (path, _shown(records)))
        found = [("%s: record %d" % (path, i), r) for i, r in enumerate(records)]
    elif os.path.isdir(os.path.join(result_dir, "runs")):
        runs = os.path.join(result_dir, "runs")
        # Temporary files of an interrupted write start with a dot: not records.
        found = [(os.path.join(runs, name), read_json(os.path.join(runs, name))) for name in sorted(os.listdir(runs))
                 if name.endswith(".json") and not name.startswith(".")]
    elif os.path.exists(os.path.join(result_dir, "runs")):
        raise ResultSetError("%s: is not a folder, expected the folder of the set's records (runs/<id>.json)" % os.path.join(result_dir, "runs"))
    else:
        raise ResultSetError("%s: not a result set (no results.json, no runs/)" % result_dir)
    for where, r in found:
        if not isinstance(r, dict):
            raise ResultSetError("%s: expected a run's record (an object), got %s" % (where, _shown(r)))
        migrate(r)
    if not os.path.isfile(path):
        found.sort(key=lambda wr: wr[1]["index"] if type(wr[1].get("index")) is int else -1)
    return found


def load(result_dir):
    """The records of a result set (sourced_records' without their places)."""
    return [r for _, r in sourced_records(result_dir)]


def checked_records(result_dir, table):
    """The records of a result set, each checked by record_problems against `table` (the set's
    metric table): ResultSetError naming the first problem's file and place, and the set's that
    holds none."""
    found = sourced_records(result_dir)
    if not found:
        raise ResultSetError("%s: holds no records (expected at least one run)" % (
            os.path.join(result_dir, "results.json" if os.path.isfile(os.path.join(result_dir, "results.json")) else "runs")))
    for where, r in found:
        problems = record_problems(r, table)
        if problems:
            more = " (and %d more)" % (len(problems) - 1) if len(problems) > 1 else ""
            raise ResultSetError("%s: %s%s" % (where, problems[0], more))
    return [r for _, r in found]


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


def anchor(text):
    """A fragment id for a page section: `text` with every character but letters, digits and dashes
    made a dash."""
    return "".join(c if c.isalnum() or c == "-" else "-" for c in text)


def view_name(r):
    return r["view"] + ("@%d" % r["frame"] if r["frame"] >= 0 else "")


def resolution(r):
    return "%dx%d" % (r["width"], r["height"])


def _built_in_metric_table():
    """The metric table of metrics/metric_table.h, the one place it is defined, as a result set
    carries it (experiment.json's "metric_table"): what sets written before they carried one were
    scored with."""
    header = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "metrics", "metric_table.h")
    with open(header) as f:
        text = f.read()
    table = text[text.index("kMetricTable[] = {"):]
    number = lambda v: None if v == "kUnbounded" else float(v)
    rows = re.findall(r'^\s*\{"(\w+)", "([^"]*)", Better::(Higher|Lower), ([\w.]+), ([\w.]+), "([\w.]+)", "(\w*)", (true|false), (true|false), (\d+), [\d.]+\},$',
                      table[:table.index("};")], re.M)
    if not rows:
        raise RuntimeError("no metrics in %s" % header)
    return [{"key": key, "label": label, "better": better.lower(), "range": [number(low), number(high)], "field": field,
             "colormap": colormap or None, "scored": scored == "true", "summarised": summarised == "true", "digits": int(digits)}
            for key, label, better, low, high, field, colormap, scored, summarised, digits in rows]


BUILT_IN_METRICS = _built_in_metric_table()
_FIELDS = {m["key"]: m["field"] for m in BUILT_IN_METRICS}


# experiment.json's parts that the report reads (the runner writes more): its metric table, the
# device the times were measured on, the fraction of the configured size rendered.
EXPERIMENT_SCHEMA = {
    "type": "object",
    "properties": {
        "metric_table": {"type": "array", "items": {
            "type": "object",
            "required": ["key", "label", "better", "range", "field", "colormap", "scored", "summarised", "digits"],
            "properties": {
                "key": {"type": "string", "minLength": 1},
                "label": {"type": "string", "minLength": 1},
                "better": {"enum": ["higher", "lower"]},
                "range": {"type": "array", "minItems": 2, "maxItems": 2, "items": {"type": ["number", "null"]}},
                "field": {"type": "string", "minLength": 1},
                "colormap": {"type": ["string", "null"]},
                "scored": {"type": "boolean"},
                "summarised": {"type": "boolean"},
                "digits": {"type": "integer", "minimum": 0, "maximum": 15},
            }}},
        "device": {"type": ["object", "null"], "additionalProperties": {"type": ["string", "number", "boolean", "null"]}},
        "resolution_scale": {"type": "number", "exclusiveMinimum": 0, "maximum": 1},
    },
}


def experiment(result_dir):
    """A result set's experiment.json, checked where the report reads it (EXPERIMENT_SCHEMA); {}
    for a set without one. ResultSetError naming the file and the first problem."""
    path = os.path.join(result_dir, "experiment.json")
    if not os.path.exists(path):
        return {}
    e = read_json(path)
    problems = _problems(e, EXPERIMENT_SCHEMA)
    if not problems and e.get("metric_table") and not any(m["scored"] for m in e["metric_table"]):
        problems = ["$.metric_table: expected a scored metric (the verdict and the charts rank by them), got none"]
    if problems:
        raise ResultSetError("%s: %s" % (path, problems[0]))
    return e


def metric_table(result_dir):
    """The metrics a result set was scored with, in the order tables list them: experiment.json's
    "metric_table" (the runner writes it), else the built-in table. Each is a dict with "key",
    "label", "better" ("higher" or "lower"), "range" ([low, high], None where unbounded), "field",
    "colormap" (None without an error map), "scored" (the verdict ranks by it) and "summarised"
    (summary tables show it) and "digits" (the decimals tables show)."""
    return experiment(result_dir).get("metric_table") or BUILT_IN_METRICS


def summarised(table):
    """The metrics of `table` that summary tables show."""
    return [m for m in table if m["summarised"]]


def higher_is_better(m):
    return m["better"] == "higher"


def metric_cell(m, value, missing="-"):
    """A table cell of metric `m`'s `value`, at its decimals."""
    return fmt(value, "%%.%df" % m["digits"], missing)


def best_value(m):
    """The value of an image equal to its reference (the best end of the range); None where unbounded."""
    return m["range"][1] if higher_is_better(m) else m["range"][0]


def metric(r, region, name):
    """The value of metric `name` (a key of the metric table) of a record on 'whole' or 'masked';
    None if absent (the region, or the metric: a config's `metrics` may leave it out, and older
    result sets lack the metrics added since). A metric's value lies at its field (a dotted path)
    in the region's scores; a metric added outside the built-in table has its key for field."""
    value = r["metrics"].get(region)
    for part in _FIELDS.get(name, name).split("."):
        if not isinstance(value, dict) or part not in value:
            return None
        value = value[part]
    return value


def fmt(value, spec="%.3f", missing="-"):
    """A table cell: `value` formatted by `spec`, or `missing` where the run has no such value."""
    return missing if value is None else spec % value


def _stage_vocabulary():
    """The stage vocabulary, in a frame's order: (name, meaning) pairs from techniques/stage_names.h,
    the one place it is defined."""
    header = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "techniques", "stage_names.h")
    with open(header) as f:
        text = f.read()
    table = text[text.index("kStageNames[] = {"):]
    names = re.findall(r'^\s*\{"([a-z_]+)", "((?:[^"\\]|\\.)*)"\},$', table[:table.index("};")], re.M)
    if not names:
        raise RuntimeError("no stage names in %s" % header)
    return names


STAGE_VOCABULARY = _stage_vocabulary()
STAGE_KINDS = [name for name, _ in STAGE_VOCABULARY]

# The stages of the rasterizer's frame (techniques/shared/raster_stages.h) but a technique's own
# passes (ssr, lens.draw): the "raster" time of the papers' tables.
RASTERIZER_STAGES = ("shadow_maps", "gbuffer", "gbuffer.upload", "heuristic.visible_pixels", "lighting", "readback", "overhead", "raster")


def stage_kind(name):
    """The kind of work a stage is charted under: its name before the first dot."""
    return name.split(".")[0]


def stages(r):
    """A record's median stage times (ms) by name."""
    return {name: s["median"] for name, s in r["stages"].items()}


def stage_kinds(r):
    """A record's median stage times (ms) summed by kind of work (stage_kind)."""
    out = {}
    for name, ms in stages(r).items():
        out[stage_kind(name)] = out.get(stage_kind(name), 0.0) + ms
    return out


def kind_order(kinds):
    """Kinds of work in a frame's order (the vocabulary's), names outside it (old result sets') last."""
    return sorted(kinds, key=lambda k: (STAGE_KINDS.index(k) if k in STAGE_KINDS else len(STAGE_KINDS), k))


def stage(r, name, missing=None):
    """The median time (ms) of a record's stage `name` (exactly that stage, not its details);
    `missing` if the technique has no such stage."""
    return stages(r).get(name, missing)


def raster_ms(r, missing=None):
    """The median time (ms) of a record's rasterizer frame: the sum of its RASTERIZER_STAGES;
    `missing` without any (no rasterizer)."""
    own = [ms for name, ms in stages(r).items() if name in RASTERIZER_STAGES]
    return sum(own) if own else missing


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
    result set's rows; exits with a message naming the folder when it holds no runs, or the file
    that is not a result set's (ResultSetError)."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("result_dir")
    ap.add_argument("--out", help="write the table(s) (Markdown) here as well as to standard output")
    for args, kwargs in extra_arguments:
        ap.add_argument(*args, **kwargs)
    a = ap.parse_args()
    try:
        rows = load(a.result_dir)
    except ResultSetError as e:
        sys.exit("%s: %s" % (name, e))
    if not rows:
        sys.exit("%s: %s has no runs" % (name, a.result_dir))
    if not os.path.isfile(os.path.join(a.result_dir, "results.json")):
        sys.stderr.write("%s: no results.json (its runner has not finished): reading the %d records in %s\n" % (
            a.result_dir, len(rows), os.path.join(a.result_dir, "runs")))
    return a, rows


def device_summary(d):
    """One line for a device record (experiment.json's "device"; DESIGN.md "Experiments and results")."""
    if not d:
        return "unknown device (recorded before result sets named theirs)"
    g = lambda k: str(d.get(k, "?"))
    return "%s [%s; %s; Vulkan %s], %s x %s cores, Embree %s, TBB %s threads, LP_NUM_THREADS %s, %s, hybridlab %s" % (
        g("vulkan_device"), g("vulkan_device_type"), g("vulkan_driver"), g("vulkan_api_version"), g("cpu_model"), g("cpu_cores"),
        g("embree_version"), g("tbb_threads"), g("lp_num_threads"), g("os"), g("program_version"))


def graphics_caveat(device):
    """What a device's build does to the hybrids' times, where it is known to matter: NVIDIA's
    H100 and H200 (and GH200) are built for compute and run graphics on few of their units, which
    slows the hybrids' raster stages, and not rt_only's frame of rays alone. None for other devices."""
    if re.search(r"\bG?H[12]00\b", str((device or {}).get("vulkan_device", ""))):
        return ("An H100/H200 runs graphics on few of its units (fragment work was measured 30x slower than compute there), "
                "which handicaps the hybrids' raster stages against rt_only.")
    return None


def devices(result_dir, rows=()):
    """The devices a result set was measured on: each run's own where a merge kept them (shards from
    several devices), else experiment.json's one; [None] when the set predates device records."""
    own = []
    for r in rows:
        if "device" in r and r["device"] not in own:
            own.append(r["device"])
    return own or [experiment(result_dir).get("device")]


def resolution_scale(result_dir):
    """experiment.json's "resolution_scale" (`hybridlab run --scale`): the fraction of the configured
    sizes the set was rendered at; 1 where it does not say."""
    return float(experiment(result_dir).get("resolution_scale", 1.0))


def device_line(result_dir, rows=()):
    """The line printed under a table: the device the times were measured on, or the devices, marked
    mixed; and the fraction of the configured size the set was rendered at, where not all of it."""
    ds = devices(result_dir, rows)
    if len(ds) == 1:
        line = "Measured on: " + device_summary(ds[0])
    else:
        line = "Measured on MIXED devices (times do not compare across them): " + "; ".join(
            "(%d) %s" % (i + 1, device_summary(d)) for i, d in enumerate(ds))
    scale = resolution_scale(result_dir)
    if scale != 1.0:
        line += "; rendered at %g of the configured size (hybridlab run --scale %g)" % (scale, scale)
    caveats = [c for c in map(graphics_caveat, ds) if c]
    if caveats:
        line += ". " + caveats[0]
    return line


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


def _where(path):
    """A record's place as "$.frame_ms.median" or "$.images.debug[0]" (as the viewer's Ajv test writes it)."""
    return "$" + "".join("[%d]" % p if isinstance(p, int) else ".%s" % p for p in path)


def _describe(error):
    """One problem, "place: what", in words that name the key a missing or unexpected one is; what
    was found is quoted in part (_shown)."""
    where, value, instance = _where(error.absolute_path), error.validator_value, error.instance
    if error.validator == "required":
        missing = [k for k in value if isinstance(instance, dict) and k not in instance]
        return "%s: missing required '%s'" % (where, missing[0] if missing else value)
    if error.validator == "additionalProperties" and isinstance(instance, dict):
        known = error.schema.get("properties", {})
        return "%s: unexpected '%s'" % (where, _cut(", ".join(sorted(k for k in instance if k not in known)), 80))
    if error.validator == "type":
        return "%s: expected %s, got %s" % (where, " or ".join(value if isinstance(value, list) else [value]), _shown(instance))
    if error.validator == "minimum":
        return "%s: %s is below the minimum %s" % (where, instance, value)
    if error.validator == "exclusiveMinimum":
        return "%s: expected a number above %s, got %s" % (where, value, instance)
    if error.validator == "maximum":
        return "%s: %s is above the maximum %s" % (where, instance, value)
    if error.validator == "maxLength":
        return "%s: expected at most %d characters, got %d (%s)" % (where, value, len(instance), _shown(instance))
    if error.validator in ("oneOf", "anyOf") and error.context:
        # The alternative that came nearest, in its own words.
        return _describe(jsonschema.exceptions.best_match(error.context))
    if error.validator in ("enum", "const"):
        return "%s: expected one of %s, got %s" % (where, _shown(value, 80), _shown(instance))
    return "%s: %s" % (where, error.message[:200])


def _problems(instance, schema):
    """Every way `instance` breaks `schema` ("place: what"), in the order of their places."""
    errors = sorted(jsonschema.Draft202012Validator(schema).iter_errors(instance), key=lambda e: [str(p) for p in e.absolute_path])
    return [_describe(e) for e in errors]


_schema = None


def schema_problems(record):
    """Every way a record breaks the schema ("place: what"), in the order of their places; [] when valid."""
    global _schema
    if _schema is None:
        with open(SCHEMA_PATH) as f:
            _schema = json.load(f)
    return _problems(record, _schema)


# The times a record holds as a median with its spread: the report draws each median with a bar
# over its interval (or its runs' range) on a log axis.
TIME_SPREADS = (("frame_ms",), ("timing", "cpu_ms"), ("timing", "device_ms"))


def _spread_problems(r):
    problems = []
    for path in TIME_SPREADS:
        s = r
        for key in path:
            s = s.get(key) if isinstance(s, dict) else None
        if not isinstance(s, dict):
            continue
        order = [k for k in ("min", "ci_low", "median", "ci_high", "max") if k in s]
        if any(s[a] > s[b] for a, b in zip(order, order[1:])):
            problems.append("%s: expected %s in that order, got %s" % (_where(path), " <= ".join(order), ", ".join("%s %g" % (k, s[k]) for k in order)))
    return problems


def _metric_problems(r, table):
    """Where a metric of `table` lies in a region's scores and holds something other than a number."""
    problems = []
    for region in ("whole", "masked"):
        for m in table:
            value = metric(r, region, m["key"])
            if value is not None and (type(value) not in (int, float)):
                problems.append("%s: expected a number (metric '%s' of the metric table), got %s" % (
                    _where(["metrics", region] + _FIELDS.get(m["key"], m["key"]).split(".")), m["key"], _shown(value)))
    return problems


def record_problems(r, table=None):
    """Every way a record breaks the schema or what the report relies on beyond it: a version this
    program reads, each time's median inside its interval and its runs' range, each metric of
    `table` (the set's metric table; by default the built-in one) a number where present."""
    problems = schema_problems(r)
    if problems:
        return problems
    if r["schema_version"] > SCHEMA_VERSION:
        return ["$.schema_version: %d is newer than this program reads (up to %d): report it with a newer hybridlab" % (
            r["schema_version"], SCHEMA_VERSION)]
    return _spread_problems(r) + _metric_problems(r, table or BUILT_IN_METRICS)


def results_problems(records):
    """The problems of every record of a results.json, each prefixed by the record's index."""
    if not isinstance(records, list):
        return ["results.json: expected an array of records"]
    return ["record %d: %s" % (i, p) for i, r in enumerate(records) for p in schema_problems(r)]


def main(argv):
    if len(argv) != 2:
        print("usage: results.py RESULT_DIR", file=sys.stderr)
        return 2
    try:
        found = results_problems(load(argv[1]))
    except ResultSetError as e:
        found = [str(e)]
    for p in found:
        print(p)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
