// Linear images for display, after tev and JERI: an exposure (EV: the linear values times 2^EV)
// and a display transform take the EXR's linear RGB to the 8-bit colours drawn. report.py writes
// each run's and reference's linear RGB as a classic script (viewer/linear/N.js, half floats, so
// that it loads from the file system) that calls window.hybridlabLinear; loaded when first needed.

import { scriptLoader } from './script_data.js';

export const DISPLAY_TRANSFORMS = [
  { id: 'srgb', name: 'sRGB, clipped (as the PNGs)' },
  { id: 'aces', name: 'ACES filmic (Narkowicz 2015)' },
  { id: 'reinhard', name: 'Reinhard, x / (1 + x)' },
  { id: 'linear', name: 'linear, clipped (no curve)' },
];
export const DEFAULT_TRANSFORM = 'srgb';

function halfToFloat(h) {
  const s = h & 0x8000 ? -1 : 1;
  const e = (h >> 10) & 0x1f;
  const m = h & 0x3ff;
  if (e === 0) return s * m * 2 ** -24;
  if (e === 31) return m ? NaN : s * Infinity;
  return s * (1 + m / 1024) * 2 ** (e - 15);
}

// The linear RGB of the image shown as `file` (a PNG path of the manifest); null without a script.
// Its script calls window.hybridlabLinear(file, width, height, base64 of half floats).
export const linearData = scriptLoader('hybridlabLinear', (width, height, base64) => {
  const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
  const halves = new Uint16Array(bytes.buffer);
  const rgb = new Float32Array(halves.length);
  for (let i = 0; i < halves.length; i += 1) rgb[i] = halfToFloat(halves[i]);
  return { width, height, rgb };
});

export function linearAt(data, x, y) {
  if (!data || x < 0 || y < 0 || x >= data.width || y >= data.height) return null;
  const i = 3 * (y * data.width + x);
  return [data.rgb[i], data.rgb[i + 1], data.rgb[i + 2]];
}

const srgbEncode = (c) => (c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055);
const clip = (c) => Math.min(1, Math.max(0, c));

// One linear channel value to display [0, 1], after the exposure.
export function displayChannel(v, ev, transform) {
  const x = Math.max(0, v * 2 ** ev);
  switch (transform) {
    case 'aces':
      // Narkowicz's fit of the ACES filmic curve, then the sRGB encoding.
      return srgbEncode(clip((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)));
    case 'reinhard':
      return srgbEncode(x / (1 + x));
    case 'linear':
      return clip(x);
    default:
      return srgbEncode(clip(x));
  }
}

export function displayRgb(rgb, ev, transform) {
  return rgb.map((v) => Math.round(255 * displayChannel(v, ev, transform)));
}

// The PNG as written shows the default transform at EV 0: no need to draw it again.
export function isIdentity(ev, transform) {
  return ev === 0 && transform === DEFAULT_TRANSFORM;
}

const drawn = new Map(); // file|ev|transform -> data URL

// A data: URL of the image under the exposure and transform (a data: URL, unlike a file:// image,
// can be read back by a canvas).
export function drawLinear(file, data, ev, transform) {
  const key = `${file}|${ev}|${transform}`;
  if (!drawn.has(key)) {
    const canvas = document.createElement('canvas');
    canvas.width = data.width;
    canvas.height = data.height;
    const ctx = canvas.getContext('2d');
    const img = ctx.createImageData(data.width, data.height);
    const lut = new Map();
    for (let p = 0, n = data.width * data.height; p < n; p += 1) {
      for (let c = 0; c < 3; c += 1) {
        const v = data.rgb[3 * p + c];
        let d = lut.get(v);
        if (d === undefined) {
          d = Math.round(255 * displayChannel(v, ev, transform));
          lut.set(v, d);
        }
        img.data[4 * p + c] = d;
      }
      img.data[4 * p + 3] = 255;
    }
    ctx.putImageData(img, 0, 0);
    drawn.set(key, canvas.toDataURL());
  }
  return drawn.get(key);
}
