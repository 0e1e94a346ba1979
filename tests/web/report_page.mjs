// Opens a report.html of `owsim view` from file:// in headless Chromium (Debian's, driven by the
// pinned playwright-core of web/) and checks it as a person would use it: no console errors, the
// summary and its sortable ground-truth table, the frame player's slider and play button, the
// map's zoom and furniture, the 3D view's orbit; screenshots of each panel in SHOT_DIR.
//   node tests/web/report_page.mjs REPORT.html SHOT_DIR [--expect-frames] [--expect-objects]
//        [--expect-wires] [--expect-empty] [--expect-evidence] [--expect-roc VALUES] [--expect-noise]
//        [--expect-warnings]
//        [--max-ready-ms N]
// Prints one JSON line of measurements; exits non-zero with the failed checks listed.
import { createRequire } from 'node:module';
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const require = createRequire(join(here, '..', '..', 'web', 'package.json'));
const { chromium } = require('playwright-core');
const zlib = require('node:zlib');

const [reportPath, shotDir, ...flags] = process.argv.slice(2);
const expectedNote = flags.includes('--expect-note') ? flags[flags.indexOf('--expect-note') + 1] : null;
const has = (flag) => flags.includes(flag);
const expectedRocValues = flags.includes('--expect-roc') ? Number(flags[flags.indexOf('--expect-roc') + 1]) : 0;
const maxReadyMs = flags.includes('--max-ready-ms') ? Number(flags[flags.indexOf('--max-ready-ms') + 1]) : 10000;
mkdirSync(shotDir, { recursive: true });

const failures = [];
const check = (ok, what) => { if (!ok) failures.push(what); };

// PNG → RGBA (8-bit RGB(A), non-interlaced: what Chromium's screenshots are), for pixel checks.
function decodePng(buffer) {
  let offset = 8;
  let width = 0, height = 0, channels = 0;
  const idat = [];
  while (offset < buffer.length) {
    const length = buffer.readUInt32BE(offset);
    const type = buffer.toString('ascii', offset + 4, offset + 8);
    const data = buffer.subarray(offset + 8, offset + 8 + length);
    if (type === 'IHDR') {
      width = data.readUInt32BE(0);
      height = data.readUInt32BE(4);
      channels = { 2: 3, 6: 4 }[data[9]];
    } else if (type === 'IDAT') idat.push(data);
    offset += 12 + length;
  }
  const raw = zlib.inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  const out = Buffer.alloc(width * height * 4);
  let prev = Buffer.alloc(stride);
  for (let y = 0; y < height; y++) {
    const filter = raw[y * (stride + 1)];
    const line = Buffer.from(raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1)));
    for (let i = 0; i < stride; i++) {
      const a = i >= channels ? line[i - channels] : 0;
      const b = prev[i];
      const c = i >= channels ? prev[i - channels] : 0;
      let v = line[i];
      if (filter === 1) v += a;
      else if (filter === 2) v += b;
      else if (filter === 3) v += (a + b) >> 1;
      else if (filter === 4) {
        const p = a + b - c;
        const pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
        v += pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      line[i] = v & 255;
    }
    for (let x = 0; x < width; x++) {
      for (let k = 0; k < 4; k++) out[4 * (y * width + x) + k] = k < channels ? line[x * channels + k] : 255;
    }
    prev = line;
  }
  return { width, height, rgba: out };
}

// How many distinct colours, how many pixels near `rgb` (±40 per channel) and the fraction that
// differ from the most common colour (the background).
function pixelStats(png, rgb) {
  const counts = new Map();
  let near = 0;
  for (let i = 0; i < png.rgba.length; i += 4) {
    const [r, g, b] = [png.rgba[i], png.rgba[i + 1], png.rgba[i + 2]];
    const key = (r << 16) | (g << 8) | b;
    counts.set(key, (counts.get(key) || 0) + 1);
    if (rgb && Math.abs(r - rgb[0]) < 40 && Math.abs(g - rgb[1]) < 40 && Math.abs(b - rgb[2]) < 40) near++;
  }
  const background = Math.max(...counts.values());
  const pixels = png.rgba.length / 4;
  return { colours: counts.size, near, foreground: (pixels - background) / pixels };
}

const browser = await chromium.launch({
  executablePath: process.env.OWSIM_CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
    '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run', '--disable-quic'],
});
const page = await browser.newPage({ viewport: { width: 1200, height: 900 } });
const consoleErrors = [];
const requests = [];
page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
page.on('pageerror', (e) => consoleErrors.push(String(e)));
page.on('request', (r) => { if (!r.url().startsWith('file:') && !r.url().startsWith('data:') && !r.url().startsWith('blob:')) requests.push(r.url()); });

const started = Date.now();
await page.goto(pathToFileURL(resolve(reportPath)).href);
await page.waitForSelector('body[data-ready]', { timeout: 60000 });
const readyWallMs = Date.now() - started;
const measured = await page.evaluate(() => ({
  ready: document.body.dataset.ready,
  readyMs: window.owsimReport?.readyMs,
  sinceNavigationMs: performance.now(),
}));
check(measured.ready === '1', `page ready state ${measured.ready}`);
check(readyWallMs <= maxReadyMs, `interactive after ${readyWallMs} ms > ${maxReadyMs} ms`);
const errorsInPage = await page.locator('.error').allTextContents();
check(errorsInPage.length === 0, `error messages in the page: ${errorsInPage.join(' | ')}`);

const shoot = async (selector, name) => {
  const path = join(shotDir, `${name}.png`);
  await page.locator(selector).screenshot({ path });
  return decodePng(await import('node:fs').then((fs) => fs.readFileSync(path)));
};

// 1. Summary.
const facts = await page.locator('#summary table.facts').innerText();
check(/Scenario/.test(facts) && /Sensor/.test(facts) && /Returns by class/.test(facts), 'summary facts');
if (has('--expect-objects')) {
  check(/Frames/.test(facts) && /Throughput/.test(facts), 'summary frames and throughput');
  const rows = await page.locator('#objects-table tbody tr').count();
  check(rows > 0, 'ground-truth rows');
  await page.click('#objects-table th[data-key="min_range_m"]');
  const column = async () => (await page.locator('#objects-table tbody tr td:nth-child(7)').allTextContents())
    .map((t) => (t === '—' ? Infinity : Number(t.replace(/,/g, ''))));
  const ascending = await column();
  const finite = ascending.filter(Number.isFinite);
  check(finite.length > 0 && finite.every((v, i) => i === 0 || finite[i - 1] <= v), 'closest range sorts ascending');
  await page.click('#objects-table th[data-key="min_range_m"]');
  const descending = (await column()).filter(Number.isFinite);
  check(descending.every((v, i) => i === 0 || descending[i - 1] >= v), 'closest range sorts descending');
  check(descending[0] === finite[finite.length - 1], 'sorting keeps the rows');
} else {
  check(await page.locator('#summary .ground-truth .empty').count() === 1, 'no-ground-truth message');
}
if (expectedNote) {
  const notes = await page.locator('#notes').innerText().catch(() => '');
  check(notes.includes(expectedNote), `a note saying "${expectedNote}" (notes: ${notes})`);
}
if (has('--expect-noise')) {
  // False returns (class noise): counted in the summary, in the legends, yellow cells in a frame.
  const row = await page.locator('#summary tr[data-key="false_returns"]').innerText().catch(() => '');
  check(/per pulse/.test(row) && /per second of flight/.test(row), `false returns in the summary (${row})`);
  check(/noise/.test(await page.locator('#frame-legend').innerText()), 'noise in the frame legend');
  check(/noise/.test(await page.locator('#cloud-legend').innerText()), 'noise in the 3D legend');
  const noiseFrame = await shoot('#frame-canvas', 'frame-noise');
  check(pixelStats(noiseFrame, [255, 230, 0]).near > 100, 'a frame shows false returns in yellow');
}
const summaryPng = await shoot('#summary', 'summary');
check(pixelStats(summaryPng).colours > 10, 'summary screenshot not blank');

// 1b. Detection evidence (owsim pd and owsim score wrote into the folder), or none.
if (has('--expect-evidence')) {
  const curve = await page.locator('#pd-window').getAttribute('points');
  const points = (curve ?? '').trim().split(/\s+/).filter(Boolean).length;
  check(points >= 3, `the Pd curve has points (${points})`);
  check(await page.locator('#pd-plot polygon').count() === 2, 'both curves have their bands');
  const demonstrated = await page.locator('#pd-demonstrated').innerText();
  check(/Pd ≥ 0\.995/.test(demonstrated), 'the demonstrated ranges are listed');
  const byClass = await page.locator('#score-by-class').innerText();
  check(/wire/.test(byClass) && /%/.test(byClass), `the detector's Pd by class (${byClass})`);
  check(await page.locator('#score-confusion tr').count() >= 2, 'the confusion table');
  check(pixelStats(await shoot('#evidence', 'evidence')).colours > 10, 'evidence screenshot not blank');
  if (expectedRocValues > 0) {
    check(await page.locator('#roc-plot circle.roc-point').count() === expectedRocValues,
      `one ROC point per value (${expectedRocValues})`);
    check(await page.locator('#roc-table tr').count() === expectedRocValues + 1, 'the ROC table has a row per value');
    check(/false returns per second/.test(await page.locator('#roc-plot').innerHTML()), 'the ROC axis is named');
    check(pixelStats(await shoot('#roc', 'roc')).colours > 10, 'ROC screenshot not blank');
  }
} else {
  check(await page.locator('#evidence').count() === 0, 'no evidence section without pd or score files');
}

// 2. Frame player.
let frameStats = null;
if (has('--expect-frames')) {
  const axes = await page.locator('#frame-canvas').getAttribute('aria-label');
  check(/mirror angle β \(degrees\)/.test(axes) && /fiber elevation α \(degrees\)/.test(axes) && /range \(m\)/.test(axes), `range image axes: ${axes}`);
  const label0 = await page.locator('#frame-label').innerText();
  check(/frame 0 of/.test(label0), `frame label: ${label0}`);
  const first = await shoot('#frame-canvas', 'frame-first');
  const slider = page.locator('#frame-slider');
  const max = Number(await slider.getAttribute('max'));
  // Drive the slider as a user does: focus it and press End, then back a few steps.
  await slider.focus();
  await page.keyboard.press('End');
  const labelEnd = await page.locator('#frame-label').innerText();
  check(labelEnd !== label0 && (await page.locator('#frame-canvas').getAttribute('data-frame')) !== '0', 'slider moves the frame');
  // The frame with the most wire cells, found through the slider, must show red cells.
  let best = { index: 0, red: -1 };
  for (let i = 0; i <= max; i += Math.max(1, Math.floor(max / 12))) {
    await slider.fill(String(i));
    const png = await shoot('#frame-canvas', 'frame-probe');
    const { near } = pixelStats(png, [255, 40, 40]);
    if (near > best.red) best = { index: i, red: near };
  }
  await slider.fill(String(best.index));
  const marked = await shoot('#frame-canvas', 'frame-wires');
  const stats = pixelStats(marked, [255, 40, 40]);
  if (has('--expect-wires')) check(stats.near > 0, 'a frame shows wire cells in red');
  check(pixelStats(first).colours > 20, 'range image not blank (colour ramp, axes, colour bar)');
  frameStats = { frames: max + 1, wireFrame: best.index, wirePixels: stats.near };
  await page.click('#frame-play');
  await page.waitForTimeout(700);
  await page.click('#frame-play');
  const afterPlay = Number(await slider.inputValue());
  check(afterPlay !== best.index, 'play advances the frames');
  await shoot('#frames', 'frame-player');
  check(/wire/.test(await page.locator('#frame-legend').innerText()), 'frame legend');
  if (has('--expect-warnings')) {
    // The detector's warnings of each frame under the player: some frame warns of a wire.
    let wireFrame = -1;
    for (let i = 0; i <= max && wireFrame < 0; i += Math.max(1, Math.floor(max / 12))) {
      await slider.fill(String(i));
      const text = await page.locator('#frame-warnings').innerText();
      check(/^Warnings: /.test(text), `frame warnings line: ${text}`);
      if (/\d+ wire \(track /.test(text)) wireFrame = i;
    }
    check(wireFrame >= 0, 'a frame lists a wire warning with its track');
  }
} else {
  check(await page.locator('#frames .empty').count() === 1, 'frame player says why it is empty');
}

// 3. Map.
const mapCanvas = page.locator('#map-canvas');
check(/north up/.test(await mapCanvas.getAttribute('aria-label')), 'map says north up');
const scale0 = Number(await mapCanvas.getAttribute('data-scale'));
const bar0 = Number(await mapCanvas.getAttribute('data-scale-bar'));
const map0 = await shoot('#map', 'map');
if (has('--expect-warnings')) {
  const drawn = JSON.parse((await mapCanvas.getAttribute('data-warnings')) || '{}');
  check(drawn.wire > 0 && drawn.tree > 0, `the map marks warned wires and trees (${JSON.stringify(drawn)})`);
  check(/Warnings \(detections.csv/.test(await page.locator('#map .caption').innerText()), 'the map says what its warning marks are');
}
check(pixelStats(map0, [255, 0, 255]).near > 50 || !has('--expect-objects'), 'flight path on the map');
await page.click('#map-zoom-in');
await page.click('#map-zoom-in');
const scale1 = Number(await mapCanvas.getAttribute('data-scale'));
check(Math.abs(scale1 / scale0 - 2.25) < 1e-6, `zoom in ×2.25: ${scale0} → ${scale1}`);
check(Number(await mapCanvas.getAttribute('data-scale-bar')) <= bar0, 'scale bar follows the zoom');
const box = await mapCanvas.boundingBox();
await page.mouse.move(box.x + 400, box.y + 300);
await page.mouse.down();
await page.mouse.move(box.x + 500, box.y + 350, { steps: 4 });
await page.mouse.up();
check(/E .* N .* m/.test(await page.locator('#map-cursor').innerText()), 'map cursor coordinates');
const mapZoomed = await shoot('#map-canvas', 'map-zoomed');
check(!mapZoomed.rgba.equals(map0.rgba), 'zoom and pan redraw the map');
// North arrow: dark pixels in the white box at the top right.
{
  const { width, rgba } = await shoot('#map-canvas', 'map-furniture');
  let dark = 0;
  for (let y = 20; y < 50; y++) for (let x = width - 45; x < width - 24; x++) {
    const i = 4 * (y * width + x);
    if (rgba[i] < 60 && rgba[i + 1] < 60 && rgba[i + 2] < 60) dark++;
  }
  check(dark > 40, `north arrow drawn (${dark} dark pixels)`);
}

// 4. 3D.
let cloudStats = null;
const glCanvas = page.locator('#cloud-canvas');
if (await glCanvas.count() === 1) {
  const before = await shoot('#cloud-canvas', 'cloud-before');
  const az0 = Number(await glCanvas.getAttribute('data-azimuth'));
  const gb = await glCanvas.boundingBox();
  await page.mouse.move(gb.x + gb.width / 2, gb.y + gb.height / 2);
  await page.mouse.down();
  await page.mouse.move(gb.x + gb.width / 2 + 150, gb.y + gb.height / 2, { steps: 6 });
  await page.mouse.up();
  const az1 = Number(await glCanvas.getAttribute('data-azimuth'));
  check(Math.abs(az1 - az0) > 0.1, `dragging orbits the 3D view (azimuth ${az0} → ${az1})`);
  await page.mouse.wheel(0, -400);
  const after = await shoot('#cloud-canvas', 'cloud-after');
  await page.selectOption('#cloud-colour', 'range');
  await shoot('#cloud', 'cloud-range');
  const stats = pixelStats(before);
  if (!has('--expect-empty')) check(stats.foreground > 0.05, `3D view not blank (${(100 * stats.foreground).toFixed(1)} % drawn)`);
  check(!after.rgba.equals(before.rgba) || has('--expect-empty'), 'orbit and zoom change the 3D picture');
  cloudStats = { drawnFraction: Number(stats.foreground.toFixed(3)), renders: Number(await glCanvas.getAttribute('data-renders')) };
} else {
  failures.push('no 3D canvas (WebGL unavailable?)');
}

await page.screenshot({ path: join(shotDir, 'page.png'), fullPage: true });
check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
check(requests.length === 0, `network requests: ${requests.join(' ')}`);
await browser.close();

const result = { report: reportPath, readyWallMs, readyInPageMs: Math.round(measured.readyMs), frames: frameStats, cloud: cloudStats, failures };
writeFileSync(join(shotDir, 'measurements.json'), JSON.stringify(result, null, 2));
console.log(JSON.stringify(result));
process.exit(failures.length ? 1 : 0);
