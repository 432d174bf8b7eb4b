// How values become the colours drawn, after tev and JERI. Linear images (and their differences)
// go through an exposure (EV: the values times 2^EV) and a display transform, or through false
// colour; one-value images (FLIP, the runner's error maps) through their colour map over their
// range, with the viewer's legend; a PNG's display values are drawn as stored.

export const DISPLAY_TRANSFORMS = [
  { id: 'srgb', name: 'sRGB, clipped (as the PNGs)' },
  { id: 'aces', name: 'ACES filmic (Narkowicz 2015)' },
  { id: 'reinhard', name: 'Reinhard, x / (1 + x)' },
  { id: 'linear', name: 'linear, clipped (no curve)' },
  { id: 'false', name: 'false colour: mean of R, G, B on viridis, 0 to 2^-EV' },
];
export const DEFAULT_TRANSFORM = 'srgb';
export const FALSE_COLOUR_MAP = 'viridis';

export const srgbEncode = (c) => (c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055);
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

// The 8-bit level a linear value is drawn at: round(255 displayChannel(v)) by a binary search among
// the 255 values where the level changes (displayChannel rises with v), a fraction of the time of
// the curve itself, which a megapixel image would evaluate three million times.
function levels(ev, transform) {
  const x = (v) => displayChannel(v, ev, transform);
  const steps = [];
  for (let k = 1; k < 256; k += 1) {
    // The smallest v drawn at level k or above: bisection on the rising curve.
    let lo = 0;
    let hi = 2 ** (EV_SEARCH - ev);
    if (Math.round(255 * x(hi)) < k) {
      steps.push(Infinity);
      continue;
    }
    for (let i = 0; i < 400; i += 1) {
      const mid = 0.5 * (lo + hi);
      if (mid === lo || mid === hi) break; // adjacent numbers: hi is the threshold
      if (Math.round(255 * x(mid)) >= k) hi = mid;
      else lo = mid;
    }
    steps.push(hi);
  }
  return (v) => {
    let a = 0;
    let b = 255;
    while (a < b) {
      const m = (a + b) >> 1;
      if (v >= steps[m]) a = m + 1;
      else b = m;
    }
    return a;
  };
}
const EV_SEARCH = 40;

// The level of every float whose top 16 bits are i, where they all share one (-1 where the level
// changes inside, about one bucket in a hundred, left to the search): one look-up a value.
function bucketLevels(level) {
  const table = new Int16Array(65536);
  const word = new Uint32Array(1);
  const float = new Float32Array(word.buffer);
  const at = (b) => {
    word[0] = b;
    const v = float[0];
    return Number.isNaN(v) ? 0 : level(v);
  };
  for (let i = 0; i < 65536; i += 1) {
    const low = at(i << 16 >>> 0);
    table[i] = low === at(((i << 16) | 0xffff) >>> 0) ? low : -1;
  }
  return table;
} // values up to 2^40 (times the exposure) are searched; above, the curves are flat

// The colour `table` (256 RGB entries) gives value v on [lo, hi].
export function mapColour(v, table, lo, hi) {
  const t = hi > lo ? (v - lo) / (hi - lo) : 0;
  return table[Math.max(0, Math.min(table.length - 1, Math.round(t * (table.length - 1))))];
}

// How an image is drawn: { ev, transform } for linear values, { colormap, range } for one value a
// pixel. `tables`: the colour maps by name.
export function pixelColour(values, image, how, tables) {
  if (image.kind === 'scalar') return mapColour(values[0], tables[how.colormap], how.range[0], how.range[1]);
  if (image.kind === 'display') return values.map((v) => Math.round(255 * v));
  if (how.transform === 'false') {
    const mean = values.reduce((a, b) => a + b, 0) / values.length;
    return mapColour(mean * 2 ** how.ev, tables[FALSE_COLOUR_MAP], 0, 1);
  }
  return values.map((v) => Math.round(255 * displayChannel(v, how.ev, how.transform)));
}

const levelTables = new Map(); // "ev transform" -> { level, byBits }

// The image's colours as ImageData.
export function drawImage(image, how, tables) {
  const out = new ImageData(image.width, image.height);
  const n = image.width * image.height;
  const c = image.channels;
  const d = image.data;
  const px = out.data;
  if (image.kind === 'linear' && how.transform !== 'false') {
    const key = `${how.ev} ${how.transform}`;
    if (!levelTables.has(key)) {
      const level = levels(how.ev, how.transform);
      levelTables.set(key, { level, byBits: bucketLevels(level) });
    }
    const { level, byBits } = levelTables.get(key);
    const bits = new Uint32Array(d.buffer, d.byteOffset, d.length);
    for (let p = 0; p < n; p += 1) {
      for (let k = 0; k < 3; k += 1) {
        const known = byBits[bits[3 * p + k] >>> 16];
        px[4 * p + k] = known >= 0 ? known : level(d[3 * p + k]);
      }
      px[4 * p + 3] = 255;
    }
    return out;
  }
  const values = new Array(c);
  for (let p = 0; p < n; p += 1) {
    for (let k = 0; k < c; k += 1) values[k] = d[c * p + k];
    const colour = pixelColour(values, image, how, tables);
    px[4 * p] = colour[0];
    px[4 * p + 1] = colour[1];
    px[4 * p + 2] = colour[2];
    px[4 * p + 3] = 255;
  }
  return out;
}

// The legend of a drawing: { colormap, low, high, what } where it uses a colour map, else null.
export function legendOf(image, how) {
  if (image.kind === 'scalar') return { colormap: how.colormap, low: how.range[0], high: how.range[1], what: how.what };
  if (image.kind === 'linear' && how.transform === 'false') {
    return { colormap: FALSE_COLOUR_MAP, low: 0, high: 2 ** -how.ev, what: 'mean of R, G, B' };
  }
  return null;
}

export function legendHtml(legend, tables, escape) {
  const table = tables[legend.colormap];
  const stops = table.filter((_, i) => i % 16 === 0 || i === table.length - 1).map((c) => `rgb(${c[0]},${c[1]},${c[2]})`);
  const fmt = (v) => Number(v.toPrecision(3)).toString();
  return `<div class="legend"><div class="bar" style="background:linear-gradient(to right,${stops.join(',')})"></div>`
    + `<div class="ends"><span class="lo">${fmt(legend.low)}</span><span>${escape(legend.what)}</span><span class="hi">${fmt(legend.high)}</span></div></div>`;
}

// The values of one of the runner's error maps (a PNG coloured by `table` over `range`, with its
// legend drawn below the map's first `height` rows): each colour's nearest entry of the table,
// scaled to the range, so that the viewer draws the map with its own legend alone. The values are
// as precise as the map's 256 colours.
export function runnerMapValues(png, table, range, height) {
  const rows = Math.min(height, png.height);
  const data = new Float32Array(png.width * rows);
  const byColour = new Map();
  for (let p = 0; p < data.length; p += 1) {
    const rgb = [0, 1, 2].map((k) => Math.round(255 * png.data[3 * p + k]));
    const packed = (rgb[0] << 16) | (rgb[1] << 8) | rgb[2];
    let v = byColour.get(packed);
    if (v === undefined) {
      let best = 0;
      let bestDistance = Infinity;
      table.forEach((c, i) => {
        const d = (c[0] - rgb[0]) ** 2 + (c[1] - rgb[1]) ** 2 + (c[2] - rgb[2]) ** 2;
        if (d < bestDistance) {
          bestDistance = d;
          best = i;
        }
      });
      v = range[0] + ((range[1] - range[0]) * best) / (table.length - 1);
      byColour.set(packed, v);
    }
    data[p] = v;
  }
  return { width: png.width, height: rows, channels: 1, data, kind: 'scalar' };
}
