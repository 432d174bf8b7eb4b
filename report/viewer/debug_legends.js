// What a technique's debug image shows, for the legend beside it: where a technique substitutes
// something for the ray-traced truth (the heuristic's excluded objects keep their raster shading,
// SSR falls back to rays or the sky), the debug image says where. Colours as the techniques write
// them (heuristic_rt_technique.cpp, ssr_fallback_technique.cpp).

export const DEBUG_LEGENDS = {
  heuristic_mask: {
    text: 'What the heuristic ray traced per pixel. Black: an object the heuristic left out (over the budget, or not selected): '
      + 'it keeps its raster shading, where a mirror or glass object shows the sky colour of the raster\'s environment terms '
      + '(a flat, sky-coloured disk for a glass sphere).',
    swatches: [['#f00', 'shadow rays'], ['#0f0', 'reflection rays'], ['#00f', 'refraction rays'], ['#fff', 'all three'], ['#000', 'raster only (excluded)']],
  },
  shadows: { text: 'The traced local (shadowed) term of the pixels the heuristic selected; black: not traced.' },
  reflections: { text: 'The traced reflected term of the selected pixels; black: not traced or not reflective.' },
  refractions: { text: 'The traced refracted term of the selected pixels; black: not traced or not refractive.' },
  reflection_source: {
    text: 'Where each reflection came from: SSR where it found the reflected surface on screen, else the fallback.',
    swatches: [['rgb(51,102,255)', 'screen-space reflection'], ['rgb(255,102,204)', 'ray-traced fallback'], ['rgb(102,255,255)', 'sky (fallback)'],
      ['rgb(38,38,38)', 'missing (no fallback)'], ['rgb(153,51,128)', 'refractive: ray traced whole'], ['#000', 'not reflective']],
  },
  ssr_failures: {
    text: 'Why the screen-space march failed (reasons add); the fallback mask is every coloured pixel.',
    swatches: [['#f00', 'left the screen'], ['#0f0', 'behind a surface'], ['#00f', 'out of steps'], ['#ff0', 'back face'],
      ['#f0f', 'maximum distance'], ['#fff', 'SSR hit'], ['#000', 'SSR not run']],
  },
  ssr_confidence: { text: 'SSR\'s confidence: white, SSR alone; black, the fallback alone; grey, a blend of the two.' },
  lens: { text: 'The lens objects as drawn from the layered environment maps (Hakura & Snyder 2001); black: no lens object.' },
};

export function debugLegendHtml(name, escape) {
  const legend = DEBUG_LEGENDS[name];
  if (!legend) return `<div class="debug-legend">${escape(name)}: a technique's debug image</div>`;
  const swatches = (legend.swatches || [])
    .map(([colour, label]) => `<span class="swatch"><i style="background:${colour}"></i>${escape(label)}</span>`)
    .join('');
  return `<div class="debug-legend">${escape(legend.text)}${swatches ? `<div class="swatches">${swatches}</div>` : ''}</div>`;
}
