// The viewer in a real browser. Two result sets: a small one the runner makes (whitted-classic at
// 64x36, three frames of the orbit path, two techniques), and one at the paper configs' size made up
// here (105 runs at 1280x720, their EXRs written with known values: synthetic_result_set.mjs).
// `hybridlab report` writes each one's report and viewer, `hybridlab view` serves them on 127.0.0.1
// (started and stopped here), and headless Chromium (Debian's, driven by playwright-core) checks:
// the records validate against experiments/results.schema.json; the paper-size set opens in under
// 5 s, the viewer's own files are under 5 MB, and the values read back are the EXRs' own; the EXRs
// OpenEXR wrote decode to the runner's display PNGs; FLIP of a pane against the reference gives the
// runner's FLIP mean; the difference of two chosen panes, and a rectangle's statistics, hold the
// values computed here from the files; a link restores a whole view; an unknown run and a page
// opened from the file system each get a notice; zoom, flip, swipe, frames, layers, exposure and
// the searchable list work; values are written inside pixels when zoomed in; one setting has one
// colour on three charts and in the viewer; the report's verdict names the known answer and its
// links open the viewer; no console error on the way.
//
//   node viewer_test.mjs HYBRIDLAB_BIN WORK_DIR
//
// Leaves WORK_DIR/{report-top,chart,viewer,viewer-difference,paper-scale}.png (screenshots) and the
// result sets and reports behind as artifacts.
import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { writeSyntheticSet } from './synthetic_result_set.mjs';

const CHROMIUM = '/usr/bin/chromium';
const [hybridlab, workArg] = process.argv.slice(2);
const work = workArg && path.resolve(workArg);
if (!hybridlab || !workArg) {
  console.error('usage: node viewer_test.mjs HYBRIDLAB_BIN WORK_DIR');
  process.exit(2);
}
if (!fs.existsSync(CHROMIUM)) {
  console.error(`${CHROMIUM} is missing: ./setup.sh installs Debian's chromium for this test`);
  process.exit(1);
}
let chromium, resultsSchema;
try {
  ({ chromium } = await import('playwright-core'));
  resultsSchema = await import('./results_schema.mjs');  // imports ajv
} catch (error) {
  if (error.code !== 'ERR_MODULE_NOT_FOUND') throw error;
  const here = path.dirname(fileURLToPath(import.meta.url));
  // A skip, as GoogleTest prints one (tests/support/skip_summary.py reads it): the npm packages come
  // only with `./setup.sh --tests`, whose npm step may fail without stopping the build.
  console.log(`Skipped\nplaywright-core or ajv is missing (npm ci in ${here} failed or did not run: ./setup.sh --tests)\n[  SKIPPED ] ViewerInBrowser`);
  process.exit(77);
}

const CONFIG = `
[experiment]
name = "viewer-test"
warmup_frames = 0
repeats = 1
keep = ["error_maps", "debug_images"]

[reference]
params = { max_depth = 4 }

[[scenes]]
scene = "whitted-classic"
resolutions = [[64, 36]]
[[scenes.views]]
path = "orbit"
frames = [0, 40]
stride = 20

[[techniques]]
name = "whitted"
label = "depth1"
params = { max_depth = 1 }

[[techniques]]
name = "rt_only"
params = { importance_cutoff = 0.01 }
`;

function hybridlabRun(args) {
  const r = spawnSync(hybridlab, args, { encoding: 'utf8' });
  assert.equal(r.status, 0, `hybridlab ${args.join(' ')} failed:\n${r.stdout}\n${r.stderr}`);
}

// Runs write debug images only where a technique makes them (images.debug.NAME in a record).
// Where none does, every run of the first technique gets one in that format (a copy of its
// difference map) so that the viewer's generic listing of debug images is exercised.
function ensureDebugImages(resultDir) {
  const file = path.join(resultDir, 'results.json');
  const records = JSON.parse(fs.readFileSync(file, 'utf8'));
  if (records.some((r) => r.images.debug)) return;
  for (const r of records.filter((x) => x.label === records[0].label)) {
    const png = `images/${r.id}.mask.png`;
    fs.copyFileSync(path.join(resultDir, r.images.maps, 'diff.png'), path.join(resultDir, png));
    r.images.debug = { mask: png };
  }
  fs.writeFileSync(file, JSON.stringify(records, null, 1));
}

fs.rmSync(work, { recursive: true, force: true });
fs.mkdirSync(work, { recursive: true });
fs.writeFileSync(path.join(work, 'viewer-test.toml'), CONFIG);
const resultDir = path.join(work, 'results');
const reportDir = path.join(resultDir, 'report');
hybridlabRun(['run', path.join(work, 'viewer-test.toml'), '--out', resultDir, '--cache', path.join(work, 'cache')]);
ensureDebugImages(resultDir);
// The records the viewer reads hold to the results schema, validated on this side by Ajv against
// experiments/results.schema.json (the file the C++ writer's tests and results.py validate
// against), and records broken in known ways are refused, each with the one problem naming its
// field (a validator that accepts anything fails).
{
  const validateRecord = resultsSchema.recordValidator();
  const records = JSON.parse(fs.readFileSync(path.join(resultDir, 'results.json'), 'utf8'));
  const problems = resultsSchema.resultsProblems(records, validateRecord);
  assert.deepEqual(problems, [], `results.json breaks experiments/results.schema.json:\n${problems.join('\n')}`);
  const broken = [
    [(r) => delete r.id, "$: missing required 'id'"],
    [(r) => { r.width = '64'; }, '$.width: must be integer'],
    [(r) => { r.frame = -2; }, '$.frame: must be >= -1'],
    [(r) => delete r.frame_ms.median, "$.frame_ms: missing required 'median'"],
    [(r) => { r.colour = 1; }, "$: unexpected 'colour'"],
    [(r) => { r.images.png = 7; }, '$.images.png: must be string'],
    [(r) => { r.metrics.whole.pixels = -1; }, '$.metrics.whole.pixels: must be >= 0'],
  ];
  for (const [breakIt, expected] of broken) {
    const record = structuredClone(records[0]);
    breakIt(record);
    assert.deepEqual(validateRecord(record), [expected]);
  }
  assert.deepEqual(resultsSchema.resultsProblems({}), ['results.json: expected an array of records']);
  console.log(`ok - ${records.length} records of results.json validate against the schema (Ajv); ${broken.length} broken ones are refused`);
}
hybridlabRun(['report', resultDir, '--out', reportDir]);
const records = JSON.parse(fs.readFileSync(path.join(resultDir, 'results.json'), 'utf8'));
const variantOf = (r) => r.label + (r.parameters_text ? ` [${r.parameters_text}]` : '');
// The runs as the viewer names their files (relative to viewer.html in RESULTS/report).
const runs = records.map((r) => ({
  ...r, variant: variantOf(r), file: `../${r.images.exr}`, referenceFile: `../${r.reference.exr}`,
  maps: Object.fromEntries(Object.entries(r.metrics.maps || {}).map(([k, m]) => [k, `../${r.images.maps}/${m.file}`])),
}));
const settings = JSON.parse(fs.readFileSync(path.join(reportDir, 'viewer', 'settings.json'), 'utf8'));

let passed = 0;
async function check(name, body) {
  await body();
  passed += 1;
  console.log(`ok - ${name}`);
}

// `hybridlab view`, started in its own process group (a terminal's Ctrl-C reaches the whole
// group), until it prints the viewer's address.
async function serve(dir, report) {
  const args = ['view', dir, '--port', '0', ...(report ? ['--report', report] : [])];
  const child = spawn(hybridlab, args, { stdio: ['ignore', 'pipe', 'pipe'], detached: true });
  let out = '';
  child.stderr.on('data', (d) => { out += d; });
  const viewer = await new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`hybridlab view printed no address in 60 s:\n${out}`)), 60_000);
    child.stdout.on('data', (d) => {
      out += d;
      const m = /viewer: (http:\/\/127\.0\.0\.1:\d+\/\S*viewer\.html)/.exec(out);
      if (m) {
        clearTimeout(timer);
        resolve(m[1]);
      }
    });
    child.on('exit', (code) => reject(new Error(`hybridlab view exited with ${code}:\n${out}`)));
  });
  assert.match(out, /serving .* on http:\/\/127\.0\.0\.1:\d+\/ \(Ctrl-C stops\)/);
  // Ctrl-C: the group gets SIGINT; the server says it stopped and the program exits with 0.
  const stop = async () => {
    const exited = new Promise((resolve) => child.on('exit', (code, signal) => resolve({ code, signal })));
    process.kill(-child.pid, 'SIGINT');
    const timeout = new Promise((resolve) => setTimeout(() => resolve(null), 20_000));
    const result = await Promise.race([exited, timeout]);
    if (!result) process.kill(-child.pid, 'SIGKILL');
    return { ...result, out };
  };
  return { viewer, report: viewer.replace(/viewer\.html$/, 'index.html'), stop };
}

const browser = await chromium.launch({ executablePath: CHROMIUM, args: ['--no-sandbox'] });
// Waits of up to 2 minutes, not playwright's 30 s: under ctest -j2 this test shares 2 cores with
// the heaviest render tests, and a wait that ran out there failed a viewer that works. ctest's
// own limit still ends a hang.
const kWaitMs = 120_000;
const consoleErrors = [];
const servers = [];
async function newPage(viewport = { width: 1400, height: 800 }) {
  const page = await browser.newPage({ viewport });
  page.setDefaultTimeout(kWaitMs);
  page.on('console', (m) => m.type() === 'error' && consoleErrors.push(m.text()));
  page.on('pageerror', (e) => consoleErrors.push(e.message));
  page.on('requestfailed', (r) => consoleErrors.push(`${r.url()}: ${r.failure().errorText}`));
  page.on('response', (r) => r.status() >= 400 && consoleErrors.push(`${r.url()}: ${r.status()}`));
  return page;
}
// Every pane drawn: from its values, or from its display PNG while they decode.
const drawn = (page) =>
  page.waitForFunction(() => {
    const c = [...document.querySelectorAll('#panes canvas.image')];
    return c.length > 0 && c.every((x) => x.dataset.drawn && x.dataset.drawn !== 'error');
  });
const drawnAs = (page, layer) =>
  page.waitForFunction((l) => [...document.querySelectorAll('#panes canvas.image')].every((c) => c.dataset.drawn && c.dataset.drawn?.startsWith(l + ' ')), layer);
const shown = (page) =>
  page.$$eval('#panes canvas.image', (cs) => cs.map((c) => ({
    pane: Number(c.dataset.pane), file: c.dataset.file, layer: c.dataset.layer, width: c.width, height: c.height, transform: c.style.transform,
  })));
const viewport = (page, slot) => page.locator(`#panes .pane[data-slot="${slot}"] .viewport`);
const inspector = (page, pane) => page.$eval(`#panes .info[data-pane="${pane}"] .inspector`, (e) => ({ x: Number(e.dataset.x), y: Number(e.dataset.y), values: e.dataset.values ? JSON.parse(e.dataset.values) : null, text: e.textContent }));
const stats = (page, pane) => page.$eval(`#panes .info[data-pane="${pane}"] .stats`, (e) => Object.fromEntries(['mean', 'max', 'mae', 'rmse'].filter((k) => e.dataset[k]).map((k) => [k, JSON.parse(e.dataset[k])])));
// The drawn rectangle as the address holds it (which follows the view within 50 ms).
async function regionOf(page) {
  await page.waitForFunction(() => new URLSearchParams(location.hash.slice(1)).has('region'));
  return page.evaluate(() => new URLSearchParams(location.hash.slice(1)).get('region').split(',').map(Number));
}
// Hovers the image pixel (x, y) of the pane in `slot` and waits for every inspector to read it.
async function hoverPixel(page, slot, x, y) {
  const box = await viewport(page, slot).boundingBox();
  const t = await page.$eval(`#panes .pane[data-slot="${slot}"] canvas.image`, (c) => c.style.transform);
  const [, tx, ty, s] = /translate\(([-\d.e]+)px, ([-\d.e]+)px\) scale\(([-\d.e]+)\)/.exec(t).map(Number);
  await page.mouse.move(box.x + tx + (x + 0.5) * s + 3, box.y + ty + (y + 0.5) * s + 3);
  await page.mouse.move(box.x + tx + (x + 0.5) * s, box.y + ty + (y + 0.5) * s);
  try {
    await page.waitForFunction(([px, py]) => [...document.querySelectorAll('#panes .inspector')].every((e) => e.dataset.x === String(px) && e.dataset.y === String(py) && e.dataset.values), [x, y]);
  } catch (e) {
    const read = await page.$$eval('#panes .inspector', (es) => es.map((i) => `${i.dataset.x},${i.dataset.y} ${i.dataset.values}`));
    const states = await page.$$eval('#panes canvas.image', (cs) => cs.map((c) => c.dataset.drawn));
    throw new Error(`the inspectors at (${x}, ${y}) read ${read.join('; ')}; panes drawn: ${states.join('; ')}: ${e.message}`);
  }
}
async function shiftDrag(page, slot, from, to) {
  const box = await viewport(page, slot).boundingBox();
  await page.keyboard.down('Shift');
  await page.mouse.move(box.x + box.width * from[0], box.y + box.height * from[1]);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width * to[0], box.y + box.height * to[1], { steps: 4 });
  await page.mouse.up();
  await page.keyboard.up('Shift');
}
// A rectangle's per-channel mean and largest value of `value(x, y)`, summed in the viewer's order.
function rectangleStats([x0, y0, w, h], value) {
  const first = value(x0, y0);
  const mean = first.map(() => 0);
  const max = first.map(() => -Infinity);
  for (let y = y0; y < y0 + h; y += 1) {
    for (let x = x0; x < x0 + w; x += 1) {
      value(x, y).forEach((v, k) => {
        mean[k] += v;
        max[k] = Math.max(max[k], v);
      });
    }
  }
  return { mean: mean.map((s) => s / (w * h)), max };
}
const close = (a, b, tolerance, what) => a.forEach((v, k) => assert.ok(Math.abs(v - b[k]) <= tolerance * Math.max(1, Math.abs(b[k])), `${what}: ${a} against ${b}`));

try {
  const server = await serve(resultDir);
  servers.push(server);
  const page = await newPage();
  const runAt = (frame, variant) => runs.find((r) => r.frame === frame && r.variant === variant);
  const variants = [...new Set(runs.map((r) => r.variant))];
  const frames = [...new Set(runs.map((r) => r.frame))].sort((a, b) => a - b);
  assert.deepEqual(frames, [0, 20, 40]);
  assert.equal(variants.length, 2);
  // The panes' files at a frame: the reference, then the variants in order.
  const expectedFiles = (frame) => [runAt(frame, variants[0]).referenceFile, ...variants.map((v) => runAt(frame, v).file)];

  await page.goto(server.viewer);
  await drawn(page);

  await check("`hybridlab view` serves on 127.0.0.1; every pane draws its run's EXR", async () => {
    assert.match(server.viewer, /^http:\/\/127\.0\.0\.1:\d+\/report\/viewer\.html$/);
    const panes = await shown(page);
    assert.deepEqual(panes.map((i) => i.file), expectedFiles(0));
    for (const i of panes) assert.deepEqual([i.width, i.height, i.layer], [64, 36, 'image'], i.file);
  });

  await check("the EXRs OpenEXR wrote, decoded here, draw as the runner's display PNGs (within one level)", async () => {
    await drawnAs(page, 'image'); // from the EXRs' values, not the PNG shown while they decode
    const worst = await page.evaluate(async (pngs) => {
      const out = [];
      for (const [pane, png] of pngs) {
        const canvas = document.querySelector(`#panes canvas.image[data-pane="${pane}"]`);
        const drawnPixels = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
        const bitmap = await createImageBitmap(await (await fetch(png)).blob(), { colorSpaceConversion: 'none' });
        const c = new OffscreenCanvas(bitmap.width, bitmap.height);
        const ctx = c.getContext('2d');
        ctx.drawImage(bitmap, 0, 0);
        const expected = ctx.getImageData(0, 0, bitmap.width, bitmap.height).data;
        let d = 0;
        for (let i = 0; i < expected.length; i += 1) if (i % 4 !== 3) d = Math.max(d, Math.abs(expected[i] - drawnPixels[i]));
        out.push(d);
      }
      return out;
    }, [[0, `../${runAt(0, variants[0]).reference.png}`], ...variants.map((v, i) => [i + 1, `../${runAt(0, v).images.png}`])]);
    assert.deepEqual(worst.map((d) => d <= 1), [true, true, true], `largest difference per pane: ${worst}`);
  });

  await check("each technique pane reads out its run's FLIP (LDR) and HDR-FLIP, named apart, below its image", async () => {
    for (const [i, v] of variants.entries()) {
      const m = runAt(0, v).metrics.whole;
      const text = await page.textContent(`#panes .info[data-pane="${i + 1}"] .metrics`);
      assert.ok(text.includes(`FLIP (LDR) ${m.flip.mean.toFixed(4)} · HDR-FLIP ${m.flip_hdr.mean.toFixed(4)}`), text);
      // The information lies below the image, not over it.
      const image = await viewport(page, i + 1).boundingBox();
      const info = await page.locator(`#panes .info[data-pane="${i + 1}"]`).boundingBox();
      assert.ok(info.y >= image.y + image.height - 1, `information at ${info.y}, image down to ${image.y + image.height}`);
    }
  });

  await check("FLIP of a pane against the reference, over the whole image, is the runner's FLIP mean", async () => {
    await page.selectOption('#panes .bar[data-pane="1"] select.layer', 'flip');
    await page.waitForFunction(() => document.querySelector('#panes canvas.image[data-pane="1"]').dataset.drawn?.startsWith('flip '));
    await shiftDrag(page, 1, [0.01, 0.01], [0.99, 0.99]);
    await page.waitForFunction(() => document.querySelector('#panes .info[data-pane="1"] .stats').dataset.mean);
    assert.deepEqual(await regionOf(page), [0, 0, 64, 36]);
    const s = await stats(page, 1);
    const runner = runAt(0, variants[0]).metrics.whole.flip.mean;
    assert.ok(Math.abs(s.mean[0] - runner) < 2e-4, `FLIP mean ${s.mean[0]} here, ${runner} by the runner`);
    assert.match(await page.textContent('#panes .info[data-pane="1"] .legend'), /FLIP/);
    await page.keyboard.press('r');
    await page.selectOption('#panes .bar[data-pane="1"] select.layer', 'image');
    await drawn(page);
  });

  await check('the inspector shows the same pixel in every pane, with its linear values', async () => {
    await hoverPixel(page, 0, 20, 18);
    const read = await Promise.all([0, 1, 2].map((i) => inspector(page, i)));
    for (const r of read) {
      assert.deepEqual([r.x, r.y], [20, 18]);
      assert.equal(r.values.length, 3);
      assert.match(r.text, /^\(20, 18\) RGB \d+ \d+ \d+ \| linear /);
    }
    assert.equal(await page.textContent('#pixel'), 'pixel (20, 18)');
  });

  await check('a wheel event in one pane zooms every pane alike, about the cursor; zoomed in, pixels show their values', async () => {
    const before = await shown(page);
    const box = await viewport(page, 1).boundingBox();
    const cursor = { x: box.x + box.width * 0.4, y: box.y + box.height * 0.55 };
    await page.mouse.move(cursor.x, cursor.y);
    const pixelBefore = await page.textContent('#pixel');
    await page.mouse.wheel(0, -600);
    await page.waitForFunction((t) => document.querySelector('#panes canvas.image').style.transform !== t, before[0].transform);
    const after = await shown(page);
    const scale = (t) => Number(/scale\(([^)]+)\)/.exec(t)[1]);
    assert.ok(scale(after[0].transform) > 2 * scale(before[0].transform), `${before[0].transform} -> ${after[0].transform}`);
    for (const i of after) assert.equal(i.transform, after[0].transform);
    await page.mouse.move(cursor.x, cursor.y);
    assert.equal(await page.textContent('#pixel'), pixelBefore);
    assert.equal(await page.$eval('#panes canvas.image', (c) => getComputedStyle(c).imageRendering), 'pixelated');
    for (let i = 0; i < 3; i += 1) await page.mouse.wheel(0, -600);
    await page.waitForFunction(() => [...document.querySelectorAll('#panes canvas.labels')].every((c) => Number(c.dataset.labels) > 0));
    await page.keyboard.press('0');
    await drawn(page);
  });

  await check('flip shows one image, F changes it and flips back; swipe cuts two at the divider', async () => {
    await page.keyboard.press('f');
    await drawn(page);
    const first = await shown(page);
    assert.equal(first.length, 1);
    await page.keyboard.press('f');
    await drawn(page);
    const second = await shown(page);
    assert.deepEqual([first[0].file, second[0].file], expectedFiles(0).slice(0, 2));
    await page.keyboard.press('w');
    await drawn(page);
    const clip = () => page.$eval('#panes canvas.top', (c) => Number(/inset\(0px 0px 0px ([\d.]+)px\)/.exec(c.style.clipPath)[1]));
    assert.deepEqual((await shown(page)).map((i) => i.file), expectedFiles(0).slice(0, 2));
    const before = await clip();
    const d = await page.locator('#panes .divider').boundingBox();
    await page.mouse.move(d.x + 1, d.y + d.height / 2);
    await page.mouse.down();
    await page.mouse.move(d.x - 100, d.y + d.height / 2, { steps: 4 });
    await page.mouse.up();
    assert.ok((await clip()) < before, `${before} -> ${await clip()}`);
    await page.keyboard.press('s');
    await drawn(page);
    assert.equal((await shown(page)).length, 3);
  });

  await check("the runner's SSIM and HDR-FLIP maps are drawn from their values, with the viewer's legend alone", async () => {
    const options = await page.$$eval('#panes .bar[data-pane="1"] select.layer option', (os) => os.map((o) => o.value));
    assert.deepEqual(options, ['image', 'abs', 'rel', 'flip', 'map:ssim', 'map:flip_hdr', 'debug:mask']);
    const run = runAt(0, variants[0]);
    // The runner's PNG has its legend strip below the map; the viewer draws the map's rows alone.
    const pngHeight = fs.readFileSync(path.join(resultDir, run.images.maps, 'ssim.png')).readUInt32BE(20);
    assert.ok(pngHeight > 36, `ssim.png is ${pngHeight} rows`);
    for (const layer of ['map:ssim', 'map:flip_hdr']) {
      await page.selectOption('#panes .bar[data-pane="1"] select.layer', layer);
      await page.waitForFunction((l) => document.querySelector('#panes canvas.image[data-pane="1"]').dataset.drawn?.startsWith(l + ' '), layer);
      const img = (await shown(page))[1];
      assert.deepEqual([img.file, img.width, img.height], [run.maps[layer.slice(4)], 64, 36]);
      assert.equal(await page.locator('#panes .info[data-pane="1"] .legend').count(), 1);
      await hoverPixel(page, 1, 32, 18);
      const value = (await inspector(page, 1)).values[0];
      assert.ok(value >= 0 && value <= 1, String(value));
    }
    await page.selectOption('#panes .bar[data-pane="1"] select.layer', 'debug:mask');
    await page.waitForFunction(() => document.querySelector('#panes canvas.image[data-pane="1"]').dataset.drawn?.startsWith('debug:mask '));
    assert.equal((await shown(page))[1].file, `../${run.images.debug.mask}`);
    await page.selectOption('#panes .bar[data-pane="1"] select.layer', 'image');
    await drawn(page);
  });

  await check('the frame slider and the arrow keys move every pane to the new frame', async () => {
    await page.$eval('#frame', (s) => {
      s.value = '1';
      s.dispatchEvent(new Event('input'));
    });
    await drawn(page);
    assert.deepEqual((await shown(page)).map((i) => i.file), expectedFiles(20));
    await page.evaluate(() => document.activeElement.blur());
    await page.keyboard.press('ArrowRight');
    await drawn(page);
    assert.deepEqual((await shown(page)).map((i) => i.file), expectedFiles(40));
  });

  await check('number keys pick the technique of the active pane; E cycles the differences of every technique pane', async () => {
    await viewport(page, 0).click();
    await page.keyboard.press('3');
    await drawn(page);
    assert.equal((await shown(page))[0].file, runAt(40, variants[1]).file);
    await page.keyboard.press('1');
    await drawn(page);
    assert.equal((await shown(page))[0].file, runAt(40, variants[0]).referenceFile);
    for (const layer of ['abs', 'rel', 'flip']) {
      await page.keyboard.press('e');
      await page.waitForFunction((l) => [...document.querySelectorAll('#panes canvas.image')].slice(1).every((c) => c.dataset.layer === l && c.dataset.drawn), layer);
    }
    await page.keyboard.press('?');
    assert.ok(await page.isVisible('#help'));
    assert.match(await page.textContent('#help'), /flip/);
    await page.keyboard.press('Escape');
    assert.ok(!(await page.isVisible('#help')));
    await page.keyboard.press('e');
    await drawnAs(page, 'image');
  });

  await check('exposure changes the pixels drawn; the inspector gives the colour drawn beside the linear value', async () => {
    const mean = () =>
      page.$eval('#panes canvas.image[data-pane="1"]', (c) => {
        const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        let sum = 0;
        for (let i = 0; i < d.length; i += 4) sum += d[i] + d[i + 1] + d[i + 2];
        return sum / (d.length / 4) / 3;
      });
    const drawnAt = (ev) => page.waitForFunction((e) => [...document.querySelectorAll('#panes canvas.image')].every((c) => c.dataset.drawn === `image ev ${e} srgb`), ev);
    for (let i = 0; i < 4; i += 1) await page.keyboard.press('-');
    await drawnAt(-2);
    const darker = await mean();
    for (let i = 0; i < 8; i += 1) await page.keyboard.press('+');
    await drawnAt(2);
    const brighter = await mean();
    assert.equal(await page.textContent('#ev-label'), 'EV +2.0');
    assert.ok(brighter > darker + 20, `mean display value ${darker} at EV -2, ${brighter} at EV +2`);
    await hoverPixel(page, 1, 30, 20);
    const { text, values } = await inspector(page, 1);
    const r = Number(/RGB (\d+)/.exec(text)[1]);
    const x = Math.min(1, Math.max(0, values[0] * 4));
    const enc = x <= 0.0031308 ? 12.92 * x : 1.055 * x ** (1 / 2.4) - 0.055;
    assert.equal(r, Math.round(255 * enc), text);
    for (let i = 0; i < 4; i += 1) await page.keyboard.press('-');
    await drawnAt(0);
  });

  await check('every variant can be selected from the searchable list', async () => {
    const frame = frames[Number(await page.$eval('#frame', (s) => s.value))];
    const options = await page.$$eval('#variant-list option', (os) => os.map((o) => o.value));
    assert.equal(options.length, 1 + variants.length);
    await viewport(page, 1).click();
    for (const v of variants) {
      const label = options.find((o) => o.endsWith(`: ${v}`));
      await page.fill('#find', label);
      await page.$eval('#find', (e) => e.dispatchEvent(new Event('change')));
      await drawn(page);
      assert.equal((await shown(page))[1].file, runAt(frame, v).file, v);
    }
  });

  await check('a link restores the whole view: panes, differences, zoom, position, exposure, display, rectangle', async () => {
    // Pane 3 shows the other setting than pane 2, differenced against pane 2.
    await page.selectOption('#panes .bar[data-pane="1"] select.variant', variants[1]);
    await page.selectOption('#panes .bar[data-pane="2"] select.variant', variants[0]);
    await page.selectOption('#panes .bar[data-pane="2"] select.against', '1');
    await page.selectOption('#panes .bar[data-pane="2"] select.layer', 'rel');
    await page.selectOption('#transform', 'false');
    await page.evaluate(() => document.activeElement.blur());
    await page.keyboard.press('+');
    const box = await viewport(page, 0).boundingBox();
    await page.mouse.move(box.x + box.width * 0.3, box.y + box.height * 0.4);
    await page.mouse.wheel(0, -300);
    await shiftDrag(page, 0, [0.3, 0.35], [0.55, 0.6]);
    await page.waitForFunction(() => [1, 2].every((i) => document.querySelector(`#panes .info[data-pane="${i}"] .stats`).dataset.mae));
    await page.waitForTimeout(200); // the address follows the view within 50 ms
    const state = async (p) => ({
      url: new URL(p.url()).hash,
      shown: (await shown(p)).map((i) => [i.pane, i.file, i.layer]),
      transform: (await shown(p)).map((i) => /translate\(([-\d.e]+)px, ([-\d.e]+)px\) scale\(([-\d.e]+)\)/.exec(i.transform).slice(1).map((v) => Math.round(Number(v)))),
      selects: await p.$$eval('#panes .bar select, #transform', (ss) => ss.map((s) => s.value)),
      ev: await p.textContent('#ev-label'),
      stats: await p.$$eval('#panes .stats', (ss) => ss.map((s) => s.textContent)),
    });
    const before = await state(page);
    assert.match(before.url, /against|pane=.*%7Crel%7C1/);
    const again = await newPage();
    await again.goto(page.url());
    await drawn(again);
    await again.waitForFunction(() => [1, 2].every((i) => document.querySelector(`#panes .info[data-pane="${i}"] .stats`).dataset.mae));
    assert.deepEqual(await state(again), before);
    await again.close();
  });

  await page.screenshot({ path: path.join(work, 'viewer-difference.png') });

  await check('an unknown run gets a notice, and the viewer opens the first scene', async () => {
    const p = await newPage();
    await p.goto(server.viewer + '#run=no-such-run');
    await drawn(p);
    assert.ok(await p.isVisible('#notice'));
    assert.match(await p.textContent('#notice'), /This result set has no run "no-such-run"/);
    await p.close();
  });

  await check('opened from the file system, the viewer says to run hybridlab view', async () => {
    const p = await browser.newPage();
    await p.goto(pathToFileURL(path.join(reportDir, 'viewer.html')).href + '#run=x');
    assert.ok(await p.isVisible('#notice'));
    assert.ok((await p.textContent('#notice')).includes(`Run  hybridlab view ${resultDir}  and open`));
    await p.close();
  });

  await check('one setting has one colour on three charts and in the viewer', async () => {
    const v = 'rt_only [importance_cutoff=0.01]';
    const colour = settings.colours[v];
    assert.match(colour, /^#[0-9a-f]{6}$/);
    const ids = runs.filter((r) => r.variant === v).map((r) => r.id);
    const figures = path.join(reportDir, 'figures');
    const charts = fs.readdirSync(figures).filter((f) => /^(speed-accuracy-whitted|work-accuracy|path|failures)-.*\.svg$/.test(f));
    assert.equal(charts.length, 4, charts.join(', '));
    for (const chart of charts) {
      const svg = fs.readFileSync(path.join(figures, chart), 'utf8');
      const fills = ids.flatMap((id) => [...svg.matchAll(new RegExp(`#run=${id}">\\s*<g[^>]*>\\s*<use[^>]*style="fill: (#[0-9a-f]{6})`, 'g'))].map((m) => m[1]));
      assert.ok(fills.length > 0, chart);
      assert.deepEqual([...new Set(fills)], [colour], chart);
    }
    const pane = await page.$$eval('#panes .bar select.variant', (ss, name) => ss.findIndex((s) => s.value === name), v);
    assert.ok(pane > 0, `no pane shows ${v}`);
    const swatch = await page.$eval(`#panes .bar[data-pane="${pane}"] .swatch`, (s) => getComputedStyle(s).backgroundColor);
    const [r, g, b] = [1, 3, 5].map((i) => parseInt(colour.slice(i, i + 2), 16));
    assert.equal(swatch, `rgb(${r}, ${g}, ${b})`);
  });

  await check("the report: contents, the verdict first, no sideways scrolling at 800 px, each figure's SVG and PDF beside it", async () => {
    const report = await newPage({ width: 800, height: 900 });
    await report.goto(server.report);
    const ids = await report.$$eval('nav.contents a', (as) => as.map((a) => a.getAttribute('href')));
    assert.equal(ids[0], '#verdict');
    for (const id of ids) assert.equal(await report.locator(id).count(), 1, id);
    const order = await report.evaluate(() => ['verdict', 'device', 'runs'].map((id) => document.getElementById(id).getBoundingClientRect().top));
    assert.ok(order[0] < order[1] && order[1] < order[2], String(order));
    assert.ok(await report.evaluate(() => document.documentElement.scrollWidth <= window.innerWidth), 'the page scrolls sideways at 800 px');
    const captions = await report.$$eval('figure figcaption', (fs) => fs.map((f) => [...f.querySelectorAll('a')].map((a) => a.getAttribute('href'))));
    assert.ok(captions.length >= 4);
    for (const [svg, pdf] of captions) {
      assert.match(svg, /^figures\/.*\.svg$/);
      assert.equal(pdf, svg.replace(/\.svg$/, '.pdf'));
      assert.ok(fs.existsSync(path.join(reportDir, pdf)), pdf);
    }
    await report.screenshot({ path: path.join(work, 'report-top.png') });
    await report.locator('figure object').first().screenshot({ path: path.join(work, 'chart.png') });
    await report.close();
  });

  await check("the report's verdict names the known answer, and its table and charts open the viewer on a run", async () => {
    const report = await newPage();
    await report.goto(server.report);
    // rt_only at 0.01 is the only setting reaching SSIM 0.99 on this scene (max_depth = 1 loses the
    // glass sphere's refraction), so the fastest reaching it, and reaching 0.97 and 0.95, on the whole
    // image and on the reflective and refractive pixels: one row.
    const fastest99 = runs.filter((r) => r.metrics.whole.ssim >= 0.99).map((r) => r.variant);
    assert.deepEqual([...new Set(fastest99)], ['rt_only [importance_cutoff=0.01]']);
    const verdictRow = await report.$$eval('table.verdict.thresholds tr', (trs) =>
      trs.map((tr) => [...tr.cells].map((c) => c.textContent)).find((cells) => cells[0].startsWith('SSIM >= 0.99')));
    assert.equal(verdictRow[0], 'SSIM >= 0.99, >= 0.97 and >= 0.95, whole image; SSIM >= 0.99, >= 0.97 and >= 0.95, refl./refr. pixels');
    assert.equal(verdictRow[1], 'rt_only [importance_cutoff=0.01]');
    const median = (xs) => {
      const v = [...xs].sort((x, y) => x - y);
      return v.length % 2 ? v[(v.length - 1) / 2] : (v[v.length / 2 - 1] + v[v.length / 2]) / 2;
    };
    const rtRuns = runs.filter((r) => r.variant === 'rt_only [importance_cutoff=0.01]');
    const rtMs = median(rtRuns.map((r) => r.frame_ms.median));
    assert.equal(verdictRow[2], rtMs.toFixed(2));
    assert.equal(verdictRow[3], (median(runs.map((r) => r.reference.frame_ms)) / rtMs).toFixed(2));
    assert.match(await report.textContent('#verdict ~ p.sentence'),
      /SSIM 0\.99 on the whole image (is|(beats|is decided faster than) the reference \([\d.]+ ms\): the fastest,) rt_only \[importance_cutoff=0\.01\]/);
    const experiment = JSON.parse(fs.readFileSync(path.join(resultDir, 'experiment.json'), 'utf8'));
    const deviceText = await report.textContent('table.device');
    if (experiment.device) assert.ok(deviceText.includes(experiment.device.vulkan_device), deviceText);
    else assert.match(deviceText, /device not recorded/);
    assert.match(deviceText, /ray backend\s*embree/);
    const hrefs = await report.$$eval('table.runs a[href^="viewer.html#run="]', (as) => as.map((a) => a.getAttribute('href')));
    assert.deepEqual(hrefs.sort(), runs.map((r) => `viewer.html#run=${r.id}`).sort());
    const target = runAt(40, variants[1]);
    const link = `table.runs a[href="viewer.html#run=${target.id}"]`;
    await Promise.all([report.waitForURL(/viewer\.html/, { waitUntil: 'commit' }), report.$eval(link, (a) => a.click())]);
    await drawn(report);
    const files = (await shown(report)).map((i) => i.file);
    assert.deepEqual(files.slice(0, 2), [target.referenceFile, target.file]);
    const firstRun = runs.find((r) => r.variant === target.variant);
    for (const svg of fs.readdirSync(path.join(reportDir, 'figures')).filter((f) => /^(speed-accuracy|path)-.*\.svg$/.test(f))) {
      const text = fs.readFileSync(path.join(reportDir, 'figures', svg), 'utf8');
      const linked = svg.startsWith('path-') ? target : firstRun;
      assert.ok(text.includes(`target="_top" xlink:href="../viewer.html#run=${linked.id}"`), svg);
    }
    await report.close();
  });

  await page.screenshot({ path: path.join(work, 'viewer.png') });

  await check('a raster on a software Vulkan device is flagged at the top of the report', async () => {
    const file = path.join(resultDir, 'experiment.json');
    const original = fs.readFileSync(file, 'utf8');
    const experiment = JSON.parse(original);
    experiment.device = {
      cpu_model: 'Test CPU 9000', cpu_cores: 2, vulkan_device: 'llvmpipe (LLVM 19.1.7, 256 bits)', vulkan_device_type: 'cpu',
      vulkan_driver: 'Mesa 25.0.7', vulkan_api_version: '1.4.305', embree_version: '3.13.5', tbb_threads: 2, lp_num_threads: 2,
      os: 'Debian GNU/Linux 12', program_version: 'test',
    };
    fs.writeFileSync(file, JSON.stringify(experiment));
    const deviceReport = path.join(work, 'device-report');
    try {
      hybridlabRun(['report', resultDir, '--out', deviceReport]);
    } finally {
      fs.writeFileSync(file, original);
    }
    const text = fs.readFileSync(path.join(deviceReport, 'index.html'), 'utf8');
    assert.ok(text.indexOf('class="warning">Warning: The raster ran on a software Vulkan device') < text.indexOf('id="verdict"'));
    assert.match(text, /Test CPU 9000 \(2 cores\)/);
    assert.match(text, /llvmpipe \(LLVM 19\.1\.7, 256 bits\) \(cpu\)/);
    assert.match(fs.readFileSync(path.join(deviceReport, 'report.md'), 'utf8'), /\*\*Warning:\*\* The raster ran on a software Vulkan device/);
  });

  await check('a damaged image in the result set: exit status 2, a message naming it, no report', async () => {
    const damaged = path.join(work, 'damaged');
    fs.cpSync(resultDir, damaged, { recursive: true, filter: (f) => !f.startsWith(reportDir) });
    const exr = path.join(damaged, runs[1].images.exr);
    fs.writeFileSync(exr, fs.readFileSync(exr).subarray(0, 1000));
    const out = path.join(work, 'damaged-report');
    const r = spawnSync(hybridlab, ['report', damaged, '--out', out], { encoding: 'utf8' });
    assert.equal(r.status, 2, r.stderr);
    assert.ok(r.stderr.includes(exr), r.stderr);
    assert.ok(!fs.existsSync(out));
  });

  await check('hybridlab view refuses a folder without a report, and stops on Ctrl-C with status 0', async () => {
    const r = spawnSync(hybridlab, ['view', work], { encoding: 'utf8' });
    assert.equal(r.status, 2, r.stderr);
    assert.match(r.stderr, /no results\.json/);
    const stopped = await servers.shift().stop();
    assert.deepEqual([stopped.code, stopped.signal], [0, null], stopped.out);
    assert.match(stopped.out, /stopped/);
  });

  // A result set at the paper configs' size, made up: 15 frames of 7 settings at 1280x720.
  const paperDir = path.join(work, 'paper-scale');
  const set = writeSyntheticSet(paperDir, { width: 1280, height: 720, frames: 15 });
  await check('the made-up 1280x720 EXRs are OpenEXR files (hybridlab compare reads them)', async () => {
    const r = spawnSync(hybridlab, ['compare', path.join(paperDir, set.records[2].images.exr), path.join(paperDir, set.records[4].images.exr), '--out', path.join(work, 'compare')], { encoding: 'utf8' });
    assert.equal(r.status, 0, r.stderr);
  });
  hybridlabRun(['report', paperDir]);
  const paperReport = path.join(paperDir, 'report');

  await check(`the viewer's own files stay under 5 MB for ${set.records.length} runs at 1280x720`, async () => {
    const size = (dir) => fs.readdirSync(dir).reduce((sum, f) => sum + fs.statSync(path.join(dir, f)).size, 0);
    const viewerBytes = fs.statSync(path.join(paperReport, 'viewer.html')).size + size(path.join(paperReport, 'viewer'));
    const smallBytes = fs.statSync(path.join(reportDir, 'viewer.html')).size + size(path.join(reportDir, 'viewer'));
    assert.ok(set.records.length >= 100);
    assert.ok(viewerBytes < 5 * 1024 * 1024, `${viewerBytes} bytes`);
    // No image is copied: the set of 105 runs has the same viewer, but for its settings, as that of 6.
    assert.ok(Math.abs(viewerBytes - smallBytes) < 20_000, `${viewerBytes} and ${smallBytes} bytes`);
    console.log(`  the viewer's files: ${(viewerBytes / 1024).toFixed(0)} KB (${set.records.length} runs at 1280x720; ${(smallBytes / 1024).toFixed(0)} KB for 6 runs at 64x36)`);
  });

  const paperServer = await serve(paperDir);
  servers.push(paperServer);
  const paper = await newPage();
  const middle = set.records.find((r) => r.frame === 7 && r.technique === 'rt_only');
  let paneVariants = null;

  await check('it opens in under 5 s, every pane drawn', async () => {
    const start = Date.now();
    await paper.goto(`${paperServer.viewer}#run=${middle.id}`);
    await drawn(paper);
    const seconds = (Date.now() - start) / 1000;
    // Then each pane's EXR, decoded, draws it again from its values.
    await drawnAs(paper, 'image');
    console.log(`  every pane drawn from its EXR's values after ${((Date.now() - start) / 1000).toFixed(2)} s`);
    const panes = await shown(paper);
    assert.equal(panes.length, 6); // the reference and one setting of each of the 5 techniques
    for (const p of panes) assert.deepEqual([p.width, p.height], [1280, 720]);
    paneVariants = await paper.$$eval('#panes .bar select.variant', (ss) => ss.map((s) => s.value));
    assert.equal(paneVariants[1], 'rt_only');
    console.log(`  opened and drew ${panes.length} panes of 1280x720 in ${seconds.toFixed(2)} s`);
    assert.ok(seconds < 5, `${seconds} s`);
  });
  const settingOf = (pane) => (paneVariants[pane] === 'reference' ? set.referenceOf(7) : set.variants.indexOf(paneVariants[pane]));

  await check("the values read back are the EXRs' own (FLOAT and HALF, ZIP, ZIPS and none)", async () => {
    // Panes 4 and 5 take the settings stored as HALF with ZIPS and with no compression.
    for (const [pane, k] of [[4, 5], [5, 6]]) {
      await paper.selectOption(`#panes .bar[data-pane="${pane}"] select.variant`, set.variants[k]);
      await paper.waitForFunction(([p, v]) => document.querySelector(`#panes .bar[data-pane="${p}"] select.variant`).value === v, [pane, set.variants[k]]);
    }
    await drawn(paper);
    paneVariants = await paper.$$eval('#panes .bar select.variant', (ss) => ss.map((s) => s.value));
    for (const [x, y] of [[0, 0], [640, 360], [1279, 3], [4, 714], [123, 457]]) {
      await hoverPixel(paper, 0, x, y);
      for (let pane = 0; pane < paneVariants.length; pane += 1) {
        assert.deepEqual((await inspector(paper, pane)).values, set.value(settingOf(pane), x, y), `pane ${pane} at (${x}, ${y})`);
      }
    }
  });

  await check('the difference of two chosen panes (absolute, relative) holds the values computed from the files', async () => {
    await paper.selectOption('#panes .bar[data-pane="3"] select.against', '2');
    await paper.waitForFunction(() => document.querySelector('#panes canvas.image[data-pane="3"]').dataset.drawn?.startsWith('abs '));
    const a = (x, y) => set.value(settingOf(3), x, y);
    const b = (x, y) => set.value(settingOf(2), x, y);
    for (const [x, y] of [[10, 20], [700, 300]]) {
      await hoverPixel(paper, 0, x, y);
      assert.deepEqual((await inspector(paper, 3)).values, a(x, y).map((v, k) => Math.fround(Math.abs(v - b(x, y)[k]))));
    }
    await paper.selectOption('#panes .bar[data-pane="3"] select.layer', 'rel');
    await paper.waitForFunction(() => document.querySelector('#panes canvas.image[data-pane="3"]').dataset.drawn?.startsWith('rel '));
    await hoverPixel(paper, 0, 700, 300);
    assert.deepEqual((await inspector(paper, 3)).values, a(700, 300).map((v, k) => Math.fround(Math.abs(v - b(700, 300)[k]) / (Math.abs(b(700, 300)[k]) + 0.01))));
  });

  await check("a rectangle's statistics hold the values computed from the files", async () => {
    await paper.selectOption('#panes .bar[data-pane="3"] select.layer', 'abs');
    await shiftDrag(paper, 0, [0.3, 0.3], [0.42, 0.45]);
    await paper.waitForFunction(() => [1, 3].every((i) => document.querySelector(`#panes .info[data-pane="${i}"] .stats`).dataset.mae));
    const region = await regionOf(paper);
    assert.ok(region[2] > 20 && region[3] > 20, String(region));
    const image = await stats(paper, 1);
    const expected = rectangleStats(region, (x, y) => set.value(settingOf(1), x, y));
    close(image.mean, expected.mean, 1e-12, 'mean');
    assert.deepEqual(image.max, expected.max);
    // Against the reference: the mean |A - B| and the RMSE per channel.
    const ref = (x, y) => set.value(settingOf(0), x, y);
    const mae = rectangleStats(region, (x, y) => set.value(settingOf(1), x, y).map((v, k) => Math.abs(v - ref(x, y)[k]))).mean;
    const mse = rectangleStats(region, (x, y) => set.value(settingOf(1), x, y).map((v, k) => (v - ref(x, y)[k]) ** 2)).mean;
    close(image.mae, mae, 1e-12, 'mean |A - B|');
    close(image.rmse, mse.map(Math.sqrt), 1e-12, 'RMSE');
    // The pane showing |A - B| against pane 3: its own values' statistics.
    const diff = await stats(paper, 3);
    const d = rectangleStats(region, (x, y) => set.value(settingOf(3), x, y).map((v, k) => Math.fround(Math.abs(v - set.value(settingOf(2), x, y)[k]))));
    close(diff.mean, d.mean, 1e-12, 'mean of the difference');
    assert.deepEqual(diff.max, d.max);
  });
  await paper.screenshot({ path: path.join(work, 'paper-scale.png') });
  await (await servers.pop()).stop();
} finally {
  for (const s of servers) await s.stop();
  await browser.close();
}

assert.deepEqual(consoleErrors, [], 'console errors');
console.log(`screenshots: ${['report-top', 'chart', 'viewer', 'viewer-difference', 'paper-scale'].map((n) => path.join(work, n + '.png')).join(' ')}`);
console.log(`${passed} passed, 0 failed`);
