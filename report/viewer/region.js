// Statistics of a rectangle drawn on the panes (shift-drag), as tev gives them: per channel the
// mean and the largest value of what a pane shows there, and against the image it is compared with
// (the reference, or the pane chosen) the mean absolute difference and the RMSE per channel, and
// the mean FLIP where the pane shows FLIP.

// The rectangle {x, y, w, h} clipped to the image; null when nothing of it is inside.
export function clipRegion(region, width, height) {
  if (!region) return null;
  const x0 = Math.max(0, region.x);
  const y0 = Math.max(0, region.y);
  const x1 = Math.min(width, region.x + region.w);
  const y1 = Math.min(height, region.y + region.h);
  return x1 > x0 && y1 > y0 ? { x: x0, y: y0, w: x1 - x0, h: y1 - y0 } : null;
}

function eachPixel(image, r, visit) {
  for (let y = r.y; y < r.y + r.h; y += 1) {
    for (let x = r.x; x < r.x + r.w; x += 1) visit(image.channels * (y * image.width + x));
  }
}

// {mean, max}: per channel over the rectangle `r` (clipped) of `image`.
export function channelStats(image, r) {
  const c = image.channels;
  const mean = new Array(c).fill(0);
  const max = new Array(c).fill(-Infinity);
  eachPixel(image, r, (i) => {
    for (let k = 0; k < c; k += 1) {
      mean[k] += image.data[i + k];
      max[k] = Math.max(max[k], image.data[i + k]);
    }
  });
  const n = r.w * r.h;
  return { mean: mean.map((s) => s / n), max };
}

// {mae, rmse}: per channel of `a` against `b` over `r`.
export function errorStats(a, b, r) {
  const c = a.channels;
  const abs = new Array(c).fill(0);
  const sq = new Array(c).fill(0);
  eachPixel(a, r, (i) => {
    for (let k = 0; k < c; k += 1) {
      const d = a.data[i + k] - b.data[i + k];
      abs[k] += Math.abs(d);
      sq[k] += d * d;
    }
  });
  const n = r.w * r.h;
  return { mae: abs.map((s) => s / n), rmse: sq.map((s) => Math.sqrt(s / n)) };
}
