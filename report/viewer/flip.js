// LDR-FLIP (Andersson et al., "FLIP: A Difference Evaluator for Alternating Images", HPG 2020) in
// the browser, for the difference of any two panes: the same steps and constants as
// metrics/flip.cpp, which the runner scores with (its comments cite the paper and NVIDIA's
// reference code): the colour pipeline (contrast sensitivity filters in YCxCz, the RGB cube,
// Hunt-adjusted L*a*b*, HyAB, redistribution to [0, 1]) and the feature pipeline (edge and point
// detectors on the achromatic channel), combined as colour error ^ (1 - feature difference).

export const PIXELS_PER_DEGREE = 67.0; // the runner's viewing condition (metrics/flip.h)

const QC = 0.7;
const PC = 0.4;
const PT = 0.95;
const W = 0.082;
// Contrast sensitivity of A, RG and BY: a1 sqrt(pi / b1) exp(-pi^2 x^2 / b1) + the same with a2, b2.
const CSF = [
  { a1: 1.0, b1: 0.0047, a2: 0.0, b2: 1e-5 },
  { a1: 1.0, b1: 0.0053, a2: 0.0, b2: 1e-5 },
  { a1: 34.1, b1: 0.04, a2: 13.5, b2: 0.025 },
];
const LARGEST_CSF_B = 0.04;

const RGB_TO_XYZ = [
  [10135552 / 24577794, 8788810 / 24577794, 4435075 / 24577794],
  [2613072 / 12288897, 8788810 / 12288897, 887015 / 12288897],
  [1425312 / 73733382, 8788810 / 73733382, 70074185 / 73733382],
];
const WHITE = RGB_TO_XYZ.map((row) => row[0] + row[1] + row[2]);
const RGB_TO_RELATIVE_XYZ = RGB_TO_XYZ.map((row, i) => row.map((v) => v / WHITE[i]));
const RELATIVE_XYZ_TO_RGB = inverse(RGB_TO_RELATIVE_XYZ);

function inverse(m) {
  const [[a, b, c], [d, e, f], [g, h, i]] = m;
  const det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
  return [
    [(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det],
    [(f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det],
    [(d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det],
  ];
}

const apply = (m, v) => [0, 1, 2].map((r) => m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2]);

function huntAdjustedLab(rgb) {
  const d3 = (6 / 29) ** 3;
  const f = (t) => (t > d3 ? Math.cbrt(t) : t / (3 * (6 / 29) ** 2) + 4 / 29);
  const n = apply(RGB_TO_RELATIVE_XYZ, rgb);
  const fx = f(n[0]);
  const fy = f(n[1]);
  const fz = f(n[2]);
  const l = 116 * fy - 16;
  return [l, 0.01 * l * 500 * (fx - fy), 0.01 * l * 200 * (fy - fz)];
}

function hyab(p, q) {
  return Math.abs(p[0] - q[0]) + Math.hypot(p[1] - q[1], p[2] - q[2]);
}

const CMAX = hyab(huntAdjustedLab([0, 1, 0]), huntAdjustedLab([0, 0, 1])) ** QC;

function redistributedColorError(distance) {
  const e = Math.fround(Math.fround(distance) ** Math.fround(QC));
  const knee = PC * CMAX;
  return e < knee ? (PT / knee) * e : PT + ((e - knee) / (CMAX - knee)) * (1 - PT);
}

const srgbToLinear = (c) => (c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4);

// The Y, Cx and Cz planes of an image's linear RGB in [0, 1] (`linear(values)` gives it).
function ycxczPlanes(image, linear) {
  const n = image.width * image.height;
  const planes = [new Float32Array(n), new Float32Array(n), new Float32Array(n)];
  const c = image.channels;
  for (let p = 0; p < n; p += 1) {
    const rgb = c === 1 ? [image.data[p], image.data[p], image.data[p]] : [image.data[3 * p], image.data[3 * p + 1], image.data[3 * p + 2]];
    const o = apply(RGB_TO_RELATIVE_XYZ, rgb.map(linear));
    planes[0][p] = 116 * o[1] - 16;
    planes[1][p] = 500 * (o[0] - o[1]);
    planes[2][p] = 200 * (o[1] - o[2]);
  }
  return planes;
}

// One pass of `kernel` (odd length, centred) along x or y, the edge replicated.
function filterAlong(plane, width, height, kernel, alongX, Out = Float64Array) {
  const out = new Out(plane.length);
  const r = (kernel.length - 1) / 2;
  for (let y = 0; y < height; y += 1) {
    for (let x = 0; x < width; x += 1) {
      let sum = 0;
      for (let i = -r; i <= r; i += 1) {
        const xx = alongX ? Math.min(width - 1, Math.max(0, x + i)) : x;
        const yy = alongX ? y : Math.min(height - 1, Math.max(0, y + i));
        sum += kernel[i + r] * plane[yy * width + xx];
      }
      out[y * width + x] = sum;
    }
  }
  return out;
}

function csfFilter(plane, width, height, csf, ppd) {
  const radius = Math.ceil(3 * Math.sqrt(LARGEST_CSF_B / (2 * Math.PI * Math.PI)) * ppd);
  const terms = [];
  for (const [a, b] of [[csf.a1, csf.b1], [csf.a2, csf.b2]]) {
    if (a === 0) continue;
    const profile = [];
    for (let i = -radius; i <= radius; i += 1) profile.push(Math.exp((-Math.PI * Math.PI * (i / ppd) ** 2) / b));
    terms.push({ profile, amplitude: a * Math.sqrt(Math.PI / b) });
  }
  const sum = (k) => k.reduce((s, v) => s + v, 0);
  const total = terms.reduce((s, t) => s + t.amplitude * sum(t.profile) ** 2, 0);
  const filtered = new Float32Array(plane.length);
  for (const t of terms) {
    const alongX = filterAlong(plane, width, height, t.profile.map((v) => (v * t.amplitude) / total), true);
    const pass = filterAlong(alongX, width, height, t.profile, false);
    for (let p = 0; p < plane.length; p += 1) filtered[p] += pass[p];
  }
  return filtered;
}

function perceptual(planes, p) {
  const yy = (planes[0][p] + 16) / 116;
  const rgb = apply(RELATIVE_XYZ_TO_RGB, [yy + planes[1][p] / 500, yy, yy - planes[2][p] / 200]).map((v) => Math.min(1, Math.max(0, v)));
  return huntAdjustedLab(rgb);
}

function featureDetectors(ppd) {
  const sd = 0.5 * W * ppd;
  const radius = Math.ceil(3 * sd);
  const gaussian = [];
  const first = [];
  const second = [];
  for (let i = -radius; i <= radius; i += 1) {
    const g = Math.exp(-(i * i) / (2 * sd * sd));
    gaussian.push(g);
    first.push(-i * g);
    second.push(((i * i) / (sd * sd) - 1) * g);
  }
  const total = gaussian.reduce((s, v) => s + v, 0);
  const signed = (k) => {
    const pos = k.filter((v) => v > 0).reduce((s, v) => s + v, 0);
    const neg = k.filter((v) => v <= 0).reduce((s, v) => s + v, 0);
    return k.map((v) => (v > 0 ? v / pos : v / -neg));
  };
  return { gaussian: gaussian.map((v) => v / total), first: signed(first), second: signed(second) };
}

function features(luminance, width, height, d) {
  const alongY = filterAlong(luminance, width, height, d.gaussian, false);
  const alongX = filterAlong(luminance, width, height, d.gaussian, true);
  const ex = filterAlong(alongY, width, height, d.first, true);
  const ey = filterAlong(alongX, width, height, d.first, false);
  const px = filterAlong(alongY, width, height, d.second, true);
  const py = filterAlong(alongX, width, height, d.second, false);
  const edges = ex.map((v, i) => Math.hypot(v, ey[i]));
  const points = px.map((v, i) => Math.hypot(v, py[i]));
  return { edges, points };
}

// The FLIP map (Float32Array, one value a pixel) of `test` against `reference`, two images of the
// same size; `linear(v)`: a stored value as linear RGB in [0, 1] (the display image's, decoded).
export function flipMap(test, reference, linear, ppd = PIXELS_PER_DEGREE) {
  const { width, height } = test;
  const t = ycxczPlanes(test, linear);
  const r = ycxczPlanes(reference, linear);
  const ft = t.map((plane, c) => csfFilter(plane, width, height, CSF[c], ppd));
  const fr = r.map((plane, c) => csfFilter(plane, width, height, CSF[c], ppd));
  const d = featureDetectors(ppd);
  const toL = (plane) => Float64Array.from(plane, (v) => v / 116 + 16 / 116);
  const at = features(toL(t[0]), width, height, d);
  const ar = features(toL(r[0]), width, height, d);
  const map = new Float32Array(width * height);
  for (let p = 0; p < map.length; p += 1) {
    const color = Math.fround(redistributedColorError(hyab(perceptual(ft, p), perceptual(fr, p))));
    const feature = Math.fround(Math.sqrt(Math.max(Math.abs(ar.edges[p] - at.edges[p]), Math.abs(ar.points[p] - at.points[p])) / Math.SQRT2));
    map[p] = color ** (1 - feature);
  }
  return map;
}

// A display image's stored value (sRGB in [0, 1]) as linear, and a linear value as the display
// image shows it (clipped to [0, 1]): the runner's FLIP is on display images.
export const fromDisplay = srgbToLinear;
export const fromLinear = (v) => Math.min(1, Math.max(0, v));
