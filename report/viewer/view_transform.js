// The zoom and pan shared by every pane: image pixel (x, y) appears at screen offset
// (tx + x * scale, ty + y * scale) inside each pane's viewport.

export const MIN_SCALE = 0.05;
export const MAX_SCALE = 64;

export function fit(viewWidth, viewHeight, imageWidth, imageHeight) {
  const scale = Math.min(viewWidth / imageWidth, viewHeight / imageHeight);
  return { scale, tx: (viewWidth - imageWidth * scale) / 2, ty: (viewHeight - imageHeight * scale) / 2 };
}

// Zoom by `factor` keeping the image point under (cx, cy) where it is.
export function zoomAbout(t, cx, cy, factor) {
  const scale = Math.min(MAX_SCALE, Math.max(MIN_SCALE, t.scale * factor));
  const f = scale / t.scale;
  return { scale, tx: cx - (cx - t.tx) * f, ty: cy - (cy - t.ty) * f };
}

export function pan(t, dx, dy) {
  return { scale: t.scale, tx: t.tx + dx, ty: t.ty + dy };
}

// The pixel under viewport offset (x, y).
export function imagePixel(t, x, y) {
  return { x: Math.floor((x - t.tx) / t.scale), y: Math.floor((y - t.ty) / t.scale) };
}

export function cssTransform(t) {
  return `translate(${t.tx}px, ${t.ty}px) scale(${t.scale})`;
}
