// The difference of two panes' images, as tev shows it: per channel |A - B| (absolute), |A - B| /
// (|B| + 0.01) (relative, the 0.01 keeping black from dividing by zero), or the FLIP map of A
// against B (flip.js, on the display images). Absolute and relative differences of linear images
// are linear values (drawn with the exposure and display transform, or false colour); FLIP is one
// value a pixel in [0, 1].

import { flipMap, fromDisplay, fromLinear } from './flip.js';

export const DIFFERENCES = [
  { id: 'abs', name: '|A - B| (absolute)' },
  { id: 'rel', name: '|A - B| / (|B| + 0.01) (relative)' },
  { id: 'flip', name: 'FLIP (LDR) of A against B' },
];
export const RELATIVE_FLOOR = 0.01;

const computed = new WeakMap(); // image A -> Map(image B -> Map(mode -> difference))

export function difference(a, b, mode) {
  if (a.width !== b.width || a.height !== b.height) {
    throw new Error(`the images differ in size (${a.width}x${a.height} and ${b.width}x${b.height})`);
  }
  if (!computed.has(a)) computed.set(a, new WeakMap());
  const byB = computed.get(a);
  if (!byB.has(b)) byB.set(b, new Map());
  const byMode = byB.get(b);
  if (!byMode.has(mode)) byMode.set(mode, compute(a, b, mode));
  return byMode.get(mode);
}

function compute(a, b, mode) {
  if (mode === 'flip') {
    const linear = a.kind === 'linear' && b.kind === 'linear' ? fromLinear : fromDisplay;
    return { width: a.width, height: a.height, channels: 1, data: flipMap(a, b, linear), kind: 'scalar' };
  }
  const data = new Float32Array(a.data.length);
  for (let i = 0; i < data.length; i += 1) {
    const d = Math.abs(a.data[i] - b.data[i]);
    data[i] = mode === 'rel' ? d / (Math.abs(b.data[i]) + RELATIVE_FLOOR) : d;
  }
  return { width: a.width, height: a.height, channels: a.channels, data, kind: a.kind === 'display' ? 'display' : 'linear' };
}
