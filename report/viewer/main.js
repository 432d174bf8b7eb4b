// The viewer page: up to eight panes side by side (or one pane in flip or swipe mode) showing the
// reference and technique variants of one scene, size, view and frame, with shared zoom and pan,
// exposure and display transform of the linear images, error maps on one scale, a pixel inspector
// and keyboard shortcuts. The result set comes from viewer/manifest.js.

import { ResultSet, REFERENCE } from './result_set.js';
import { fit, zoomAbout, pan, imagePixel, cssTransform } from './view_transform.js';
import { paneContent, nextErrorLayer } from './pane_content.js';
import { pixelData, rgbaAt, mapValue } from './pixels.js';
import { actionOf, helpHtml } from './shortcuts.js';
import { DISPLAY_TRANSFORMS, DEFAULT_TRANSFORM, linearData, linearAt, displayRgb, isIdentity, drawLinear } from './display.js';
import { sharedRange, sameRange, recolour } from './error_scale.js';
import { debugLegendHtml } from './debug_legends.js';

const MAX_PANES = 8;
const EV_STEP = 0.5;
const EV_LIMIT = 10;
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
  ev: 0, // exposure of the linear images: values times 2^ev
  display: DEFAULT_TRANSFORM, // the display transform of the linear images
  sharedScale: true, // error maps on one scale per scene, size and metric (else each pane its own)
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
  // The panes open on the reference and one setting of each technique (its default where it ran);
  // the rest follow, for the pane count menu.
  const defaults = results.defaultVariants(state.sel);
  const first = [...variantsFirst, ...defaults].filter((v, i, all) => state.variants.includes(v) && all.indexOf(v) === i);
  const order = [...first, ...state.variants.filter((v) => !first.includes(v))];
  state.panes = [REFERENCE, ...order].slice(0, MAX_PANES).map((variant) => ({ variant, layer: 'image' }));
  while (state.panes.length < MAX_PANES) state.panes.push({ variant: order[0] || REFERENCE, layer: 'image' });
  state.paneCount = Math.min(MAX_PANES, 1 + first.length);
  state.active = Math.min(1, state.paneCount - 1);
  state.transform = null;
  fillSelect($('scene'), results.scenes(), scene);
  fillSelect($('size'), sizes, size);
  fillSelect($('view'), views, view);
  $('pane-count').value = String(state.paneCount);
  $('variant-list').innerHTML = [REFERENCE, ...state.variants].map((v) => `<option value="${escapeHtml(variantLabel(v))}"></option>`).join('');
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

// The range a map layer is drawn over: the shared one of its scene, size and metric, or its own.
function mapRange(layer) {
  const shared = state.sharedScale && sharedRange(results, state.sel, layer.id);
  return shared || layer.legend.range;
}

function legendHtml(legend, range, shared) {
  const table = results.colormaps[legend.colormap];
  if (!table) return '';
  const stops = table.filter((_, i) => i % 16 === 0 || i === table.length - 1).map((c) => `rgb(${c[0]},${c[1]},${c[2]})`);
  const fmt = (v) => Number(v).toPrecision(3);
  return `<div class="legend"><div class="bar" style="background:linear-gradient(to right,${stops.join(',')})"></div>`
    + `<div class="ends"><span class="lo">${fmt(range[0])}</span><span>${escapeHtml(legend.colormap)}</span><span class="hi">${fmt(range[1])}</span></div>`
    + `<div class="scale">${shared ? 'scale shared by every pane (M: per pane)' : "this pane's own scale (M: shared)"}</div></div>`;
}

function infoHtml(c) {
  const lines = [`<div class="title">${escapeHtml(c.title)}</div>`];
  if (c.parameters) lines.push(`<div class="params">${escapeHtml(c.parameters)}</div>`);
  if (c.run && c.run.not_applicable) lines.push(`<div class="not-applicable">not applicable here: ${escapeHtml(c.run.not_applicable)}</div>`);
  lines.push(`<div class="time">frame ${c.frameMs.toFixed(2)} ms</div>`);
  if (c.stages) {
    const s = Object.entries(c.stages).map(([k, v]) => `${escapeHtml(k)} ${v.toFixed(2)}`).join('<br>');
    lines.push(`<div class="stages">${s}</div>`);
  }
  const m = c.metrics;
  if (m) {
    const f = (v, d) => (v === null || v === undefined ? '-' : v.toFixed(d));
    // HDR-FLIP is absent (a dash) in result sets written before the runner scored it.
    lines.push(
      `<div class="metrics">SSIM ${f(m.ssim, 4)} &middot; FLIP (LDR) ${f(m.flip, 4)} &middot; HDR-FLIP ${f(m.flip_hdr, 4)} &middot; PSNR ${f(m.psnr, 2)} dB</div>`,
    );
    if (m.masked_ssim !== null && m.masked_ssim !== undefined) {
      lines.push(
        `<div class="metrics masked">refl./refr.: SSIM ${f(m.masked_ssim, 4)} &middot; FLIP (LDR) ${f(m.masked_flip, 4)} &middot; HDR-FLIP ${f(m.masked_flip_hdr, 4)}</div>`,
      );
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
  variants.title = variantLabel(state.panes[paneIndex].variant);
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
  const layer = content.layer;
  let legend = '';
  if (layer.legend) legend = legendHtml(layer.legend, mapRange(layer), state.sharedScale);
  else if (layer.id.startsWith('debug:')) legend = debugLegendHtml(layer.id.slice('debug:'.length), escapeHtml);
  div.insertAdjacentHTML('beforeend', infoHtml(content) + legend);
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
  img.dataset.drawn = 'png';
  redraw(img, content.layer, content.height);
  return img;
}

// Images drawn from their linear data under the exposure and transform, and error maps coloured
// over the shared scale: the PNG first, replaced when the data has loaded.
function redraw(img, layer, height) {
  const file = layer.file;
  if (layer.id === 'image' && !isIdentity(state.ev, state.display)) {
    const ev = state.ev;
    const display = state.display;
    linearData(file, results.linearScripts[file]).then((data) => {
      if (!data || !img.isConnected || ev !== state.ev || display !== state.display) return;
      img.src = drawLinear(file, data, ev, display);
      img.dataset.drawn = `ev ${ev} ${display}`;
    });
  } else if (layer.legend && state.sharedScale && !sameRange(mapRange(layer), layer.legend.range)) {
    const range = mapRange(layer);
    const table = results.colormaps[layer.legend.colormap];
    pixelData(file, results.pixelScripts[file]).then((data) => {
      if (!data || !table || !img.isConnected) return;
      img.src = recolour(file, data, table, layer.legend.range, range, height);
      img.dataset.drawn = `scale ${range.join(' ')}`;
    });
  }
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
  const n = slots().length;
  container.style.gridTemplateColumns = `repeat(${n <= 4 ? n : Math.ceil(n / 2)}, minmax(0, 1fr))`;
  $('ev').value = String(state.ev);
  $('ev-label').textContent = `EV ${state.ev >= 0 ? '+' : ''}${state.ev.toFixed(1)}`;
  $('transform').value = state.display;
  $('shared-scale').checked = state.sharedScale;
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
    const linear = layer.id === 'image' ? linearData(layer.file, results.linearScripts[layer.file]) : Promise.resolve(null);
    Promise.all([pixelData(layer.file, results.pixelScripts[layer.file]), linear]).then(([data, lin]) => {
      if (state.pixel !== p || !out.isConnected) return;
      const rgba = rgbaAt(data, p.x, p.y);
      const rgb = linearAt(lin, p.x, p.y);
      if (rgb) {
        // The displayed colour (under the exposure and transform) beside the linear value.
        const d = displayRgb(rgb, state.ev, state.display);
        out.textContent = `${where} RGB ${d[0]} ${d[1]} ${d[2]} | linear ${rgb.map((v) => v.toPrecision(4)).join(' ')}`;
      } else if (!rgba) {
        return;
      } else if (layer.legend && results.colormaps[layer.legend.colormap]) {
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

function setExposure(ev) {
  state.ev = Math.max(-EV_LIMIT, Math.min(EV_LIMIT, Math.round(ev / EV_STEP) * EV_STEP));
  render();
}

function toggleSharedScale() {
  state.sharedScale = !state.sharedScale;
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
  scale: toggleSharedScale,
  find: () => $('find').focus(),
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
fillSelect($('transform'), DISPLAY_TRANSFORMS.map((t) => t.id), state.display, (id) => DISPLAY_TRANSFORMS.find((t) => t.id === id).name);
$('ev').addEventListener('input', () => setExposure(Number($('ev').value)));
$('transform').addEventListener('change', () => {
  state.display = $('transform').value;
  render();
});
$('shared-scale').addEventListener('change', toggleSharedScale);
$('find').addEventListener('change', () => {
  if (findVariant($('find').value)) $('find').value = '';
});
$('fit').addEventListener('click', ACTIONS.fit);
$('help-button').addEventListener('click', () => toggleHelp());
window.addEventListener('hashchange', openFromHash);
window.addEventListener('resize', refit);

if (!openFromHash()) select(null, null, null, null, []);
