// Pixel values for the inspector. A page opened from the file system may not read back the pixels
// of its own images (file:// images taint a canvas), so report.py writes each PNG the viewer shows
// also as a small classic script holding it as a data: URL, which a canvas may read; the script
// calls window.hybridlabPixels(file, dataUrl). Loaded on first hover, kept afterwards.

import { scriptLoader } from './script_data.js';

function decode(dataUrl) {
  return new Promise((resolve) => {
    const img = new Image();
    img.onload = () => {
      const canvas = document.createElement('canvas');
      canvas.width = img.naturalWidth;
      canvas.height = img.naturalHeight;
      const ctx = canvas.getContext('2d', { willReadFrequently: true });
      ctx.drawImage(img, 0, 0);
      resolve(ctx.getImageData(0, 0, canvas.width, canvas.height));
    };
    img.onerror = () => resolve(null);
    img.src = dataUrl;
  });
}

// The decoded pixels of `file` (a path in the manifest), or null when there is no pixel script.
export const pixelData = scriptLoader('hybridlabPixels', decode);

export function rgbaAt(data, x, y) {
  if (!data || x < 0 || y < 0 || x >= data.width || y >= data.height) return null;
  const i = 4 * (y * data.width + x);
  return [data.data[i], data.data[i + 1], data.data[i + 2], data.data[i + 3]];
}

// The value an error map's colour stands for: the nearest entry of the map's colour table (256
// colours from matplotlib), scaled to the map's range.
export function mapValue(rgb, table, range) {
  let best = 0;
  let bestDistance = Infinity;
  table.forEach((c, i) => {
    const d = (c[0] - rgb[0]) ** 2 + (c[1] - rgb[1]) ** 2 + (c[2] - rgb[2]) ** 2;
    if (d < bestDistance) {
      bestDistance = d;
      best = i;
    }
  });
  return range[0] + (range[1] - range[0]) * (best / (table.length - 1));
}
