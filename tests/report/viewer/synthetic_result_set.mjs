// A result set made up by the viewer's test, at the paper configs' size, without rendering: records
// in the layout of experiments/results.schema.json, and EXR images whose every value is known (a
// formula of the pixel), written here as OpenEXR lays them out (scan lines, ZIP, ZIPS or no
// compression, FLOAT or HALF channels) with their display PNGs. The runs of one setting share its
// image files' contents
// through hard links, each run still naming its own file, so that a set of a hundred 1280x720 runs
// costs a few images' time and disk.
//
//   const set = writeSyntheticSet(folder, { width: 1280, height: 720, frames: 15 });
//   set.value(technique, x, y) -> [r, g, b]: the values its EXRs hold at (x, y)
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';

const COMPRESSION = { none: 0, zips: 2, zip: 3 };
const LINES = { none: 1, zips: 1, zip: 16 };

// A float as the nearest half's bits (the values written as HALF are exact halves).
function halfBits(v) {
  const f = new Float32Array([v]);
  const b = new Uint32Array(f.buffer)[0];
  const sign = (b >>> 16) & 0x8000;
  const e = ((b >>> 23) & 0xff) - 127 + 15;
  const m = b & 0x7fffff;
  if (e <= 0) return sign | Math.round((m | 0x800000) / 2 ** (14 - e)); // subnormal
  if (e >= 31) return sign | 0x7c00;
  return sign | ((e << 10) + Math.round(m / 2 ** 13)); // a mantissa rounded up to 1024 carries into the exponent
}

export function halfValue(v) {
  const h = halfBits(v);
  const e = (h >> 10) & 0x1f;
  const m = h & 0x3ff;
  const s = h & 0x8000 ? -1 : 1;
  return e === 0 ? s * m * 2 ** -24 : s * (1 + m / 1024) * 2 ** (e - 15);
}

function attribute(name, type, value) {
  const size = Buffer.alloc(4);
  size.writeInt32LE(value.length);
  return Buffer.concat([Buffer.from(`${name}\0${type}\0`, 'latin1'), size, value]);
}

const int32s = (...xs) => Buffer.from(new Int32Array(xs).buffer);
const float32s = (...xs) => Buffer.from(new Float32Array(xs).buffer);

// An EXR of `width` x `height` RGB pixels `pixel(x, y)` -> [r, g, b], channels of `type` ('float'
// or 'half'), `compression` ('zip', 'zips' or 'none').
export function writeExr(file, width, height, pixel, { type = 'float', compression = 'zip' } = {}) {
  const bytes = type === 'float' ? 4 : 2;
  const pixelType = type === 'float' ? 2 : 1;
  const channels = Buffer.concat([...['B', 'G', 'R'].map((n) => Buffer.concat([Buffer.from(`${n}\0`), int32s(pixelType, 0, 1, 1)])), Buffer.from([0])]);
  const header = Buffer.concat([
    int32s(20000630, 2),
    attribute('channels', 'chlist', channels),
    attribute('compression', 'compression', Buffer.from([COMPRESSION[compression]])),
    attribute('dataWindow', 'box2i', int32s(0, 0, width - 1, height - 1)),
    attribute('displayWindow', 'box2i', int32s(0, 0, width - 1, height - 1)),
    attribute('lineOrder', 'lineOrder', Buffer.from([0])),
    attribute('pixelAspectRatio', 'float', float32s(1)),
    attribute('screenWindowCenter', 'v2f', float32s(0, 0)),
    attribute('screenWindowWidth', 'float', float32s(1)),
    Buffer.from([0]),
  ]);
  const lines = LINES[compression];
  const blocks = [];
  for (let y0 = 0; y0 < height; y0 += lines) {
    const n = Math.min(lines, height - y0);
    const raw = Buffer.alloc(n * 3 * width * bytes);
    for (let y = y0; y < y0 + n; y += 1) {
      const row = Array.from({ length: width }, (_, x) => pixel(x, y));
      [2, 1, 0].forEach((channel, k) => { // B, G, R: the channels in name order
        const at = ((y - y0) * 3 + k) * width * bytes;
        for (let x = 0; x < width; x += 1) {
          if (type === 'float') raw.writeFloatLE(row[x][channel], at + 4 * x);
          else raw.writeUInt16LE(halfBits(row[x][channel]), at + 2 * x);
        }
      });
    }
    let data = raw;
    if (compression !== 'none') {
      // OpenEXR's Zip: even and odd bytes split into halves, then each byte as the difference to
      // the one before plus 128, then zlib.
      const split = Buffer.alloc(raw.length);
      const half = (raw.length + 1) >> 1;
      for (let i = 0; i < raw.length; i += 1) split[(i & 1 ? half : 0) + (i >> 1)] = raw[i];
      const t = Buffer.alloc(raw.length);
      t[0] = split[0];
      for (let i = 1; i < raw.length; i += 1) t[i] = (split[i] - split[i - 1] + 128 + 256) & 0xff;
      const packed = zlib.deflateSync(t, { level: 1 });
      data = packed.length < raw.length ? packed : raw;
    }
    blocks.push(Buffer.concat([int32s(y0, data.length), data]));
  }
  const offsets = Buffer.alloc(8 * blocks.length);
  let at = header.length + offsets.length;
  blocks.forEach((b, i) => {
    offsets.writeBigUInt64LE(BigInt(at), 8 * i);
    at += b.length;
  });
  fs.writeFileSync(file, Buffer.concat([header, offsets, ...blocks]));
}

const srgb = (v) => {
  const c = Math.min(1, Math.max(0, v));
  return Math.round(255 * (c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055));
};

// CRC-32 of `bytes`, as PNG's chunks carry it: the one a gzip member's trailer holds (RFC 1952),
// since zlib.crc32 arrived in Node.js 20.15 and Debian 12's Node.js is 18.
const crc32 = (bytes) => {
  const member = zlib.gzipSync(bytes, { level: 0 });
  return member.readUInt32LE(member.length - 8);
};

function chunk(type, data) {
  const head = Buffer.alloc(8);
  head.writeUInt32BE(data.length);
  head.write(type, 4, 'latin1');
  const crc = Buffer.alloc(4);
  crc.writeUInt32BE(crc32(Buffer.concat([head.subarray(4), data])));
  return Buffer.concat([head, data, crc]);
}

// The display PNG of the same pixels, as the runner writes one beside each EXR: 8-bit sRGB of the
// values clipped to [0, 1].
export function writePng(file, width, height, pixel) {
  const rows = Buffer.alloc(height * (1 + 3 * width));
  for (let y = 0; y < height; y += 1) {
    const at = y * (1 + 3 * width); // filter byte 0, then the row
    for (let x = 0; x < width; x += 1) pixel(x, y).forEach((v, c) => { rows[at + 1 + 3 * x + c] = srgb(v); });
  }
  const header = Buffer.alloc(13);
  header.writeUInt32BE(width, 0);
  header.writeUInt32BE(height, 4);
  header.set([8, 2, 0, 0, 0], 8); // 8 bits, RGB
  fs.writeFileSync(file, Buffer.concat([Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]), chunk('IHDR', header),
    chunk('IDAT', zlib.deflateSync(rows, { level: 1 })), chunk('IEND', Buffer.alloc(0))]));
}

// The settings of the set: a technique, its parameters, how its EXR is stored, its SSIM and time.
// The viewer opens on one setting of each technique (the first five, stored as the runner stores
// its images: FLOAT, ZIP); the last two hold the other layouts it reads (HALF; ZIPS, none).
export const SETTINGS = [
  { technique: 'raster', params: '', type: 'float', compression: 'zip', ssim: 0.91, ms: 4.0 },
  { technique: 'rt_only', params: '', type: 'float', compression: 'zip', ssim: 0.999, ms: 40.0 },
  { technique: 'heuristic_rt', params: 'budget=5000', type: 'float', compression: 'zip', ssim: 0.97, ms: 20.0 },
  { technique: 'ssr_fallback', params: '', type: 'float', compression: 'zip', ssim: 0.985, ms: 15.0 },
  { technique: 'whitted', params: 'max_depth=2', label: 'whitted-depth', type: 'float', compression: 'zip', ssim: 0.995, ms: 60.0 },
  { technique: 'heuristic_rt', params: 'budget=20000', type: 'half', compression: 'zips', ssim: 0.99, ms: 30.0 },
  { technique: 'whitted', params: 'max_depth=3', label: 'whitted-depth', type: 'half', compression: 'none', ssim: 0.998, ms: 70.0 },
];
const REFERENCE = { type: 'float', compression: 'zip' };

const variantOf = (s) => (s.label || s.technique) + (s.params ? ` [${s.params}]` : '');

// The values of setting k's image (k = -1 for the reference, -2 for the other frames' reference),
// as the EXR holds them (float32, or half where the setting is stored as half).
export function pixelOf(k, type) {
  const exact = type === 'half' ? halfValue : Math.fround;
  return (x, y) => [
    exact((((x + 37 * (k + 2)) % 256) / 256) * 1.5),
    exact(y / 720 + 0.001 * (k + 2)),
    exact((((x * 3 + y * 5 + 11 * (k + 2)) % 97) / 97) * 0.5),
  ];
}

// Writes the set into `folder` (results.json, experiment.json, images/, references/); returns
// { records, settings, variants, value(setting index or -1, x, y), referenceOf(frame) }.
export function writeSyntheticSet(folder, { width = 1280, height = 720, frames = 15 } = {}) {
  fs.mkdirSync(path.join(folder, 'images'), { recursive: true });
  fs.mkdirSync(path.join(folder, 'references'), { recursive: true });
  const uniques = path.join(folder, 'unique');
  fs.mkdirSync(uniques, { recursive: true });
  const first = {};
  const write = (name, k, layout) => {
    const file = path.join(uniques, name);
    writeExr(`${file}.exr`, width, height, pixelOf(k, layout.type), layout);
    writePng(`${file}.png`, width, height, pixelOf(k, layout.type));
    return file;
  };
  SETTINGS.forEach((s, k) => {
    first[k] = write(`setting-${k}`, k, s);
  });
  const references = [-1, -2].map((k) => write(`reference${k}`, k, REFERENCE));
  const link = (from, to) => ['exr', 'png'].forEach((ext) => fs.linkSync(`${from}.${ext}`, path.join(folder, `${to}.${ext}`)));
  const records = [];
  for (let f = 0; f < frames; f += 1) {
    const ref = `references/orbit-${f}.exr`;
    link(references[f % 2], ref.replace('.exr', ''));
    SETTINGS.forEach((s, k) => {
      const index = records.length;
      const id = `${String(index).padStart(5, '0')}-paper-scene-orbit_${f}-${width}x${height}-${s.technique}`;
      const exr = `images/${id}.exr`;
      link(first[k], exr.replace('.exr', ''));
      records.push({
        index, id, scene: 'paper-scene', scene_stats: { objects: 30, vertices: 100000, triangles: 60000, lights: 2, reflective: 3, refractive: 23 },
        view: 'orbit', frame: f, time: f / 10, width, height, technique: s.technique, label: s.label || s.technique,
        parameters: {}, parameters_text: s.params, sequence: `paper-scene|orbit|${s.params}`,
        stages: { trace: { median: s.ms * 0.8, min: s.ms * 0.8, max: s.ms * 0.8 } },
        counters: { rays_total: Math.round(width * height * s.ms / 10) },
        frame_ms: { median: s.ms * (1 + 0.01 * (f % 3)), min: s.ms, max: s.ms * 1.05 },
        metrics: { whole: { pixels: width * height, ssim: s.ssim - 0.001 * (f % 2), flip: { mean: 1 - s.ssim } }, masked: null,
                   reference: ref, test: exr, width, height },
        reference: { key: `orbit-${f}`, exr: ref, png: ref.replace('.exr', '.png'), frame_ms: 80.0, cache_hit: false },
        images: { exr, png: exr.replace('.exr', '.png'), maps: null },
      });
    });
  }
  fs.rmSync(uniques, { recursive: true });
  fs.writeFileSync(path.join(folder, 'results.json'), JSON.stringify(records));
  fs.writeFileSync(path.join(folder, 'experiment.json'), JSON.stringify({ name: 'synthetic-paper-scale' }));
  return {
    records,
    variants: SETTINGS.map(variantOf),
    value: (k, x, y) => pixelOf(k, k < 0 ? REFERENCE.type : SETTINGS[k].type)(x, y),
    referenceOf: (frame) => (frame % 2 ? -2 : -1),
  };
}
