// The viewer page: up to four panes side by side (or one pane in flip or swipe mode) showing the
// reference and technique variants of one scene, size, view and frame, with shared zoom and pan,
// a pixel inspector and keyboard shortcuts. The result set comes from viewer/manifest.js.

import { ResultSet, REFERENCE } from './result_set.js';
import { fit, zoomAbout, pan, imagePixel, cssTransform } from './view_transform.js';
import { paneContent, nextErrorLayer } from './pane_content.js';
import { pixelData, rgbaAt, mapValue } from './pixels.js';
import { actionOf, helpHtml } from './shortcuts.js';

const MAX_PANES = 4;
const PLAY_INTERVAL_MS = 700;

const results = new ResultSet(window.HYBRIDLAB_MANIFEST);
const $ = (id) => document.getElementById(id);
const escapeHtml = (s) => String(s).replace(/[&<>"']/g, (c) => `&#${c.charCodeAt(0)};`);

const state = {
  sel: null, // { scene, size, view }
  frames: [],
  frameIndex: 0,
  variants: [],
  panes: [], // { variant, layer } each
  paneCount: MAX_PANES,
  mode: 'side', // 'side' | 'flip' | 'swipe'
  flipSecond: false,
  swipe: 0.5, // the divider, a fraction of the viewport width
  transform: null, // shared zoom and pan; null: fit at the next render
  active: 1,
  player: null,
  pixel: null, // the inspected pixel
};

function fillSelect(select, values, current, label = (v) => v) {
  select.innerHTML = values.map((v) => `<option value="${escapeHtml(v)}">${escapeHtml(label(v))}</option>`).join('');
  select.value = current;
}

// Scene, size and view (each defaulting to the first available), frame index and pane choices.
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
  const order = [...variantsFirst.filter((v) => state.variants.includes(v)), ...state.variants.filter((v) => !variantsFirst.includes(v))];
  state.panes = [REFERENCE, ...order].slice(0, MAX_PANES).map((variant) => ({ variant, layer: 'image' }));
  while (state.panes.length < MAX_PANES) state.panes.push({ variant: order[0] || REFERENCE, layer: 'image' });
  state.paneCount = Math.min(MAX_PANES, 1 + state.variants.length);
  state.active = Math.min(1, state.paneCount - 1);
  state.transform = null;
  fillSelect($('scene'), results.scenes(), scene);
  fillSelect($('size'), sizes, size);
  fillSelect($('view'), views, view);
  $('pane-count').value = String(state.paneCount);
  $('frame').max = String(state.frames.length - 1);
  $('frame-controls').hidden = state.frames.length < 2;
  render();
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

function legendHtml(legend) {
  const table = results.colormaps[legend.colormap];
  if (!table) return '';
  const stops = table.filter((_, i) => i % 16 === 0 || i === table.length - 1).map((c) => `rgb(${c[0]},${c[1]},${c[2]})`);
  const fmt = (v) => Number(v).toPrecision(3);
  return `<div class="legend"><div class="bar" style="background:linear-gradient(to right,${stops.join(',')})"></div>`
    + `<div class="ends"><span>${fmt(legend.range[0])}</span><span>${escapeHtml(legend.colormap)}</span><span>${fmt(legend.range[1])}</span></div></div>`;
}

function infoHtml(c) {
  const lines = [`<div class="title">${escapeHtml(c.title)}</div>`];
  if (c.parameters) lines.push(`<div class="params">${escapeHtml(c.parameters)}</div>`);
  lines.push(`<div class="time">frame ${c.frameMs.toFixed(2)} ms</div>`);
  if (c.stages) {
    const s = Object.entries(c.stages).map(([k, v]) => `${escapeHtml(k)} ${v.toFixed(2)}`).join('<br>');
    lines.push(`<div class="stages">${s}</div>`);
  }
  const m = c.metrics;
  if (m) {
    const f = (v, d) => (v === null || v === undefined ? '-' : v.toFixed(d));
    lines.push(`<div class="metrics">SSIM ${f(m.ssim, 4)} &middot; FLIP ${f(m.flip, 4)} &middot; PSNR ${f(m.psnr, 2)} dB</div>`);
    if (m.masked_ssim !== null && m.masked_ssim !== undefined) {
      lines.push(`<div class="metrics masked">refl./refr.: SSIM ${f(m.masked_ssim, 4)} &middot; FLIP ${f(m.masked_flip, 4)}</div>`);
    }
    if (m.temporal !== null && m.temporal !== undefined) lines.push(`<div class="metrics">temporal ${f(m.temporal, 5)}</div>`);
  }
  return lines.join('');
}

function overlay(paneIndex, content, side) {
  const div = document.createElement('div');
  div.className = 'overlay ' + side;
  div.dataset.pane = String(paneIndex);
  const variants = document.createElement('select');
  variants.className = 'variant';
  fillSelect(variants, [REFERENCE, ...state.variants], state.panes[paneIndex].variant, variantLabel);
  variants.addEventListener('change', () => {
    state.panes[paneIndex].variant = variants.value;
    render();
  });
  div.appendChild(variants);
  if (!content) {
    div.insertAdjacentHTML('beforeend', '<div class="missing">no run at this frame</div>');
    return div;
  }
  const layers = document.createElement('select');
  layers.className = 'layer';
  fillSelect(layers, content.layers.map((l) => l.id), content.layer.id, (id) => content.layers.find((l) => l.id === id).name);
  layers.addEventListener('change', () => {
    state.panes[paneIndex].layer = layers.value;
    render();
  });
  div.appendChild(layers);
  div.insertAdjacentHTML('beforeend', infoHtml(content) + (content.layer.legend ? legendHtml(content.layer.legend) : ''));
  const inspector = document.createElement('div');
  inspector.className = 'inspector';
  div.appendChild(inspector);
  return div;
}

function image(paneIndex, content, cls) {
  const img = document.createElement('img');
  img.className = 'image ' + cls;
  img.dataset.pane = String(paneIndex);
  img.dataset.file = content.layer.file;
  img.dataset.layer = content.layer.id;
  img.alt = `${content.title} ${content.layer.name}`;
  img.draggable = false;
  img.src = content.layer.file;
  return img;
}

function render() {
  const sel = state.sel;
  const frame = frameNumber();
  $('frame').value = String(state.frameIndex);
  $('frame-label').textContent = `frame ${frame} (${state.frameIndex + 1} of ${state.frames.length})`;
  $('mode').value = state.mode;
  document.title = `hybridlab viewer: ${sel.scene} ${sel.size} ${sel.view}` + (frame >= 0 ? ` @ ${frame}` : '');
  const container = $('panes');
  container.innerHTML = '';
  let first = null;
  slots().forEach((sources, slot) => {
    const pane = document.createElement('div');
    pane.className = 'pane' + (sources.includes(state.active) ? ' active' : '');
    pane.dataset.slot = String(slot);
    const viewport = document.createElement('div');
    viewport.className = 'viewport';
    pane.appendChild(viewport);
    sources.forEach((paneIndex, k) => {
      const content = paneContent(results, sel, frame, state.panes[paneIndex]);
      if (content) {
        first = first || content;
        const img = image(paneIndex, content, k === 0 ? 'base' : 'top');
        if (k === 1) img.style.clipPath = `inset(0 0 0 0)`;
        viewport.appendChild(img);
      }
      pane.appendChild(overlay(paneIndex, content, k === 0 ? 'left' : 'right'));
    });
    if (sources.length === 2) {
      const divider = document.createElement('div');
      divider.className = 'divider';
      viewport.appendChild(divider);
    }
    pane.addEventListener('pointerdown', () => setActive(sources[sources.length - 1]));
    attachViewportEvents(viewport);
    container.appendChild(pane);
  });
  if (!state.transform && first) {
    const vp = container.querySelector('.viewport');
    state.transform = fit(vp.clientWidth, vp.clientHeight, first.width, first.height);
  }
  applyTransform();
  if (state.pixel) inspect(state.pixel);
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
  document.querySelectorAll('#panes img.image').forEach((img) => {
    img.style.transform = css;
  });
  document.querySelectorAll('#panes .viewport').forEach((vp) => {
    const top = vp.querySelector('img.top');
    const divider = vp.querySelector('.divider');
    if (!top || !divider) return;
    const x = state.swipe * vp.clientWidth;
    divider.style.left = `${x}px`;
    // The clip is in the image's own (unscaled) coordinates.
    const left = Math.max(0, (x - state.transform.tx) / state.transform.scale);
    top.style.clipPath = `inset(0 0 0 ${left}px)`;
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
    },
    { passive: false },
  );
  vp.addEventListener('pointerdown', (e) => {
    if (e.button !== 0) return;
    drag = { x: e.clientX, y: e.clientY, divider: e.target.classList.contains('divider') };
    vp.setPointerCapture(e.pointerId);
  });
  vp.addEventListener('pointermove', (e) => {
    if (drag && drag.divider) {
      const r = vp.getBoundingClientRect();
      state.swipe = Math.min(1, Math.max(0, (e.clientX - r.left) / r.width));
      applyTransform();
    } else if (drag) {
      state.transform = pan(state.transform, e.clientX - drag.x, e.clientY - drag.y);
      drag.x = e.clientX;
      drag.y = e.clientY;
      applyTransform();
    }
    inspectAt(vp, e);
  });
  const end = () => {
    drag = null;
  };
  vp.addEventListener('pointerup', end);
  vp.addEventListener('pointercancel', end);
}

function inspectAt(vp, e) {
  if (!state.transform) return;
  const r = vp.getBoundingClientRect();
  inspect(imagePixel(state.transform, e.clientX - r.left, e.clientY - r.top));
}

// The pixel's coordinates in the header and in every pane, with the value each pane shows there:
// display RGB (8 bits) of images, the error value of error maps.
function inspect(p) {
  state.pixel = p;
  const first = state.sel && results.referenceRun(state.sel, frameNumber());
  const inside = first && p.x >= 0 && p.y >= 0 && p.x < first.width && p.y < first.height;
  $('pixel').textContent = inside ? `pixel (${p.x}, ${p.y})` : '';
  document.querySelectorAll('#panes .overlay').forEach((ov) => {
    const out = ov.querySelector('.inspector');
    if (!out) return;
    const paneIndex = Number(ov.dataset.pane);
    const content = paneContent(results, state.sel, frameNumber(), state.panes[paneIndex]);
    out.dataset.x = String(p.x);
    out.dataset.y = String(p.y);
    if (!inside) {
      out.textContent = '';
      return;
    }
    const where = `(${p.x}, ${p.y})`;
    out.textContent = where;
    const layer = content.layer;
    pixelData(layer.file, results.pixelScripts[layer.file]).then((data) => {
      if (state.pixel !== p || !out.isConnected) return;
      const rgba = rgbaAt(data, p.x, p.y);
      if (!rgba) return;
      if (layer.legend && results.colormaps[layer.legend.colormap]) {
        out.textContent = `${where} ${layer.id} ${mapValue(rgba, results.colormaps[layer.legend.colormap], layer.legend.range).toPrecision(3)}`;
      } else {
        out.textContent = `${where} RGB ${rgba[0]} ${rgba[1]} ${rgba[2]}`;
      }
    });
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
};

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

// `#run=ID` (the report's links) opens the run's scene, size, view and frame with the reference
// in the first pane and the run's technique variant in the second.
function openFromHash() {
  const id = new URLSearchParams(location.hash.slice(1)).get('run');
  const run = id && results.byId.get(id);
  if (run) select(run.scene, run.size, run.view, run.frame, [run.variant]);
  return Boolean(run);
}

$('scene').addEventListener('change', () => select($('scene').value, state.sel.size, null, null, []));
$('size').addEventListener('change', () => select(state.sel.scene, $('size').value, state.sel.view, frameNumber(), state.panes.map((p) => p.variant)));
$('view').addEventListener('change', () => select(state.sel.scene, state.sel.size, $('view').value, null, state.panes.map((p) => p.variant)));
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
$('fit').addEventListener('click', ACTIONS.fit);
$('help-button').addEventListener('click', () => toggleHelp());
window.addEventListener('hashchange', openFromHash);
window.addEventListener('resize', refit);

if (!openFromHash()) select(null, null, null, null, []);
