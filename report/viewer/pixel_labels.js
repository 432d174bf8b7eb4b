// Pixel values written inside the pixels, as tev does, once a pixel is drawn large enough to hold
// them: one line per channel, in black or white against the colour drawn there.

const MIN_PIXEL_PX = 44; // a pixel's size on screen from which its values are written
const MAX_LABELS = 4000; // a bound on the text drawn per pane

// Clears `canvas` (laid over the viewport `vp`) and writes the values of `image` under the
// transform `t` where its pixels are large enough; `colourOf(values)`: the colour drawn there.
export function drawPixelValues(canvas, vp, t, image, colourOf) {
  const ratio = window.devicePixelRatio || 1;
  const w = vp.clientWidth;
  const h = vp.clientHeight;
  if (canvas.width !== Math.round(w * ratio) || canvas.height !== Math.round(h * ratio)) {
    canvas.width = Math.round(w * ratio);
    canvas.height = Math.round(h * ratio);
  }
  const ctx = canvas.getContext('2d');
  ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  ctx.clearRect(0, 0, w, h);
  canvas.dataset.labels = '0';
  if (!t || !image || t.scale < MIN_PIXEL_PX) return;
  const x0 = Math.max(0, Math.floor(-t.tx / t.scale));
  const y0 = Math.max(0, Math.floor(-t.ty / t.scale));
  const x1 = Math.min(image.width, Math.ceil((w - t.tx) / t.scale));
  const y1 = Math.min(image.height, Math.ceil((h - t.ty) / t.scale));
  if ((x1 - x0) * (y1 - y0) > MAX_LABELS) return;
  const c = image.channels;
  const size = Math.min(14, t.scale / (c + 1.5));
  ctx.font = `${size}px monospace`;
  ctx.textAlign = 'center';
  ctx.textBaseline = 'middle';
  let count = 0;
  for (let y = y0; y < y1; y += 1) {
    for (let x = x0; x < x1; x += 1) {
      const i = c * (y * image.width + x);
      const values = Array.from(image.data.subarray(i, i + c));
      const [r, g, b] = colourOf(values);
      ctx.fillStyle = 0.2126 * r + 0.7152 * g + 0.0722 * b > 128 ? '#000' : '#fff';
      const cx = t.tx + (x + 0.5) * t.scale;
      const cy = t.ty + (y + 0.5) * t.scale;
      values.forEach((v, k) => ctx.fillText(v.toPrecision(4), cx, cy + (k - (c - 1) / 2) * size * 1.15));
      count += 1;
    }
  }
  canvas.dataset.labels = String(count);
}
