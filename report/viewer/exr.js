// OpenEXR images decoded in the browser: single-part scan-line files with NONE, ZIPS or ZIP
// compression and HALF, FLOAT or UINT channels (what the runner writes: FLOAT RGBA, ZIP). The
// values come out exactly as stored (a HALF widened to float exactly), as linear RGB.
//
// ZIP (OpenEXR's Zip compressor): each block of scan lines (1 for ZIPS, 16 for ZIP) is a zlib
// stream, inflated here by pako (Debian's node-pako, copied beside the viewer by report/viewer.py:
// a 1280x720 ZIPS image is 720 streams, and the browser's DecompressionStream spent milliseconds
// setting up each one), of the block's bytes
// after a predictor (each byte the difference to the one before, plus 128) and a split of the even
// and odd bytes into two halves; a block that would not shrink is stored as it is. A line holds
// the channels one after the other in the header's (name) order.

import { inflate } from './pako.js';

const MAGIC = 20000630;
const LINES_PER_BLOCK = { 0: 1, 2: 1, 3: 16 }; // NONE, ZIPS, ZIP
const COMPRESSION_NAMES = ['NONE', 'RLE', 'ZIPS', 'ZIP', 'PIZ', 'PXR24', 'B44', 'B44A', 'DWAA', 'DWAB'];
const BYTES = { 0: 4, 1: 2, 2: 4 }; // UINT, HALF, FLOAT

export class ExrError extends Error {}

let halfTable = null;

// Every half float's value as a float: exact, since a float holds every half.
function halves() {
  if (!halfTable) {
    halfTable = new Float32Array(65536);
    for (let h = 0; h < 65536; h += 1) {
      const s = h & 0x8000 ? -1 : 1;
      const e = (h >> 10) & 0x1f;
      const m = h & 0x3ff;
      if (e === 0) halfTable[h] = s * m * 2 ** -24;
      else if (e === 31) halfTable[h] = m ? NaN : s * Infinity;
      else halfTable[h] = s * (1 + m / 1024) * 2 ** (e - 15);
    }
  }
  return halfTable;
}

function readHeader(view, bytes) {
  if (bytes.length < 8 || view.getInt32(0, true) !== MAGIC) throw new ExrError('not an OpenEXR file');
  if (bytes[5] & 0x1e) throw new ExrError('only single-part scan-line files are read (this one is tiled, deep or multi-part)');
  const text = (from, to) => String.fromCharCode(...bytes.subarray(from, to));
  const attributes = {};
  let i = 8;
  while (bytes[i] !== 0) {
    const nameEnd = bytes.indexOf(0, i);
    const typeEnd = bytes.indexOf(0, nameEnd + 1);
    const size = view.getInt32(typeEnd + 1, true);
    attributes[text(i, nameEnd)] = { type: text(nameEnd + 1, typeEnd), at: typeEnd + 5, size };
    i = typeEnd + 5 + size;
    if (nameEnd < 0 || typeEnd < 0 || i > bytes.length) throw new ExrError('its header is cut short');
  }
  return { attributes, end: i + 1 };
}

function channelList(view, bytes, a) {
  const channels = [];
  let i = a.at;
  while (bytes[i] !== 0) {
    const nameEnd = bytes.indexOf(0, i);
    const name = String.fromCharCode(...bytes.subarray(i, nameEnd));
    const type = view.getInt32(nameEnd + 1, true);
    const xSampling = view.getInt32(nameEnd + 9, true);
    const ySampling = view.getInt32(nameEnd + 13, true);
    if (!(type in BYTES)) throw new ExrError(`channel ${name} has an unknown pixel type ${type}`);
    if (xSampling !== 1 || ySampling !== 1) throw new ExrError(`channel ${name} is subsampled`);
    channels.push({ name, type });
    i = nameEnd + 17;
  }
  return channels;
}

// The predictor and the split of even and odd bytes undone, in one pass: t[i] is the i-th byte of
// the split halves, the first half the even bytes of the block, the second the odd ones.
function unpredict(t) {
  const out = new Uint8Array(t.length);
  const half = (t.length + 1) >> 1;
  let previous = 0;
  for (let i = 0; i < t.length; i += 1) {
    previous = i === 0 ? t[0] : (previous + t[i] - 128) & 0xff;
    out[i < half ? 2 * i : 2 * (i - half) + 1] = previous;
  }
  return out;
}

// One channel's line into every third value of `rgb` from `start`: a function per type, so that
// each loop reads one kind of array (a loop that met all three ran several times slower).
function copyFloats(line, rgb, start) {
  for (let x = 0; x < line.length; x += 1) rgb[start + 3 * x] = line[x];
}

function copyHalves(line, rgb, start, table) {
  for (let x = 0; x < line.length; x += 1) rgb[start + 3 * x] = table[line[x]];
}

function copyUints(line, rgb, start) {
  for (let x = 0; x < line.length; x += 1) rgb[start + 3 * x] = line[x];
}

// {width, height, rgb}: the R, G and B channels (Y for all three in a grey image) as one
// Float32Array, row by row, top row first.
export function decodeExr(buffer) {
  const bytes = new Uint8Array(buffer);
  const view = new DataView(buffer);
  const { attributes, end } = readHeader(view, bytes);
  for (const name of ['channels', 'compression', 'dataWindow']) {
    if (!attributes[name]) throw new ExrError(`its header has no ${name}`);
  }
  const compression = bytes[attributes.compression.at];
  if (!(compression in LINES_PER_BLOCK)) {
    throw new ExrError(`${COMPRESSION_NAMES[compression] || compression} compression is not read here (NONE, ZIPS and ZIP are)`);
  }
  const channels = channelList(view, bytes, attributes.channels);
  const w = attributes.dataWindow.at;
  const [x0, y0, x1, y1] = [0, 4, 8, 12].map((k) => view.getInt32(w + k, true));
  const width = x1 - x0 + 1;
  const height = y1 - y0 + 1;
  if (width < 1 || height < 1 || width > 16384 || height > 16384) throw new ExrError(`its data window is ${width} x ${height}`);
  const find = (n) => channels.findIndex((c) => c.name === n);
  const sources = ['R', 'G', 'B'].map((n) => (find(n) >= 0 ? find(n) : find('Y')));
  if (sources.some((s) => s < 0)) throw new ExrError(`it has neither R, G and B nor Y channels (${channels.map((c) => c.name).join(', ')})`);
  const lineBytes = channels.reduce((sum, c) => sum + BYTES[c.type] * width, 0);
  const linesPerBlock = LINES_PER_BLOCK[compression];
  const blocks = Math.ceil(height / linesPerBlock);
  const rgb = new Float32Array(width * height * 3);
  const table = halves();
  const decodeBlock = (b) => {
    const offset = Number(view.getBigUint64(end + 8 * b, true));
    if (offset + 8 > bytes.length) throw new ExrError(`block ${b} lies past the end of the file`);
    const y = view.getInt32(offset, true) - y0;
    const size = view.getInt32(offset + 4, true);
    const lines = Math.min(linesPerBlock, height - y);
    if (y < 0 || lines < 1 || offset + 8 + size > bytes.length) throw new ExrError(`block ${b} is damaged`);
    const stored = bytes.slice(offset + 8, offset + 8 + size);
    let raw = stored;
    if (compression !== 0 && size !== lines * lineBytes) {
      try {
        raw = unpredict(inflate(stored));
      } catch (e) {
        throw new ExrError(`block ${b} does not inflate (${e.message || e})`);
      }
    }
    if (raw.length !== lines * lineBytes) throw new ExrError(`block ${b} holds ${raw.length} bytes, not ${lines * lineBytes}`);
    // A copy at offset 0, so that every channel's line is aligned for a typed view of it (the
    // file and this machine are both little-endian: OpenEXR's byte order, and every browser's).
    const aligned = raw.byteOffset === 0 ? raw.buffer : raw.slice().buffer;
    for (let line = 0; line < lines; line += 1) {
      let at = line * lineBytes;
      const row = (y + line) * width * 3;
      for (let k = 0; k < channels.length; k += 1) {
        const type = channels[k].type;
        for (let target = 0; target < 3; target += 1) {
          if (sources[target] !== k) continue;
          if (type === 2) copyFloats(new Float32Array(aligned, at, width), rgb, row + target);
          else if (type === 1) copyHalves(new Uint16Array(aligned, at, width), rgb, row + target, table);
          else copyUints(new Uint32Array(aligned, at, width), rgb, row + target);
        }
        at += BYTES[type] * width;
      }
    }
  };
  for (let b = 0; b < blocks; b += 1) decodeBlock(b);
  return { width, height, rgb };
}
