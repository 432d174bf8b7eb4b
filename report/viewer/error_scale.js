// Error maps on one scale. The runner colours each run's absolute-difference map over that run's
// own range, so colours cannot be compared across panes; here a map is recoloured over the largest
// range of its metric among the runs of the scene and size (chosen once per scene and metric), the
// scale its legend then shows. SSIM, FLIP and HDR-FLIP maps already share their fixed range [0, 1].

import { mapValue } from './pixels.js';

// The shared range of `metric`'s maps over the runs of the scene and size of `sel`.
export function sharedRange(results, sel, metric) {
  let hi = 0;
  let lo = Infinity;
  for (const r of results.runs) {
    const m = r.maps && r.maps[metric];
    if (r.scene !== sel.scene || r.size !== sel.size || !m) continue;
    lo = Math.min(lo, m.range[0]);
    hi = Math.max(hi, m.range[1]);
  }
  return lo === Infinity ? null : [lo, hi];
}

export function sameRange(a, b) {
  return a[0] === b[0] && a[1] === b[1];
}

const recoloured = new Map(); // file|range -> data URL

// A data: URL of the map `data` (ImageData coloured by `table` over `own`) coloured over `shared`,
// its first `height` rows only: the runner draws the map's own legend below the image, which would
// contradict the shared scale (the pane's legend shows that).
export function recolour(file, data, table, own, shared, height) {
  const key = `${file}|${shared.join(',')}|${height}`;
  if (!recoloured.has(key)) {
    const rows = Math.min(height, data.height);
    const canvas = document.createElement('canvas');
    canvas.width = data.width;
    canvas.height = rows;
    const ctx = canvas.getContext('2d');
    const out = ctx.createImageData(data.width, rows);
    const byColour = new Map();
    const last = table.length - 1;
    for (let i = 0; i < out.data.length; i += 4) {
      const packed = (data.data[i] << 16) | (data.data[i + 1] << 8) | data.data[i + 2];
      let c = byColour.get(packed);
      if (!c) {
        const v = mapValue([data.data[i], data.data[i + 1], data.data[i + 2]], table, own);
        const t = shared[1] > shared[0] ? (v - shared[0]) / (shared[1] - shared[0]) : 0;
        c = table[Math.max(0, Math.min(last, Math.round(t * last)))];
        byColour.set(packed, c);
      }
      out.data.set([c[0], c[1], c[2], 255], i);
    }
    ctx.putImageData(out, 0, 0);
    recoloured.set(key, canvas.toDataURL());
  }
  return recoloured.get(key);
}
