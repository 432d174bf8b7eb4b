// The result set as the viewer reads it: the records of results.json (what the runner wrote: the
// images' paths are the result set's own) and the report's settings.json (title, the report's
// colour of each setting, the settings not applicable to a scene, the metric table, the steps that
// read older records as current ones), grouped into scenes, sizes, views, frames and technique
// settings.

import { scoresOf } from './metric_readout.js';

export const REFERENCE = 'reference';

const keyOf = (scene, size, view, frame, variant) => [scene, size, view, frame, variant].join('\u0001');

function distinct(values) {
  return [...new Set(values)];
}

// Numbers inside names by value: "budget=5000" before "budget=20000".
const naturalOrder = new Intl.Collator('en', { numeric: true }).compare;

// `values` (a record's stages or counters) with its keys renamed; values that meet under one name
// add up, number by number.
function renamed(values, rename, prefixes) {
  const out = {};
  for (let [key, value] of Object.entries(values)) {
    key = rename[key] ?? key;
    for (const [old, now] of Object.entries(prefixes)) if (key.startsWith(old)) key = now + key.slice(old.length);
    if (!(key in out)) out[key] = value;
    else if (typeof value === 'object') out[key] = Object.fromEntries(Object.entries(value).map(([k, v]) => [k, (out[key][k] ?? 0) + v]));
    else out[key] += value;
  }
  return out;
}

// The record as the current schema_version has it: the one place old result sets' names are read,
// each step of experiments/results.migrations.json (settings.json's `migrations`) in turn from the
// record's version (none: 1), as report/results.py migrate() does.
export function migrated(record, steps) {
  let version = record.schema_version ?? 1;
  const r = { ...record };
  for (const step of steps) {
    if (step.from < version) continue;
    for (const field of new Set([...Object.keys(step.rename || {}), ...Object.keys(step.rename_prefixes || {})])) {
      if (r[field]) r[field] = renamed(r[field], (step.rename || {})[field] || {}, (step.rename_prefixes || {})[field] || {});
    }
    version = step.to;
  }
  r.schema_version = version;
  return r;
}

// A technique with its parameter set, named as the report names it (report/results.py variant()).
export function variantOf(r) {
  return r.label + (r.parameters_text ? ` [${r.parameters_text}]` : '');
}

// One run as the viewer shows it; `base`: the result set's folder as seen from viewer.html.
function runOf(r, base, notApplicable, metricTable) {
  const file = (path) => encodeURI(base + path);
  const size = `${r.width}x${r.height}`;
  const maps = {};
  for (const [name, m] of Object.entries((r.images.maps && r.metrics.maps) || {})) {
    maps[name] = { file: file(`${r.images.maps}/${m.file}`), colormap: m.colormap, range: m.range };
  }
  const variant = variantOf(r);
  return {
    id: r.id, index: r.index, scene: r.scene, size, width: r.width, height: r.height, view: r.view, frame: r.frame,
    technique: r.technique, label: r.label, variant, parameters_text: r.parameters_text,
    image: file(r.images.exr), reference: file(r.reference.exr), png: file(r.images.png), reference_png: file(r.reference.png), frame_ms: r.frame_ms.median, reference_ms: r.reference.frame_ms,
    stages: Object.fromEntries(Object.entries(r.stages || {}).map(([k, s]) => [k, s.median])),
    scores: scoresOf(r, metricTable), temporal: r.temporal_error ?? null,
    maps,
    debug: Object.fromEntries(Object.entries(r.images.debug || {}).map(([k, v]) => [k, file(v)])),
    not_applicable: notApplicable.get(keyOf(r.scene, size, '', '', variant)) || null,
  };
}

export class ResultSet {
  constructor(records, settings) {
    this.title = settings.title;
    this.colours = settings.colours || {};
    this.colormaps = settings.colormaps;
    this.referenceParameters = settings.reference_parameters;
    this.metricTable = settings.metrics;
    const base = settings.result_set ? `${settings.result_set}/` : '';
    const notApplicable = new Map((settings.not_applicable || []).map(([scene, size, name, why]) => [keyOf(scene, size, '', '', name), why]));
    this.runs = records.map((r) => runOf(migrated(r, settings.migrations || []), base, notApplicable, this.metricTable));
    this.byId = new Map(this.runs.map((r) => [r.id, r]));
    this.byKey = new Map(this.runs.map((r) => [keyOf(r.scene, r.size, r.view, r.frame, r.variant), r]));
  }

  scenes() {
    return distinct(this.runs.map((r) => r.scene));
  }

  sizes(scene) {
    return distinct(this.runs.filter((r) => r.scene === scene).map((r) => r.size));
  }

  views(scene, size) {
    return distinct(this.runs.filter((r) => r.scene === scene && r.size === size).map((r) => r.view));
  }

  // The runs of one scene, size and view: what the frame slider and the technique choices span.
  group(sel) {
    return this.runs.filter((r) => r.scene === sel.scene && r.size === sel.size && r.view === sel.view);
  }

  frames(sel) {
    return distinct(this.group(sel).map((r) => r.frame)).sort((a, b) => a - b);
  }

  variants(sel) {
    return distinct(this.group(sel).map((r) => r.variant)).sort(naturalOrder);
  }

  // One setting per technique, techniques in the order they first appear: the one run with the
  // technique's defaults (no parameters) where there is one, else the first in name order. Settings
  // the report found not applicable to the scene (they change nothing there) are left out.
  defaultVariants(sel) {
    const byTechnique = new Map();
    for (const r of this.group(sel)) {
      if (r.not_applicable) continue;
      if (!byTechnique.has(r.technique)) byTechnique.set(r.technique, new Set());
      byTechnique.get(r.technique).add(r.variant);
    }
    return [...byTechnique.values()].map((set) => {
      const plain = this.group(sel).find((r) => set.has(r.variant) && !r.parameters_text);
      return plain ? plain.variant : [...set].sort(naturalOrder)[0];
    });
  }

  run(sel, frame, variant) {
    return this.byKey.get(keyOf(sel.scene, sel.size, sel.view, frame, variant));
  }

  // Any run of the frame carries the reference it was scored against (one per camera and size).
  referenceRun(sel, frame) {
    return this.group(sel).find((r) => r.frame === frame);
  }
}
