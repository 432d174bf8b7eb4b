// The viewer page: up to eight panes side by side (or one pane in flip or swipe mode) showing the
// reference and technique settings of one scene, size, view and frame, drawn from the result set's
// own images (EXR decoded here, linear values exact), with shared zoom and pan, exposure, display
// transform and false colour, the difference of any two panes, a pixel inspector, values written
// inside pixels when zoomed in, statistics of a drawn rectangle, and the whole view in the address.

import { ResultSet, REFERENCE } from './result_set.js';
import { fit, zoomAbout, pan, imagePixel, cssTransform } from './view_transform.js';
import { paneContent, nextErrorLayer } from './pane_content.js';
import { metricReadout } from './metric_readout.js';
import { loadImage, isLoading, valuesAt } from './images.js';
import { actionOf, helpHtml } from './shortcuts.js';
import { DISPLAY_TRANSFORMS, DEFAULT_TRANSFORM, drawImage, legendOf, legendHtml, pixelColour, runnerMapValues } from './display.js';
import { difference } from './difference.js';
import { clipRegion, channelStats, errorStats } from './region.js';
import { encodeView, decodeView } from './view_state.js';
import { debugLegendHtml } from './debug_legends.js';
import { drawPixelValues } from './pixel_labels.js';

const MAX_PANES = 8;
const EV_STEP = 0.5;
const EV_LIMIT = 10;
const PLAY_INTERVAL_MS = 700;

let results = null;
const $ = (id) => document.getElementById(id);
const escapeHtml = (s) => String(s).replace(/[&<>"']/g, (c) => `&#${c.charCodeAt(0)};`);

const state = {
  sel: null, // { scene, size, view }
  frames: [],
  frameIndex: 0,
  variants: [],
  panes: [], // { variant, layer, against (a pane index or null: the reference) } each
  paneCount: MAX_PANES,
  mode: 'side', // 'side' | 'flip' | 'swipe'
  flipSecond: false,
  swipe: 0.5, // the divider, a fraction of the viewport width
  transform: null, // shared zoom and pan; null: fit (or the address's zoom) at the next render
  pendingView: null, // { zoom, centre } from the address, applied at the next render
  active: 1,
  player: null,
  pixel: null, // the inspected pixel
  ev: 0, // exposure of the linear images: values times 2^ev
  display: DEFAULT_TRANSFORM,
  region: null, // the drawn rectangle, in image pixels { x, y, w, h }
  generation: 0, // render count: drawings of an older render are dropped
};

function notice(text) {
  const box = $('notice');
  box.hidden = !text;
  box.querySelector('.text').textContent = text || '';
}

function fillSelect(select, values, current, label = (v) => v) {
  select.innerHTML = values.map((v) => `<option value="${escapeHtml(v)}">${escapeHtml(label(v))}</option>`).join('');
  select.value = current;
}

// Scene, size and view (each defaulting to the first available), frame and pane choices.
function select(scene, size, view, frame, variantsFirst) {
  scene = results.scenes().includes(scene) ? scene : results.scenes()[0];
  const sizes = results.sizes(scene);
  size = sizes.includes(size) ? size : sizes[0];
  const views = results.views(scene, size);
  view = views.includes(view) ? view : views[0];
  state.sel = { scene, size, view };
  state.frames = results.frames(state.sel);
  state.frameIndex = Math.max(0, state.frames.indexOf(frame));
  state.variants = results.variants(state.sel);
  // The panes open on the reference and one setting of each technique (its default where it ran);
  // the rest follow, for the pane count menu.
  const defaults = results.defaultVariants(state.sel);
  const first = [...variantsFirst, ...defaults].filter((v, i, all) => state.variants.includes(v) && all.indexOf(v) === i);
  const order = [...first, ...state.variants.filter((v) => !first.includes(v))];
  state.panes = [REFERENCE, ...order].slice(0, MAX_PANES).map((variant) => ({ variant, layer: 'image', against: null }));
  while (state.panes.length < MAX_PANES) state.panes.push({ variant: order[0] || REFERENCE, layer: 'image', against: null });
  state.paneCount = Math.min(MAX_PANES, 1 + first.length);
  state.active = Math.min(1, state.paneCount - 1);
  state.transform = null;
  fillSelect($('scene'), results.scenes(), scene);
  fillSelect($('size'), sizes, size);
  fillSelect($('view'), views, view);
  $('variant-list').innerHTML = [REFERENCE, ...state.variants].map((v) => `<option value="${escapeHtml(variantLabel(v))}"></option>`).join('');
  $('frame').max = String(state.frames.length - 1);
  $('frame-controls').hidden = state.frames.length < 2;
}

function frameNumber() {
  return state.frames[state.frameIndex];
}

// The panes each slot on screen shows: one per pane side by side, one pane in flip mode, panes 1
// and 2 left and right of the divider in swipe mode.
function slots() {
  if (state.mode === 'flip') return [[state.flipSecond ? 1 : 0]];
  if (state.mode === 'swipe') return [[0, 1]];
  return [...Array(state.paneCount).keys()].map((i) => [i]);
}

function variantLabel(v) {
  if (v === REFERENCE) return '1: reference (whitted)';
  return `${state.variants.indexOf(v) + 2}: ${v}`;
}

// The pane a pane is differenced against: the one chosen, else the reference's pane where its own
// variant is not the reference; null where there is none.
function comparedWith(i) {
  const p = state.panes[i];
  if (p.against !== null && p.against !== i && p.against < MAX_PANES) return { pane: p.against, variant: state.panes[p.against].variant };
  return p.variant === REFERENCE ? null : { pane: null, variant: REFERENCE };
}

function comparedName(i) {
  const c = comparedWith(i);
  if (!c) return '';
  return c.pane === null ? 'the reference' : `pane ${c.pane + 1} (${c.variant === REFERENCE ? 'reference' : c.variant})`;
}

function contentOf(i) {
  return paneContent(results, state.sel, frameNumber(), state.panes[i], Boolean(comparedWith(i)));
}

// The values pane i shows (an image of images.js), with how to draw them.
async function shownImage(i) {
  const content = contentOf(i);
  if (!content) return null;
  const layer = content.layer;
  if (layer.difference) {
    const c = comparedWith(i);
    const other = paneContent(results, state.sel, frameNumber(), { variant: c.variant, layer: 'image' }, false);
    if (!other) throw new Error(`${comparedName(i)} has no run at this frame`);
    const [a, b] = await Promise.all([loadImage(content.file), loadImage(other.file)]);
    return difference(a, b, layer.difference);
  }
  if (layer.id.startsWith('map:')) {
    return runnerMapValues(await loadImage(layer.file), results.colormaps[layer.colormap], layer.range, content.height);
  }
  return loadImage(layer.id === 'image' ? content.file : layer.file);
}

function how(layer) {
  return { ev: state.ev, transform: state.display, colormap: layer.colormap || 'magma', range: layer.range || [0, 1], what: layer.what || layer.id };
}

function infoHtml(c) {
  const lines = [];
  if (c.parameters) lines.push(`<div class="params">${escapeHtml(c.parameters)}</div>`);
  if (c.run && c.run.not_applicable) lines.push(`<div class="not-applicable">not applicable here: ${escapeHtml(c.run.not_applicable)}</div>`);
  let time = `frame ${c.frameMs.toFixed(2)} ms`;
  if (c.stages) time += ': ' + Object.entries(c.stages).map(([k, v]) => `${escapeHtml(k)} ${v.toFixed(2)}`).join(', ');
  lines.push(`<div class="time">${time}</div>`);
  if (c.scores) {
    for (const line of metricReadout(results.metricTable, c.scores, c.temporal)) {
      lines.push(`<div class="metrics${line.masked ? ' masked' : ''}">${escapeHtml(line.text)}</div>`);
    }
  }
  return lines.join('');
}

// The pane's bar above its image: its setting (in the report's colour), its layer, and the pane
// it is differenced against.
function paneBar(i, content) {
  const bar = document.createElement('div');
  bar.className = 'bar';
  bar.dataset.pane = String(i);
  const swatch = document.createElement('span');
  swatch.className = 'swatch';
  swatch.style.background = (content && content.colour) || 'transparent';
  bar.appendChild(swatch);
  const variants = document.createElement('select');
  variants.className = 'variant';
  fillSelect(variants, [REFERENCE, ...state.variants], state.panes[i].variant, variantLabel);
  variants.title = variantLabel(state.panes[i].variant);
  variants.addEventListener('change', () => {
    state.panes[i].variant = variants.value;
    render();
  });
  bar.appendChild(variants);
  if (!content) return bar;
  const layers = document.createElement('select');
  layers.className = 'layer';
  fillSelect(layers, content.layers.map((l) => l.id), content.layer.id, (id) => content.layers.find((l) => l.id === id).name);
  layers.addEventListener('change', () => {
    state.panes[i].layer = layers.value;
    render();
  });
  bar.appendChild(layers);
  const against = document.createElement('select');
  against.className = 'against';
  against.title = 'the image B that this pane (A) is differenced against';
  const choices = ['', ...[...Array(state.paneCount).keys()].filter((k) => k !== i).map(String)];
  fillSelect(against, choices, state.panes[i].against === null ? '' : String(state.panes[i].against),
    (k) => (k !== '' ? `B: pane ${Number(k) + 1}` : state.panes[i].variant === REFERENCE ? 'B: none' : 'B: the reference'));
  against.addEventListener('change', () => {
    state.panes[i].against = against.value === '' ? null : Number(against.value);
    if (state.panes[i].layer === 'image') state.panes[i].layer = 'abs';
    render();
  });
  bar.appendChild(against);
  return bar;
}

function paneInfo(i, content) {
  const info = document.createElement('div');
  info.className = 'info';
  info.dataset.pane = String(i);
  if (!content) {
    info.innerHTML = '<div class="missing">no run at this frame</div>';
    return info;
  }
  const layer = content.layer;
  const what = layer.difference ? `<div class="layer-note">${escapeHtml(layer.name.replace('A', 'this pane').replace(/B(?=\W|$)/g, comparedName(i)))}</div>` : '';
  info.innerHTML = what + infoHtml(content) + '<div class="legend-slot"></div><div class="inspector"></div><div class="stats"></div>';
  if (layer.id.startsWith('debug:')) info.querySelector('.legend-slot').innerHTML = debugLegendHtml(layer.id.slice('debug:'.length), escapeHtml);
  return info;
}

function render() {
  const sel = state.sel;
  const frame = frameNumber();
  const generation = ++state.generation;
  shownNow.clear();
  $('frame').value = String(state.frameIndex);
  $('frame-label').textContent = `frame ${frame} (${state.frameIndex + 1} of ${state.frames.length})`;
  $('mode').value = state.mode;
  $('pane-count').value = String(state.paneCount);
  document.title = `hybridlab viewer: ${sel.scene} ${sel.size} ${sel.view}` + (frame >= 0 ? ` @ ${frame}` : '');
  const container = $('panes');
  container.innerHTML = '';
  const n = slots().length;
  container.style.gridTemplateColumns = `repeat(${n <= 4 ? n : Math.ceil(n / 2)}, minmax(0, 1fr))`;
  $('ev').value = String(state.ev);
  $('ev-label').textContent = `EV ${state.ev >= 0 ? '+' : ''}${state.ev.toFixed(1)}`;
  $('transform').value = state.display;
  let first = null;
  const drawings = [];
  slots().forEach((sources, slot) => {
    const pane = document.createElement('div');
    pane.className = 'pane' + (sources.includes(state.active) ? ' active' : '');
    pane.dataset.slot = String(slot);
    const contents = sources.map((i) => contentOf(i));
    const bars = document.createElement('div');
    bars.className = 'bars';
    sources.forEach((i, k) => bars.appendChild(paneBar(i, contents[k])));
    pane.appendChild(bars);
    const viewport = document.createElement('div');
    viewport.className = 'viewport';
    pane.appendChild(viewport);
    sources.forEach((i, k) => {
      const content = contents[k];
      if (!content) return;
      first = first || content;
      const canvas = document.createElement('canvas');
      canvas.className = 'image ' + (k === 0 ? 'base' : 'top');
      canvas.dataset.pane = String(i);
      canvas.dataset.layer = content.layer.id;
      canvas.dataset.file = content.layer.id === 'image' ? content.file : content.layer.file || '';
      canvas.width = content.width;
      canvas.height = content.height;
      viewport.appendChild(canvas);
      const preview = content.layer.id === 'image' && content.preview && !isLoading(content.file) && state.ev === 0
        && state.display === DEFAULT_TRANSFORM;
      drawings.push({ draw: () => draw(i, canvas, content, generation), preview: preview && drawPreview(canvas, content, generation) });
    });
    if (sources.length === 2) {
      const divider = document.createElement('div');
      divider.className = 'divider';
      viewport.appendChild(divider);
    }
    const labels = document.createElement('canvas');
    labels.className = 'labels';
    viewport.appendChild(labels);
    const box = document.createElement('div');
    box.className = 'region-box';
    viewport.appendChild(box);
    sources.forEach((i, k) => pane.appendChild(paneInfo(i, contents[k])));
    pane.addEventListener('pointerdown', () => setActive(sources[sources.length - 1]));
    attachViewportEvents(viewport);
    container.appendChild(pane);
  });
  Promise.allSettled(drawings.map((d) => d.preview)).then(() => drawings.forEach((d) => d.draw()));
  if (!state.transform && first) {
    const vp = container.querySelector('.viewport');
    const pending = state.pendingView;
    state.pendingView = null;
    state.transform = pending && pending.zoom && pending.centre
      ? { scale: pending.zoom, tx: vp.clientWidth / 2 - pending.centre.x * pending.zoom, ty: vp.clientHeight / 2 - pending.centre.y * pending.zoom }
      : fit(vp.clientWidth, vp.clientHeight, first.width, first.height);
  }
  applyTransform();
  if (state.pixel) inspect(state.pixel);
  saveView();
}

// The runner's display PNG of an image, drawn while its EXR is read and decoded: the browser
// decodes a PNG off the page's thread in milliseconds, and at EV 0 in sRGB it is what the EXR's
// values draw as (to one level), so every pane shows at once and its values follow.
// The previews are drawn before any EXR is decoded, which would take the cores they need.
async function drawPreview(canvas, content, generation) {
  try {
    const response = await fetch(content.preview);
    if (!response.ok) return;
    const bitmap = await createImageBitmap(await response.blob(), { colorSpaceConversion: 'none' });
    if (canvas.dataset.drawn || generation !== state.generation || !canvas.isConnected) return;
    canvas.getContext('2d').drawImage(bitmap, 0, 0);
    canvas.dataset.drawn = 'preview';
  } catch (e) {
    // No preview: the values draw the pane when they arrive.
  }
}

// Draws pane i's values into its canvas, then its legend, values in pixels and statistics.
async function draw(i, canvas, content, generation) {
  const info = () => document.querySelector(`#panes .info[data-pane="${i}"]`);
  try {
    const image = await shownImage(i);
    if (generation !== state.generation || !canvas.isConnected) return;
    const manner = how(content.layer);
    canvas.width = image.width;
    canvas.height = image.height;
    canvas.getContext('2d').putImageData(drawImage(image, manner, results.colormaps), 0, 0);
    canvas.dataset.drawn = `${content.layer.id} ev ${state.ev} ${state.display}`;
    const legend = legendOf(image, manner);
    if (legend && info()) info().querySelector('.legend-slot').innerHTML = legendHtml(legend, results.colormaps, escapeHtml);
    drawLabels();
    showStats(i, image);
    if (state.pixel) inspect(state.pixel); // the hovered pixel's values, now that they are here
  } catch (e) {
    if (generation !== state.generation) return;
    canvas.dataset.drawn = 'error';
    if (info()) info().insertAdjacentHTML('afterbegin', `<div class="missing">${escapeHtml(e.message)}</div>`);
    console.warn(e);
  }
}

function setActive(paneIndex) {
  state.active = paneIndex;
  document.querySelectorAll('#panes .pane').forEach((p, slot) => p.classList.toggle('active', slots()[slot].includes(paneIndex)));
}

// Zoom and pan apply to every image alike; in swipe mode the top image is cut at the divider,
// which stays where it is on screen.
function applyTransform() {
  if (!state.transform) return;
  const css = cssTransform(state.transform);
  document.querySelectorAll('#panes canvas.image').forEach((c) => {
    c.style.transform = css;
  });
  document.querySelectorAll('#panes .viewport').forEach((vp) => {
    const top = vp.querySelector('canvas.top');
    const divider = vp.querySelector('.divider');
    if (top && divider) {
      const x = state.swipe * vp.clientWidth;
      divider.style.left = `${x}px`;
      // The clip is in the image's own (unscaled) coordinates.
      const left = Math.max(0, (x - state.transform.tx) / state.transform.scale);
      top.style.clipPath = `inset(0 0 0 ${left}px)`;
    }
    placeRegionBox(vp);
  });
  drawLabels();
}

function placeRegionBox(vp) {
  const box = vp.querySelector('.region-box');
  if (!box) return;
  box.hidden = !state.region;
  if (!state.region) return;
  const t = state.transform;
  Object.assign(box.style, {
    left: `${t.tx + state.region.x * t.scale}px`, top: `${t.ty + state.region.y * t.scale}px`,
    width: `${state.region.w * t.scale}px`, height: `${state.region.h * t.scale}px`,
  });
}

// Each pane's pixel values written inside its pixels, where they are large enough to hold them.
function drawLabels() {
  document.querySelectorAll('#panes .viewport').forEach((vp) => {
    const labels = vp.querySelector('canvas.labels');
    const base = vp.querySelector('canvas.image.base');
    if (!labels || !base) return;
    const i = Number(base.dataset.pane);
    const content = contentOf(i);
    const drawn = base.dataset.drawn && base.dataset.drawn !== 'error';
    const image = drawn ? shownNow.get(i) : null;
    drawPixelValues(labels, vp, state.transform, image, (values) => pixelColour(values, image, how(content.layer), results.colormaps));
  });
}

// The values each pane shows, once drawn (for the labels, the inspector and the statistics).
const shownNow = new Map();

function showStats(i, image) {
  shownNow.set(i, image);
  const info = document.querySelector(`#panes .info[data-pane="${i}"]`);
  const out = info && info.querySelector('.stats');
  if (!out) return;
  const r = state.region && clipRegion(state.region, image.width, image.height);
  out.textContent = '';
  delete out.dataset.mean;
  if (!r) return;
  const s = channelStats(image, r);
  const f = (xs) => xs.map((v) => v.toPrecision(4)).join(' ');
  out.dataset.mean = JSON.stringify(s.mean);
  out.dataset.max = JSON.stringify(s.max);
  let text = `rectangle (${r.x}, ${r.y}) ${r.w} x ${r.h}: mean ${f(s.mean)}, max ${f(s.max)}`;
  out.textContent = text;
  const c = comparedWith(i);
  const content = contentOf(i);
  if (!c || !content) return;
  const other = paneContent(results, state.sel, frameNumber(), { variant: c.variant, layer: 'image' }, false);
  if (!other) return;
  Promise.all([loadImage(content.file), loadImage(other.file)]).then(([a, b]) => {
    if (!out.isConnected || a.width !== b.width || a.height !== b.height) return;
    const e = errorStats(a, b, r);
    out.dataset.mae = JSON.stringify(e.mae);
    out.dataset.rmse = JSON.stringify(e.rmse);
    text += `; against ${comparedName(i)}: mean |A - B| ${f(e.mae)}, RMSE ${f(e.rmse)}`;
    if (content.layer.difference === 'flip') text += `, FLIP mean ${s.mean[0].toPrecision(4)}`;
    out.textContent = text;
  });
}

function attachViewportEvents(vp) {
  let drag = null;
  vp.addEventListener(
    'wheel',
    (e) => {
      e.preventDefault();
      const r = vp.getBoundingClientRect();
      state.transform = zoomAbout(state.transform, e.clientX - r.left, e.clientY - r.top, Math.exp(-e.deltaY * 0.002));
      applyTransform();
      inspectAt(vp, e);
      saveView();
    },
    { passive: false },
  );
  vp.addEventListener('pointerdown', (e) => {
    if (e.button !== 0) return;
    const r = vp.getBoundingClientRect();
    const at = imagePixel(state.transform, e.clientX - r.left, e.clientY - r.top);
    drag = { x: e.clientX, y: e.clientY, divider: e.target.classList.contains('divider'), region: e.shiftKey ? at : null };
    vp.setPointerCapture(e.pointerId);
  });
  vp.addEventListener('pointermove', (e) => {
    const r = vp.getBoundingClientRect();
    if (drag && drag.divider) {
      state.swipe = Math.min(1, Math.max(0, (e.clientX - r.left) / r.width));
      applyTransform();
    } else if (drag && drag.region) {
      const at = imagePixel(state.transform, e.clientX - r.left, e.clientY - r.top);
      const x = Math.min(drag.region.x, at.x);
      const y = Math.min(drag.region.y, at.y);
      const size = results.referenceRun(state.sel, frameNumber());
      state.region = clipRegion({ x, y, w: Math.abs(at.x - drag.region.x) + 1, h: Math.abs(at.y - drag.region.y) + 1 }, size.width, size.height);
      document.querySelectorAll('#panes .viewport').forEach(placeRegionBox);
    } else if (drag) {
      state.transform = pan(state.transform, e.clientX - drag.x, e.clientY - drag.y);
      drag.x = e.clientX;
      drag.y = e.clientY;
      applyTransform();
    }
    inspectAt(vp, e);
  });
  const end = () => {
    if (drag && drag.region) setRegion(state.region);
    else if (drag) saveView();
    drag = null;
  };
  vp.addEventListener('pointerup', end);
  vp.addEventListener('pointercancel', end);
}

function setRegion(region) {
  state.region = region;
  document.querySelectorAll('#panes .viewport').forEach(placeRegionBox);
  for (const [i, image] of shownNow) showStats(i, image);
  saveView();
}

function inspectAt(vp, e) {
  if (!state.transform) return;
  const r = vp.getBoundingClientRect();
  inspect(imagePixel(state.transform, e.clientX - r.left, e.clientY - r.top));
}

// The pixel's coordinates in the header and in every pane, with the values each pane shows there
// (an image's linear values and the colour drawn for them; a difference's or map's value).
function inspect(p) {
  state.pixel = p;
  const first = state.sel && results.referenceRun(state.sel, frameNumber());
  const inside = first && p.x >= 0 && p.y >= 0 && p.x < first.width && p.y < first.height;
  $('pixel').textContent = inside ? `pixel (${p.x}, ${p.y})` : '';
  document.querySelectorAll('#panes .info').forEach((info) => {
    const out = info.querySelector('.inspector');
    if (!out) return;
    const i = Number(info.dataset.pane);
    const image = shownNow.get(i);
    const values = inside && valuesAt(image, p.x, p.y);
    out.dataset.x = String(p.x);
    out.dataset.y = String(p.y);
    if (!values) {
      out.textContent = inside ? `(${p.x}, ${p.y})` : '';
      delete out.dataset.values;
      return;
    }
    out.dataset.values = JSON.stringify(values);
    const layer = contentOf(i).layer;
    const shown = pixelColour(values, image, how(layer), results.colormaps);
    const numbers = values.map((v) => v.toPrecision(4)).join(' ');
    if (image.kind === 'scalar') out.textContent = `(${p.x}, ${p.y}) ${how(layer).what} ${numbers}`;
    else if (image.kind === 'display') out.textContent = `(${p.x}, ${p.y}) RGB ${shown.join(' ')}`;
    else out.textContent = `(${p.x}, ${p.y}) RGB ${shown.join(' ')} | linear ${numbers}`;
  });
}

function stepFrame(delta) {
  const n = state.frames.length;
  state.frameIndex = (state.frameIndex + delta + n) % n;
  render();
}

function togglePlay() {
  if (state.player) {
    clearInterval(state.player);
    state.player = null;
  } else if (state.frames.length > 1) {
    state.player = setInterval(() => stepFrame(1), PLAY_INTERVAL_MS);
  }
  $('play').textContent = state.player ? 'pause' : 'play';
}

// A change of the panes' number or width fits the image again.
function refit() {
  state.transform = null;
  render();
}

function setMode(mode) {
  const refitNeeded = (mode === 'side') !== (state.mode === 'side');
  state.mode = mode;
  if (mode !== 'side' && state.paneCount < 2) state.paneCount = 2;
  if (refitNeeded) refit();
  else render();
}

function flip() {
  if (state.mode !== 'flip') {
    state.flipSecond = false;
    setMode('flip');
  } else {
    state.flipSecond = !state.flipSecond;
    render();
  }
}

function cycleErrorMaps() {
  const next = nextErrorLayer(state.panes[state.active].layer);
  state.panes.forEach((p) => {
    p.layer = next;
  });
  render();
}

function pickVariant(n) {
  const choices = [REFERENCE, ...state.variants];
  if (n >= 1 && n <= choices.length) {
    state.panes[state.active].variant = choices[n - 1];
    render();
  }
}

function setExposure(ev) {
  state.ev = Math.max(-EV_LIMIT, Math.min(EV_LIMIT, Math.round(ev / EV_STEP) * EV_STEP));
  render();
}

// The searchable list: a variant by its menu label (or its name) into the active pane.
function findVariant(text) {
  const v = [REFERENCE, ...state.variants].find((x) => variantLabel(x) === text || x === text);
  if (!v) return false;
  state.panes[state.active].variant = v;
  render();
  return true;
}

function toggleHelp(show) {
  const help = $('help');
  help.innerHTML = helpHtml(escapeHtml);
  help.hidden = show === undefined ? !help.hidden : !show;
}

const ACTIONS = {
  help: () => toggleHelp(),
  close: () => toggleHelp(false),
  flip,
  errors: cycleErrorMaps,
  previous: () => stepFrame(-1),
  next: () => stepFrame(1),
  play: togglePlay,
  side: () => setMode('side'),
  swipe: () => setMode('swipe'),
  fit: refit,
  overlays: () => document.body.classList.toggle('no-overlays'),
  brighter: () => setExposure(state.ev + EV_STEP),
  darker: () => setExposure(state.ev - EV_STEP),
  falseColour: () => {
    state.display = state.display === 'false' ? DEFAULT_TRANSFORM : 'false';
    render();
  },
  clearRegion: () => setRegion(null),
  find: () => $('find').focus(),
};

// The view as the address holds it (view_state.js), kept there as it changes.
function currentView() {
  const vp = document.querySelector('#panes .viewport');
  const t = state.transform;
  return {
    ...state.sel, frame: frameNumber(), panes: state.panes, paneCount: state.paneCount, mode: state.mode,
    zoom: t && vp ? t.scale : null, centre: t && vp ? { x: (vp.clientWidth / 2 - t.tx) / t.scale, y: (vp.clientHeight / 2 - t.ty) / t.scale } : null,
    ev: state.ev, display: state.display, region: state.region,
  };
}

let saving = null;
function saveView() {
  clearTimeout(saving);
  saving = setTimeout(() => history.replaceState(null, '', '#' + encodeView(currentView())), 50);
}

// The address's view: `#run=ID` (the report's links: the run's scene, size, view and frame with
// the reference in the first pane and the run's setting in the second), or a whole view; a run or
// scene the result set does not have opens the first scene, saying so.
function openFromHash() {
  const v = decodeView(location.hash);
  notice('');
  if (v && v.run !== undefined) {
    const run = results.byId.get(v.run);
    if (run) select(run.scene, run.size, run.view, run.frame, [run.variant]);
    else {
      select(null, null, null, null, []);
      notice(`This result set has no run "${v.run}" (the link may be from another result set, or the run was not kept): showing ${state.sel.scene} instead.`);
    }
  } else if (v) {
    select(v.scene, v.size, v.view, v.frame, []);
    if (state.sel.scene !== v.scene || state.sel.size !== v.size || state.sel.view !== v.view) {
      notice(`This result set has no ${v.scene} ${v.size} ${v.view}: showing ${state.sel.scene} ${state.sel.size} ${state.sel.view} instead.`);
    } else {
      v.panes.slice(0, MAX_PANES).forEach((p, i) => {
        if (p.variant === REFERENCE || state.variants.includes(p.variant)) state.panes[i] = { variant: p.variant, layer: p.layer, against: p.against };
      });
      if (v.paneCount >= 1 && v.paneCount <= MAX_PANES) state.paneCount = v.paneCount;
      if (['side', 'flip', 'swipe'].includes(v.mode)) state.mode = v.mode;
      if (v.ev !== null) state.ev = Math.max(-EV_LIMIT, Math.min(EV_LIMIT, v.ev));
      if (DISPLAY_TRANSFORMS.some((t) => t.id === v.display)) state.display = v.display;
      state.region = v.region;
      state.pendingView = v.zoom ? { zoom: v.zoom, centre: v.centre } : null;
    }
  } else {
    select(null, null, null, null, []);
  }
  render();
}

function wire() {
  $('scene').addEventListener('change', () => {
    select($('scene').value, state.sel.size, null, null, []);
    render();
  });
  $('size').addEventListener('change', () => {
    select(state.sel.scene, $('size').value, state.sel.view, frameNumber(), state.panes.map((p) => p.variant));
    render();
  });
  $('view').addEventListener('change', () => {
    select(state.sel.scene, state.sel.size, $('view').value, null, state.panes.map((p) => p.variant));
    render();
  });
  $('pane-count').addEventListener('change', () => {
    state.paneCount = Number($('pane-count').value);
    state.active = Math.min(state.active, state.paneCount - 1);
    refit();
  });
  $('mode').addEventListener('change', () => setMode($('mode').value));
  $('frame').addEventListener('input', () => {
    state.frameIndex = Number($('frame').value);
    render();
  });
  $('play').addEventListener('click', togglePlay);
  fillSelect($('transform'), DISPLAY_TRANSFORMS.map((t) => t.id), state.display, (id) => DISPLAY_TRANSFORMS.find((t) => t.id === id).name);
  $('ev').addEventListener('input', () => setExposure(Number($('ev').value)));
  $('transform').addEventListener('change', () => {
    state.display = $('transform').value;
    render();
  });
  $('find').addEventListener('change', () => {
    if (findVariant($('find').value)) $('find').value = '';
  });
  $('fit').addEventListener('click', ACTIONS.fit);
  $('help-button').addEventListener('click', () => toggleHelp());
  $('notice').querySelector('button').addEventListener('click', () => notice(''));
  document.addEventListener('keydown', (e) => {
    // Menus and the slider keep their own keys.
    if (e.target instanceof HTMLSelectElement || e.target instanceof HTMLInputElement) return;
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const action = actionOf(e.key);
    if (!action) return;
    e.preventDefault();
    if (action === 'pick') pickVariant(Number(e.key));
    else ACTIONS[action]();
  });
  window.addEventListener('hashchange', () => {
    if (location.hash.slice(1) !== encodeView(currentView())) openFromHash();
  });
  window.addEventListener('resize', refit);
}

async function fetchJson(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: ${response.status} ${response.statusText}`);
  return response.json();
}

async function start() {
  try {
    const settings = await fetchJson('viewer/settings.json');
    results = new ResultSet(await fetchJson(`${settings.result_set}/results.json`), settings);
  } catch (e) {
    notice(`The viewer cannot read its result set: ${e.message}`);
    return;
  }
  wire();
  openFromHash();
}

start();
