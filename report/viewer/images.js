// The result set's images as values, read straight from the set (the viewer keeps no copy): an
// EXR decoded to its linear RGB (exr.js), a PNG (debug images, the runner's error maps) decoded by
// the browser to its stored 8-bit values in [0, 1]. Each file is read once and kept while it is
// among the most recently used.
//
// An image here: { width, height, channels (3 or 1), data (Float32Array, row by row, top first),
// kind ('linear': an EXR's values; 'display': a PNG's values as stored; 'scalar': one value a
// pixel, such as an error map) }.

const KEPT = 24; // images kept decoded (a 1280x720 RGB image is 11 MB)
const cache = new Map(); // url -> Promise<image>

// The EXR decoders: one worker a core (up to four), each given the next file in turn.
const workers = [];
const pending = new Map(); // id -> { resolve, reject }
let nextId = 0;

function decodeInWorker(buffer) {
  if (!workers.length) {
    const n = Math.max(1, Math.min(4, navigator.hardwareConcurrency || 2));
    for (let i = 0; i < n; i += 1) {
      const worker = new Worker(new URL('./decode_worker.js', import.meta.url), { type: 'module' });
      worker.onmessage = ({ data }) => {
        const { resolve, reject } = pending.get(data.id);
        pending.delete(data.id);
        if (data.error) reject(new Error(data.error));
        else resolve({ width: data.width, height: data.height, rgb: data.rgb });
      };
      workers.push(worker);
    }
  }
  const id = nextId++;
  return new Promise((resolve, reject) => {
    pending.set(id, { resolve, reject });
    workers[id % workers.length].postMessage({ id, buffer }, [buffer]);
  });
}

async function decodePng(blob) {
  const bitmap = await createImageBitmap(blob, { colorSpaceConversion: 'none', premultiplyAlpha: 'none' });
  const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
  const ctx = canvas.getContext('2d', { willReadFrequently: true });
  ctx.drawImage(bitmap, 0, 0);
  const rgba = ctx.getImageData(0, 0, bitmap.width, bitmap.height).data;
  const data = new Float32Array(bitmap.width * bitmap.height * 3);
  for (let p = 0, q = 0; p < rgba.length; p += 4, q += 3) {
    data[q] = rgba[p] / 255;
    data[q + 1] = rgba[p + 1] / 255;
    data[q + 2] = rgba[p + 2] / 255;
  }
  return { width: bitmap.width, height: bitmap.height, channels: 3, data, kind: 'display' };
}

async function read(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: ${response.status} ${response.statusText}`);
  const buffer = await response.arrayBuffer();
  const head = new Uint8Array(buffer, 0, Math.min(4, buffer.byteLength));
  try {
    if (head[0] === 0x76 && head[1] === 0x2f && head[2] === 0x31 && head[3] === 0x01) {
      const exr = await decodeInWorker(buffer);
      return { width: exr.width, height: exr.height, channels: 3, data: exr.rgb, kind: 'linear' };
    }
    return await decodePng(new Blob([buffer]));
  } catch (e) {
    throw new Error(`${url}: ${e.message}`);
  }
}

export function loadImage(url) {
  if (cache.has(url)) {
    const kept = cache.get(url);
    cache.delete(url); // most recently used last
    cache.set(url, kept);
    return kept;
  }
  const loading = read(url);
  cache.set(url, loading);
  loading.catch(() => cache.delete(url));
  while (cache.size > KEPT) cache.delete(cache.keys().next().value);
  return loading;
}

// Whether `url` is read or being read already.
export function isLoading(url) {
  return cache.has(url);
}

// The values of pixel (x, y), or null outside the image.
export function valuesAt(image, x, y) {
  if (!image || x < 0 || y < 0 || x >= image.width || y >= image.height) return null;
  const i = image.channels * (y * image.width + x);
  return Array.from(image.data.subarray(i, i + image.channels));
}
