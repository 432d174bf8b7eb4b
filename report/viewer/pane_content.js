// What one pane shows: the reference or a technique setting at the current frame, and one of its
// layers: the image; its difference (absolute, relative, FLIP) against the image of another pane,
// or against the reference where none is chosen; the runner's SSIM and HDR-FLIP maps, drawn from
// their values (read back from the map's colours) with the viewer's legend; its debug images.

import { REFERENCE } from './result_set.js';
import { DIFFERENCES } from './difference.js';

// The runner's maps that the viewer does not compute itself (|A - B| and FLIP it does, against any
// pane), each against the reference.
export const RUNNER_MAPS = [
  { map: 'ssim', name: "SSIM map (the runner's, against the reference)" },
  { map: 'flip_hdr', name: "HDR-FLIP map (the runner's, against the reference)" },
];

// Every layer of a pane's run (the reference has its image and the differences), in the order E
// cycles through them: the image, the differences, the runner's maps, then the debug images.
export function layersOf(run, comparable) {
  const layers = [{ id: 'image', name: 'image' }];
  if (comparable) {
    for (const d of DIFFERENCES) layers.push({ id: d.id, name: d.name, difference: d.id, colormap: 'magma', range: [0, 1], what: 'FLIP (LDR)' });
  }
  for (const m of RUNNER_MAPS) {
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
    const layers = layersOf(null, comparable);
    return {
      title: 'reference (whitted)', colour: null, parameters: results.referenceParameters, frameMs: any.reference_ms, stages: null,
      metrics: null, run: null, file: any.reference, preview: any.reference_png, layers, layer: layers.find((l) => l.id === pane.layer) || layers[0],
      width: any.width, height: any.height,
    };
  }
  const run = results.run(sel, frame, pane.variant);
  if (!run) return null;
  const layers = layersOf(run, comparable);
  return {
    title: run.label, colour: results.colours[run.variant] || null, parameters: run.parameters_text, frameMs: run.frame_ms,
    stages: run.stages, metrics: run.metrics, run, file: run.image, preview: run.png, layers, layer: layers.find((l) => l.id === pane.layer) || layers[0],
    width: run.width, height: run.height,
  };
}

// The layer after `current` among the image and the differences (E).
export function nextErrorLayer(current) {
  const cycle = ['image', ...DIFFERENCES.map((d) => d.id)];
  return cycle[(cycle.indexOf(current) + 1) % cycle.length];
}
