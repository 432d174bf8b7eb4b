// What one pane shows: the reference or a technique setting at the current frame, and one of its
// layers: the image; its difference (absolute, relative, FLIP) against the image of another pane,
// or against the reference where none is chosen; the runner's maps (SSIM, HDR-FLIP), drawn from
// their values (read back from the map's colours) with the viewer's legend; its debug images.

import { REFERENCE } from './result_set.js';
import { DIFFERENCES } from './difference.js';

// The metrics whose maps the viewer computes itself, against any pane (flip.js; |A - B| is no
// metric's): the runner's maps of the others in the metric table are layers, each against the
// reference.
const COMPUTED_HERE = new Set(['flip']);

export function runnerMaps(metricTable) {
  return metricTable.filter((m) => m.colormap && !COMPUTED_HERE.has(m.key))
    .map((m) => ({ map: m.key, name: `${m.label} map (the runner's, against the reference)` }));
}

// Every layer of a pane's run (the reference has its image and the differences), in the order E
// cycles through them: the image, the differences, the runner's maps, then the debug images.
export function layersOf(run, comparable, metricTable) {
  const layers = [{ id: 'image', name: 'image' }];
  if (comparable) {
    for (const d of DIFFERENCES) layers.push({ id: d.id, name: d.name, difference: d.id, colormap: 'magma', range: [0, 1], what: 'FLIP (LDR)' });
  }
  for (const m of runnerMaps(metricTable)) {
    const file = run && run.maps[m.map];
    if (file) layers.push({ id: 'map:' + m.map, name: m.name, file: file.file, colormap: file.colormap, range: file.range, what: m.map });
  }
  for (const [name, file] of Object.entries((run && run.debug) || {})) layers.push({ id: 'debug:' + name, name: 'debug: ' + name, file });
  return layers;
}

// `pane`: {variant, layer, against}; `comparable`: whether it has an image to be differenced with
// (another pane chosen, or the reference for a technique's pane).
export function paneContent(results, sel, frame, pane, comparable) {
  if (pane.variant === REFERENCE) {
    const any = results.referenceRun(sel, frame);
    if (!any) return null;
    const layers = layersOf(null, comparable, results.metricTable);
    return {
      title: 'reference (whitted)', colour: null, parameters: results.referenceParameters, frameMs: any.reference_ms, stages: null,
      scores: null, temporal: null, run: null, file: any.reference, preview: any.reference_png, layers, layer: layers.find((l) => l.id === pane.layer) || layers[0],
      width: any.width, height: any.height,
    };
  }
  const run = results.run(sel, frame, pane.variant);
  if (!run) return null;
  const layers = layersOf(run, comparable, results.metricTable);
  return {
    title: run.label, colour: results.colours[run.variant] || null, parameters: run.parameters_text, frameMs: run.frame_ms,
    stages: run.stages, scores: run.scores, temporal: run.temporal, run, file: run.image, preview: run.png, layers, layer: layers.find((l) => l.id === pane.layer) || layers[0],
    width: run.width, height: run.height,
  };
}

// The layer after `current` among the image and the differences (E).
export function nextErrorLayer(current) {
  const cycle = ['image', ...DIFFERENCES.map((d) => d.id)];
  return cycle[(cycle.indexOf(current) + 1) % cycle.length];
}
