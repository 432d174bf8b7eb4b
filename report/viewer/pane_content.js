// What one pane shows: the reference or a technique variant at the current frame, and one of its
// layers (the image, an error map, a debug image), with the numbers for its overlay.

import { REFERENCE } from './result_set.js';

export const ERROR_MAPS = [
  { id: 'diff', name: 'absolute difference' },
  { id: 'ssim', name: 'SSIM map' },
  { id: 'flip', name: 'FLIP (LDR) map' },
  { id: 'flip_hdr', name: 'HDR-FLIP map' },
];

// Every layer of a run, in the order E cycles through the error maps: the image, the error maps
// it has, then its debug images (whatever the technique wrote: heuristic mask, path mask, ...).
export function layersOf(run) {
  const layers = [{ id: 'image', name: 'image', file: run.image }];
  for (const m of ERROR_MAPS) {
    const map = run.maps && run.maps[m.id];
    if (map) layers.push({ id: m.id, name: m.name, file: map.file, legend: map });
  }
  for (const [name, file] of Object.entries(run.debug || {})) layers.push({ id: 'debug:' + name, name: 'debug: ' + name, file });
  return layers;
}

export function paneContent(results, sel, frame, pane) {
  if (pane.variant === REFERENCE) {
    const any = results.referenceRun(sel, frame);
    if (!any) return null;
    return {
      title: 'reference (whitted)',
      parameters: results.referenceParameters,
      frameMs: any.reference_ms,
      stages: null,
      metrics: null,
      run: null,
      layers: [{ id: 'image', name: 'image', file: any.reference }],
      layer: { id: 'image', name: 'image', file: any.reference },
      width: any.width,
      height: any.height,
    };
  }
  const run = results.run(sel, frame, pane.variant);
  if (!run) return null;
  const layers = layersOf(run);
  return {
    title: run.label,
    parameters: run.parameters_text,
    frameMs: run.frame_ms,
    stages: run.stages,
    metrics: run.metrics,
    run,
    layers,
    layer: layers.find((l) => l.id === pane.layer) || layers[0],
    width: run.width,
    height: run.height,
  };
}

// The layer after `current` among the image and the error maps (E).
export function nextErrorLayer(current) {
  const cycle = ['image', ...ERROR_MAPS.map((m) => m.id)];
  const i = cycle.indexOf(current);
  return cycle[(i + 1) % cycle.length];
}
