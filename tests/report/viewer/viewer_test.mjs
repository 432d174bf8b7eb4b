// The viewer in a real browser: the runner makes a small result set (whitted-classic at 64x36,
// three frames of the orbit path, two techniques), `hybridlab report` writes viewer.html, and
// headless Chromium (Debian's, driven by playwright-core) opens it from the file system and checks:
// the records validate against experiments/results.schema.json, every pane's image loads, a wheel
// event zooms all panes alike, flip changes the image and back,
// the FLIP (LDR) and HDR-FLIP map layers show their maps' files and each pane reads out both
// FLIPs of its run, the frame slider moves every pane to the new frame, the inspector shows the
// same pixel in every pane, exposure changes the pixels drawn (and the inspector shows linear
// values), two panes' difference maps share one scale in their legends, every variant
// can be picked from the searchable list, and the report's verdict names the known answer (rt_only
// at 0.01 is the fastest, indeed the only, setting reaching SSIM 0.99); no console error on the way.
//
//   node viewer_test.mjs HYBRIDLAB_BIN WORK_DIR
//
// Leaves WORK_DIR/viewer.png (a screenshot) and the result set and report behind as artifacts.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

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
    [(r) => { r.metrics.whole.rmse = -1; }, '$.metrics.whole.rmse: must be >= 0'],
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
const manifest = JSON.parse(fs.readFileSync(path.join(reportDir, 'viewer', 'manifest.json'), 'utf8'));
const viewerUrl = pathToFileURL(path.join(reportDir, 'viewer.html')).href;

let passed = 0;
async function check(name, body) {
  await body();
  passed += 1;
  console.log(`ok - ${name}`);
}

const browser = await chromium.launch({ executablePath: CHROMIUM, args: ['--no-sandbox'] });
// Waits of up to 2 minutes, not playwright's 30 s: under ctest -j2 this test shares 2 cores with
// the heaviest render tests, and a wait that ran out there failed a viewer that works. ctest's
// own limit (5 minutes) still ends a hang.
const kWaitMs = 120_000;
const consoleErrors = [];
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 800 } });
  page.setDefaultTimeout(kWaitMs);
  page.on('console', (m) => m.type() === 'error' && consoleErrors.push(m.text()));
  page.on('pageerror', (e) => consoleErrors.push(e.message));
  page.on('requestfailed', (r) => consoleErrors.push(`${r.url()}: ${r.failure().errorText}`));

  // Every shown image loaded, with the size of the run (error maps add their legend below).
  const panesLoaded = () =>
    page.waitForFunction(() => {
      const imgs = [...document.querySelectorAll('#panes img.image')];
      return imgs.length > 0 && imgs.every((i) => i.complete && i.naturalWidth > 0);
    });
  const shown = () =>
    page.$$eval('#panes img.image', (imgs) =>
      imgs.map((i) => ({ pane: i.dataset.pane, file: i.dataset.file, src: i.src, width: i.naturalWidth, transform: i.style.transform })),
    );
  const viewport = (slot) => page.locator(`#panes .pane[data-slot="${slot}"] .viewport`);
  const runAt = (frame, variant) => manifest.runs.find((r) => r.frame === frame && r.variant === variant);
  const variants = [...new Set(manifest.runs.map((r) => r.variant))];
  const frames = [...new Set(manifest.runs.map((r) => r.frame))].sort((a, b) => a - b);
  assert.deepEqual(frames, [0, 20, 40]);
  assert.equal(variants.length, 2);
  // The panes' files at a frame: the reference, then the variants in order.
  const expectedFiles = (frame) => [runAt(frame, variants[0]).reference, ...variants.map((v) => runAt(frame, v).image)];

  await page.goto(viewerUrl);
  await panesLoaded();

  await check("every pane's image loads", async () => {
    const imgs = await shown();
    assert.equal(imgs.length, 3);
    assert.deepEqual(imgs.map((i) => i.file), expectedFiles(0));
    for (const i of imgs) assert.equal(i.width, 64, i.file);
  });

  await check("each technique pane reads out its run's FLIP (LDR) and HDR-FLIP, named apart", async () => {
    for (const [i, v] of variants.entries()) {
      const m = runAt(0, v).metrics;
      assert.equal(typeof m.flip_hdr, 'number', v);
      assert.equal(typeof m.masked_flip_hdr, 'number', v);
      const text = await page.textContent(`#panes .overlay[data-pane="${i + 1}"] .metrics`);
      assert.ok(text.includes(`FLIP (LDR) ${m.flip.toFixed(4)} · HDR-FLIP ${m.flip_hdr.toFixed(4)}`), text);
      const masked = await page.textContent(`#panes .overlay[data-pane="${i + 1}"] .metrics.masked`);
      assert.ok(masked.includes(`FLIP (LDR) ${m.masked_flip.toFixed(4)} · HDR-FLIP ${m.masked_flip_hdr.toFixed(4)}`), masked);
    }
  });

  await check('the inspector shows the same pixel in every pane', async () => {
    const box = await viewport(0).boundingBox();
    await page.mouse.move(box.x + box.width * 0.3, box.y + box.height * 0.5);
    await page.waitForFunction(() => [...document.querySelectorAll('#panes .inspector')].every((e) => e.textContent.includes('RGB')));
    const read = await page.$$eval('#panes .inspector', (els) => els.map((e) => ({ x: e.dataset.x, y: e.dataset.y, text: e.textContent })));
    assert.equal(read.length, 3);
    const where = read[0].text.split(' RGB')[0];
    assert.match(where, /^\(\d+, \d+\)$/);
    for (const r of read) {
      assert.equal(r.text.split(' RGB')[0], where);
      assert.equal(`(${r.x}, ${r.y})`, where);
    }
    assert.equal(await page.textContent('#pixel'), `pixel ${where}`);
  });

  await check('a wheel event in one pane zooms every pane alike, about the cursor', async () => {
    const before = await shown();
    const box = await viewport(1).boundingBox();
    const cursor = { x: box.x + box.width * 0.4, y: box.y + box.height * 0.55 };
    await page.mouse.move(cursor.x, cursor.y);
    const pixelBefore = await page.textContent('#pixel');
    await page.mouse.wheel(0, -600);
    await page.waitForFunction((t) => document.querySelector('#panes img.image').style.transform !== t, before[0].transform);
    const after = await shown();
    const scale = (t) => Number(/scale\(([^)]+)\)/.exec(t)[1]);
    assert.ok(scale(after[0].transform) > 2 * scale(before[0].transform), `${before[0].transform} -> ${after[0].transform}`);
    for (const i of after) assert.equal(i.transform, after[0].transform);
    // The pixel under the cursor stays under it.
    await page.mouse.move(cursor.x, cursor.y);
    assert.equal(await page.textContent('#pixel'), pixelBefore);
    // At this zoom a pixel covers many screen pixels and is drawn as a square.
    assert.equal(await page.$eval('#panes img.image', (i) => getComputedStyle(i).imageRendering), 'pixelated');
  });

  await check('flip shows one image, F changes it and flips back', async () => {
    await page.keyboard.press('f');
    await panesLoaded();
    const first = await shown();
    assert.equal(first.length, 1);
    await page.keyboard.press('f');
    await panesLoaded();
    const second = await shown();
    assert.equal(second.length, 1);
    assert.notEqual(second[0].src, first[0].src);
    assert.deepEqual([first[0].file, second[0].file], expectedFiles(0).slice(0, 2));
    await page.keyboard.press('f');
    await panesLoaded();
    assert.equal((await shown())[0].src, first[0].src);
  });

  await check('swipe shows two images cut at the divider, which drags', async () => {
    await page.keyboard.press('w');
    await panesLoaded();
    const clip = () => page.$eval('#panes img.top', (i) => Number(/inset\(0px 0px 0px ([\d.]+)px\)/.exec(i.style.clipPath)[1]));
    assert.deepEqual((await shown()).map((i) => i.file), expectedFiles(0).slice(0, 2));
    const before = await clip();
    const d = await page.locator('#panes .divider').boundingBox();
    await page.mouse.move(d.x + 1, d.y + d.height / 2);
    await page.mouse.down();
    await page.mouse.move(d.x - 100, d.y + d.height / 2, { steps: 4 });
    await page.mouse.up();
    assert.ok((await clip()) < before, `${before} -> ${await clip()}`);
    await page.keyboard.press('s');
    await panesLoaded();
    assert.equal((await shown()).length, 3);
  });

  await check("selecting the FLIP map shows the map's file with its legend", async () => {
    await page.selectOption('#panes .overlay[data-pane="1"] select.layer', 'flip');
    await panesLoaded();
    const img = (await shown())[1];
    const run = runAt(0, variants[0]);
    assert.equal(img.file, run.maps.flip.file);
    assert.match(img.file, /maps\/.*\/flip\.png$/);
    assert.equal(decodeURIComponent(new URL(img.src).pathname), path.join(reportDir, run.maps.flip.file));
    assert.ok(fs.existsSync(path.join(reportDir, img.file)));
    assert.equal(img.width, 64);
    assert.equal(await page.locator('#panes .overlay[data-pane="1"] .legend').count(), 1);
    // The inspector reads the FLIP value back from the map's colour.
    const box = await viewport(1).boundingBox();
    await page.mouse.move(box.x + box.width * 0.5, box.y + box.height * 0.5);
    await page.waitForFunction(() => /flip \d/.test(document.querySelector('#panes .overlay[data-pane="1"] .inspector').textContent));
  });

  await check("selecting the HDR-FLIP map shows its own file beside FLIP's, with its legend", async () => {
    await page.selectOption('#panes .overlay[data-pane="1"] select.layer', 'flip_hdr');
    await panesLoaded();
    const img = (await shown())[1];
    const run = runAt(0, variants[0]);
    assert.equal(img.file, run.maps.flip_hdr.file);
    assert.match(img.file, /maps\/.*\/flip_hdr\.png$/);
    assert.notEqual(img.file, run.maps.flip.file);
    assert.ok(fs.existsSync(path.join(reportDir, img.file)));
    assert.equal(img.width, 64);
    assert.equal(await page.locator('#panes .overlay[data-pane="1"] .legend').count(), 1);
    const names = await page.$$eval('#panes .overlay[data-pane="1"] select.layer option', (os) => os.map((o) => o.textContent));
    assert.ok(names.includes('FLIP (LDR) map') && names.includes('HDR-FLIP map'), names.join(', '));
    const box = await viewport(1).boundingBox();
    await page.mouse.move(box.x + box.width * 0.5, box.y + box.height * 0.5);
    await page.waitForFunction(() => /flip_hdr \d/.test(document.querySelector('#panes .overlay[data-pane="1"] .inspector').textContent));
  });

  await check('the debug images are listed and shown', async () => {
    const options = await page.$$eval('#panes .overlay[data-pane="1"] select.layer option', (os) => os.map((o) => o.value));
    assert.deepEqual(options, ['image', 'diff', 'ssim', 'flip', 'flip_hdr', 'debug:mask']);
    await page.selectOption('#panes .overlay[data-pane="1"] select.layer', 'debug:mask');
    await panesLoaded();
    assert.equal((await shown())[1].file, runAt(0, variants[0]).debug.mask);
    await page.selectOption('#panes .overlay[data-pane="1"] select.layer', 'image');
  });

  await check('the frame slider changes every pane to the new frame', async () => {
    await page.$eval('#frame', (s) => {
      s.value = '1';
      s.dispatchEvent(new Event('input'));
    });
    await panesLoaded();
    assert.deepEqual((await shown()).map((i) => i.file), expectedFiles(20));
    assert.notDeepEqual(expectedFiles(20), expectedFiles(0));
    await page.locator('body').click({ position: { x: 5, y: 790 } });
    await page.keyboard.press('ArrowRight');
    await panesLoaded();
    assert.deepEqual((await shown()).map((i) => i.file), expectedFiles(40));
  });

  await check('number keys pick the technique of the active pane', async () => {
    await viewport(0).click();
    await page.keyboard.press('3');
    await panesLoaded();
    assert.equal((await shown())[0].file, runAt(40, variants[1]).image);
    await page.keyboard.press('1');
    await panesLoaded();
    assert.equal((await shown())[0].file, runAt(40, variants[0]).reference);
  });

  await check('E cycles the error maps of every technique pane; ? shows the shortcuts', async () => {
    await page.keyboard.press('e');
    await panesLoaded();
    const files = (await shown()).map((i) => i.file);
    assert.deepEqual(files, [runAt(40, variants[0]).reference, ...variants.map((v) => runAt(40, v).maps.diff.file)]);
    await page.keyboard.press('?');
    assert.ok(await page.isVisible('#help'));
    assert.match(await page.textContent('#help'), /flip/);
    await page.keyboard.press('Escape');
    assert.ok(!(await page.isVisible('#help')));
    await page.keyboard.press('e');
    await page.keyboard.press('e');
    await page.keyboard.press('e');
    await panesLoaded();
    assert.deepEqual((await shown()).map((i) => i.file).slice(1), variants.map((v) => runAt(40, v).maps.flip_hdr.file));
  });

  await check('exposure changes the pixels drawn; the inspector shows linear values beside display ones', async () => {
    const mean = () =>
      page.$eval('#panes img.image[data-pane="1"]', (img) => {
        const c = document.createElement('canvas');
        c.width = img.naturalWidth;
        c.height = img.naturalHeight;
        const ctx = c.getContext('2d');
        ctx.drawImage(img, 0, 0);
        const d = ctx.getImageData(0, 0, c.width, c.height).data;
        let sum = 0;
        for (let i = 0; i < d.length; i += 4) sum += d[i] + d[i + 1] + d[i + 2];
        return sum / (d.length / 4) / 3;
      });
    const drawnAt = (ev) => page.waitForFunction((e) => [...document.querySelectorAll('#panes img.image')].every((i) => i.dataset.drawn === `ev ${e} srgb` && i.complete), ev);
    await page.locator('body').click({ position: { x: 5, y: 790 } });
    await page.keyboard.press('e'); // from the HDR-FLIP maps back to the images
    await page.waitForFunction(() => [...document.querySelectorAll('#panes img.image')].every((i) => i.dataset.layer === 'image'));
    for (let i = 0; i < 4; i += 1) await page.keyboard.press('-');
    await drawnAt(-2);
    const darker = await mean();
    for (let i = 0; i < 8; i += 1) await page.keyboard.press('+');
    await drawnAt(2);
    const brighter = await mean();
    assert.equal(await page.textContent('#ev-label'), 'EV +2.0');
    assert.ok(brighter > darker + 20, `mean display value ${darker} at EV -2, ${brighter} at EV +2`);
    const box = await viewport(1).boundingBox();
    await page.mouse.move(box.x + box.width * 0.5, box.y + box.height * 0.5);
    await page.waitForFunction(() => /RGB \d+ \d+ \d+ \| linear [\d.e+-]+ [\d.e+-]+ [\d.e+-]+$/.test(document.querySelector('#panes .overlay[data-pane="1"] .inspector').textContent));
    // The display value is the linear one times 2^EV, clipped and sRGB-encoded.
    const text = await page.textContent('#panes .overlay[data-pane="1"] .inspector');
    const [, r, , , lr] = /RGB (\d+) (\d+) (\d+) \| linear ([\d.e+-]+)/.exec(text);
    const x = Math.min(1, Math.max(0, Number(lr) * 4));
    const enc = x <= 0.0031308 ? 12.92 * x : 1.055 * x ** (1 / 2.4) - 0.055;
    assert.ok(Math.abs(Number(r) - 255 * enc) <= 1.5, text);
    for (let i = 0; i < 4; i += 1) await page.keyboard.press('-');
    await page.waitForFunction(() => [...document.querySelectorAll('#panes img.image')].every((i) => i.dataset.drawn === 'png'));
    assert.deepEqual((await shown()).map((i) => i.src.startsWith('file:')), [true, true, true]);
  });

  await check("two panes' difference maps share one scale, shown in their legends; M gives each its own", async () => {
    await page.keyboard.press('e');
    await panesLoaded();
    const highs = () => page.$$eval('#panes .legend .hi', (es) => es.map((e) => e.textContent));
    const frame = Number(await page.$eval('#frame', (s) => s.value));
    const runs = variants.map((v) => runAt(frames[frame], v));
    const shared = Math.max(...manifest.runs.map((r) => r.maps.diff.range[1]));
    assert.deepEqual(await highs(), [shared.toPrecision(3), shared.toPrecision(3)]);
    await page.waitForFunction(() => [...document.querySelectorAll('#panes img.image')].slice(1).every((i) => i.dataset.drawn === 'png' || i.dataset.drawn.startsWith('scale ')));
    await page.keyboard.press('m');
    await panesLoaded();
    assert.deepEqual(await highs(), runs.map((r) => r.maps.diff.range[1].toPrecision(3)));
    await page.keyboard.press('m');
    await page.keyboard.press('e'); // from the difference maps through SSIM, FLIP (LDR) and HDR-FLIP back to the images
    await page.keyboard.press('e');
    await page.keyboard.press('e');
    await page.keyboard.press('e');
    await panesLoaded();
    assert.deepEqual((await shown()).map((i) => i.file).slice(1), runs.map((r) => r.image));
  });

  await check('every variant can be selected from the searchable list', async () => {
    const frame = frames[Number(await page.$eval('#frame', (s) => s.value))];
    const options = await page.$$eval('#variant-list option', (os) => os.map((o) => o.value));
    assert.equal(options.length, 1 + variants.length);
    await viewport(1).click();
    for (const v of variants) {
      const label = options.find((o) => o.endsWith(`: ${v}`));
      assert.ok(label, v);
      await page.fill('#find', label);
      await page.$eval('#find', (e) => e.dispatchEvent(new Event('change')));
      await panesLoaded();
      assert.equal((await shown())[1].file, runAt(frame, v).image, v);
    }
  });

  await page.screenshot({ path: path.join(work, 'viewer.png') });

  await check("the report's table and charts open the viewer on a run", async () => {
    const report = await browser.newPage({ viewport: { width: 1400, height: 800 } });
    report.setDefaultTimeout(kWaitMs);
    report.on('pageerror', (e) => consoleErrors.push(e.message));
    await report.goto(pathToFileURL(path.join(reportDir, 'index.html')).href);
    // The verdict: rt_only at 0.01 is the only setting reaching SSIM 0.99 on this scene (max_depth = 1
    // loses the glass sphere's refraction), so the fastest reaching it.
    const fastest99 = manifest.runs.filter((r) => r.metrics.ssim >= 0.99).map((r) => r.variant);
    assert.deepEqual([...new Set(fastest99)], ['rt_only [importance_cutoff=0.01]']);
    const verdictRow = await report.$$eval('table.verdict.thresholds tr', (trs) =>
      trs.map((tr) => [...tr.cells].map((c) => c.textContent)).find((cells) => cells[0] === 'SSIM >= 0.99, whole image'));
    assert.equal(verdictRow[1], 'rt_only [importance_cutoff=0.01]');
    // Its frame time is the median of its runs' medians, its speed-up the reference's median over it.
    const median = (xs) => {
      const v = [...xs].sort((x, y) => x - y);
      return v.length % 2 ? v[(v.length - 1) / 2] : (v[v.length / 2 - 1] + v[v.length / 2]) / 2;
    };
    const rtRuns = manifest.runs.filter((r) => r.variant === 'rt_only [importance_cutoff=0.01]');
    const rtMs = median(rtRuns.map((r) => r.frame_ms));
    assert.equal(verdictRow[2], rtMs.toFixed(2));
    assert.equal(verdictRow[3], (median(manifest.runs.map((r) => r.reference_ms)) / rtMs).toFixed(2));
    assert.equal(verdictRow[4], '1.00');
    assert.match(await report.textContent('#verdict ~ p.sentence'), /SSIM 0\.99 on the whole image is rt_only \[importance_cutoff=0\.01\]/);
    // The device: named where experiment.json records it, "device not recorded" where it does not.
    const experiment = JSON.parse(fs.readFileSync(path.join(resultDir, 'experiment.json'), 'utf8'));
    const deviceText = await report.textContent('table.device');
    if (experiment.device) assert.ok(deviceText.includes(experiment.device.vulkan_device), deviceText);
    else assert.match(deviceText, /device not recorded/);
    assert.match(deviceText, /ray backend\s*embree/);
    const hrefs = await report.$$eval('table.runs a[href^="viewer.html#run="]', (as) => as.map((a) => a.getAttribute('href')));
    assert.deepEqual(hrefs.sort(), manifest.runs.map((r) => `viewer.html#run=${r.id}`).sort());
    const target = runAt(40, variants[1]);
    // The anchor's own click, and the navigation awaited from before it: a click at coordinates can
    // land beside the link while the report's figures still lay out on a loaded machine, and the
    // viewer's images are awaited below rather than through the page's load event.
    const link = `table.runs a[href="viewer.html#run=${target.id}"]`;
    await Promise.all([report.waitForURL(/viewer\.html/, { waitUntil: 'commit' }), report.$eval(link, (a) => a.click())]);
    await report.waitForFunction(() => {
      const imgs = [...document.querySelectorAll('#panes img.image')];
      return imgs.length >= 2 && imgs.every((i) => i.complete && i.naturalWidth > 0);
    });
    const files = await report.$$eval('#panes img.image', (imgs) => imgs.map((i) => i.dataset.file));
    assert.deepEqual(files.slice(0, 2), [target.reference, target.image]);
    // A path figure's points are runs; a speed-accuracy point is a setting, which opens its first run.
    const firstRun = manifest.runs.find((r) => r.variant === target.variant);
    for (const svg of fs.readdirSync(path.join(reportDir, 'figures')).filter((f) => /^(speed-accuracy|path)-.*\.svg$/.test(f))) {
      const text = fs.readFileSync(path.join(reportDir, 'figures', svg), 'utf8');
      const linked = svg.startsWith('path-') ? target : firstRun;
      assert.ok(text.includes(`target="_top" xlink:href="../viewer.html#run=${linked.id}"`), svg);
    }
    await report.close();
  });

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
    const page = fs.readFileSync(path.join(deviceReport, 'index.html'), 'utf8');
    assert.ok(page.indexOf('Test CPU 9000 (2 cores)') < page.indexOf('id="verdict"'));
    assert.match(page, /llvmpipe \(LLVM 19\.1\.7, 256 bits\) \(cpu\)/);
    assert.match(page, /class="warning">Warning: The raster ran on a software Vulkan device/);
    assert.match(fs.readFileSync(path.join(deviceReport, 'report.md'), 'utf8'), /\*\*Warning:\*\* The raster ran on a software Vulkan device/);
  });

  await check('a damaged image in the result set: exit status 2, a message naming it, no report', async () => {
    const damaged = path.join(work, 'damaged');
    fs.cpSync(resultDir, damaged, { recursive: true, filter: (f) => !f.startsWith(reportDir) });
    const exr = path.join(damaged, manifest.runs[1].exr.replace(/^\.\.\//, ''));
    fs.writeFileSync(exr, fs.readFileSync(exr).subarray(0, 1000));
    const out = path.join(work, 'damaged-report');
    const r = spawnSync(hybridlab, ['report', damaged, '--out', out], { encoding: 'utf8' });
    assert.equal(r.status, 2, r.stderr);
    assert.ok(r.stderr.includes(exr), r.stderr);
    assert.ok(!fs.existsSync(out));
  });
} finally {
  await browser.close();
}

assert.deepEqual(consoleErrors, [], 'console errors');
console.log(`screenshot: ${path.join(work, 'viewer.png')}`);
console.log(`${passed} passed, 0 failed`);
