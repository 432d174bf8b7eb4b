// The result set as the viewer reads it: the manifest that report.py writes (one entry per run,
// paths relative to viewer.html), grouped into scenes, sizes, views, frames and technique variants.

export const REFERENCE = 'reference';

const keyOf = (scene, size, view, frame, variant) => [scene, size, view, frame, variant].join('\u0001');

function distinct(values) {
  return [...new Set(values)];
}

// Numbers inside names by value: "budget=5000" before "budget=20000".
const naturalOrder = new Intl.Collator('en', { numeric: true }).compare;

export class ResultSet {
  constructor(manifest) {
    this.title = manifest.title;
    this.runs = manifest.runs;
    this.colormaps = manifest.colormaps;
    this.pixelScripts = manifest.pixel_scripts;
    this.linearScripts = manifest.linear_scripts || {};
    this.referenceParameters = manifest.reference_parameters;
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
      const key = r.technique || r.label;
      if (!byTechnique.has(key)) byTechnique.set(key, new Set());
      byTechnique.get(key).add(r.variant);
    }
    return [...byTechnique.entries()].map(([, set]) => {
      const names = [...set].sort();
      const plain = this.group(sel).find((r) => set.has(r.variant) && !r.parameters_text);
      return plain ? plain.variant : names[0];
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
